#include "frame_loop.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include <epoxy/gl.h>
// GLFW after epoxy (epoxy provides the GL declarations).
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "input.h"
#include "panel.h"
#include "pbrkit/image/compare.h"
#include "pbrkit/util/error.h"
#include "screenshot.h"
#include "truth_view.h"

namespace pbrkit::viewer {

namespace {

// The path tracer runs only while a truth view is shown; it restarts on any change of
// what it renders, and keeps its image across switches between the truth views. Its
// newest snapshot (or the denoised colour) becomes the path texture when what it shows
// changed.
void update_path_view(ViewerState& s, bool truth, int fb_w, int fb_h) {
  if (truth && s.path_dirty && fb_w > 0 && fb_h > 0) start_path(s, fb_w, fb_h);
  if (auto snap = s.path.latest(s.path_seen)) {
    s.path_seen = snap->serial;
    if (snap->job == s.path_job) {
      s.snapshot = std::move(*snap);
      s.path_display_dirty = true;
    }
  }
  if (s.shown_display.exposure_ev != s.display.exposure_ev ||
      s.shown_display.tone_mapper != s.display.tone_mapper || s.shown_mode != s.mode)
    s.path_display_dirty = true;
  // The denoised colour: asked for when the toggle is on and the render is final, taken
  // when the denoiser's thread has it.
  if (s.denoise && s.snapshot) s.denoiser.request(*s.snapshot, s.denoiser_choice);
  if (s.denoiser.poll()) s.path_display_dirty = true;
  if (truth && s.snapshot && s.path_display_dirty) {
    s.path_texture.upload(path_display(s));
    s.shown_display = s.display;
    s.shown_mode = s.mode;
    s.path_display_dirty = false;
  }
}

// Automation: whether frame `frame_index` is the last (the mode's image is final).
bool automation_done(const ViewerState& s, int frame_index, bool truth) {
  const ViewerOptions& options = s.options;
  if (options.exit_when_done)
    return truth ? (s.snapshot && s.snapshot->complete && frame_index + 1 >= options.frames &&
                    (!denoise_shown(s) || s.denoiser.result(s.snapshot->serial) ||
                     s.denoiser.error()))
                 : frame_index + 1 >= std::max(options.frames, 2);
  return options.frames > 0 && frame_index + 1 >= options.frames;
}

// The raster frame into the window (or a cleared window in the path view); returns the
// float frame when `read_back`, else nothing. `gpu_ms` gets the renderer's GPU time.
Image draw_raster_frame(const ViewerState& s, gl::Renderer& renderer, bool raster, int fb_w,
                        int fb_h, bool read_back, double& gpu_ms) {
  Image frame;
  if (fb_w <= 0 || fb_h <= 0) return frame;
  if (!raster) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb_w, fb_h);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    return frame;
  }
  // At the framebuffer's size of this frame, so the projection has the window's aspect,
  // also right after a resize. The debug channel in the raster view only: the split and
  // the error compare the shaded image with the truth.
  gl::RenderSettings settings = s.settings;
  settings.debug_channel = s.mode == ViewMode::kRaster ? s.channel : gl::DebugChannel::kNone;
  renderer.render(current_camera(s, fb_w, fb_h), fb_w, fb_h, settings);
  gpu_ms = renderer.latest_gpu_time_ms();
  // The display transform on the GPU, straight into the window (display.glsl, the PNG
  // outputs' code, held to it by tests/gl/display_glsl_test.cpp); the float frame is read
  // back only for a screenshot or the error view.
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const DisplaySettings shown = s.mode == ViewMode::kRaster ? raster_display(s) : s.display;
  renderer.display(shown.exposure_ev, shown.tone_mapper);
  if (read_back) frame = renderer.read_back();
  return frame;
}

// The truth views over the raster frame, behind the panel.
void draw_truth_views(const ViewerState& s, const ImGuiIO& io) {
  ImDrawList* back = ImGui::GetBackgroundDrawList();
  const ImVec2 size = io.DisplaySize;
  const auto texture = [](const DisplayTexture& t) {
    return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(t.id()));
  };
  if (s.mode == ViewMode::kPath && !s.path_texture.empty())
    back->AddImage(texture(s.path_texture), ImVec2(0, 0), size);
  if (s.mode == ViewMode::kSplit && !s.path_texture.empty()) {
    const float x = s.split * size.x;
    back->AddImage(texture(s.path_texture), ImVec2(x, 0), size, ImVec2(s.split, 0), ImVec2(1, 1));
    back->AddLine(ImVec2(x, 0), ImVec2(x, size.y), IM_COL32(255, 255, 255, 200), 2.0f);
  }
  if (s.mode == ViewMode::kDifference && !s.error_texture.empty())
    back->AddImage(texture(s.error_texture), ImVec2(0, 0), size);
}

}  // namespace

float framebuffer_aspect(GLFWwindow* window, const ViewerOptions& options) {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window, &width, &height);
  if (width <= 0 || height <= 0) return float(options.width) / float(options.height);
  return float(width) / float(height);
}

void run_frames(ViewerState& s, gl::Renderer& renderer, GLFWwindow* window) {
  const ViewerOptions& options = s.options;
  double cpu_ms = 0.0, gpu_ms = 0.0;
  int last_w = 0, last_h = 0;
  Clock::time_point previous = Clock::now();
  for (int frame_index = 0; !glfwWindowShouldClose(window); ++frame_index) {
    const auto t0 = Clock::now();
    // The animation's clock runs on the wall clock, but not across a stall (a scene
    // dropped on the window, a bake): at most a quarter second a frame.
    const double elapsed = std::min(std::chrono::duration<double>(t0 - previous).count(), 0.25);
    previous = t0;
    glfwPollEvents();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGuiIO& io = ImGui::GetIO();
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    if (!s.dropped.empty()) handle_drops(s, renderer, framebuffer_aspect(window, options));
    handle_mouse(s, io);
    const bool screenshot = handle_keys(s, renderer, window, io);
    if (draw_panel(s, renderer, cpu_ms, gpu_ms)) s.path_dirty = s.path_scene_dirty = true;
    // Playing: this frame's pose, uploaded before the raster frame draws it.
    if (s.playback.playing && advance(s.playback, elapsed)) apply_pose(s, renderer);
    s.settings.metallic_override = s.override_metallic ? s.metallic : -1.0f;
    s.settings.roughness_override = s.override_roughness ? s.roughness : -1.0f;

    const bool truth = s.mode != ViewMode::kRaster;
    const bool raster = s.mode != ViewMode::kPath;
    if (fb_w != last_w || fb_h != last_h) s.path_dirty = true;
    last_w = fb_w;
    last_h = fb_h;
    update_path_view(s, truth, fb_w, fb_h);

    const bool automation = options.frames > 0 || options.exit_when_done;
    const bool done =
        (options.exit_when_done || options.frames > 0) && automation_done(s, frame_index, truth);
    if (automation && truth && s.path.error()) fail("path tracer: {}", *s.path.error());

    // The raster frame, read back only when it is needed on the CPU.
    const bool error_due = s.mode == ViewMode::kDifference && s.snapshot && !s.snapshot->preview &&
                           (Clock::now() - s.error_time > std::chrono::milliseconds(200) || done);
    const Image frame =
        draw_raster_frame(s, renderer, raster, fb_w, fb_h, screenshot || done || error_due, gpu_ms);
    if (error_due && !frame.empty() && frame.width == s.snapshot->color.width &&
        frame.height == s.snapshot->color.height) {
      s.error = luminance_error(frame, s.snapshot->color);
      s.error_texture.upload(error_heatmap(s.error.error, 0.5f));
      s.error_time = Clock::now();
    }
    draw_truth_views(s, io);

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb_w, fb_h);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    if ((screenshot || (done && !options.screenshot.empty())) && fb_w > 0 && fb_h > 0)
      save_view(s,
                !options.screenshot.empty() ? options.screenshot
                                            : "out/view_" + std::to_string(frame_index) + ".png",
                frame, fb_w);
    glfwSwapBuffers(window);
    cpu_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (done) break;
    // While the path tracer works and nothing else moves, draw at most ~30 frames a
    // second: it has the other cores, and the window needs no more.
    if (truth && !automation) std::this_thread::sleep_for(std::chrono::milliseconds(15));
  }
}

}  // namespace pbrkit::viewer
