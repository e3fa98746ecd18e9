#include "input.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>

#include <epoxy/gl.h>
// GLFW after epoxy (epoxy provides the GL declarations).
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit::viewer {

void handle_drops(ViewerState& s, gl::Renderer& renderer, float aspect) {
  for (const std::string& path : s.dropped) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".gltf" || ext == ".glb") {
      const ViewerOptions previous_options = s.options;
      const Playback previous_playback = s.playback;
      try {
        s.options.scene = path;
        s.options.camera.reset();
        s.options.variant.clear();  // another file's variants and animations
        s.options.animation.clear();
        s.options.animation_time = 0.0f;
        s.playback.playing = false;
        load_scene_into(s, renderer);
        reset_orbit(s, aspect);
        s.orbit_moved = false;
        s.message.clear();
      } catch (const Error& e) {
        s.options = previous_options;
        s.playback = previous_playback;
        s.message = std::string("not loaded: ") + e.what();
      }
    } else if (ext == ".hdr" || ext == ".exr") {
      const int previous = s.env_choice;
      try {
        s.env_choices.push_back(path);
        s.env_choice = int(s.env_choices.size()) - 1;
        s.options.no_env = false;
        load_environment(s, renderer);
        s.message.clear();
      } catch (const Error& e) {
        s.env_choices.pop_back();
        s.env_choice = previous;
        load_environment(s, renderer);
        s.message = std::string("not loaded: ") + e.what();
      }
    } else {
      s.message = path + ": not a .gltf/.glb scene or an .hdr/.exr environment";
    }
    s.path_dirty = true;
  }
  s.dropped.clear();
}

void handle_mouse(ViewerState& s, const ImGuiIO& io) {
  if (io.WantCaptureMouse) return;
  const float divider_x = s.split * io.DisplaySize.x;
  if (s.mode == ViewMode::kSplit && ImGui::IsMouseClicked(ImGuiMouseButton_Left) &&
      std::fabs(io.MousePos.x - divider_x) < 8.0f)
    s.dragging_divider = true;
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) s.dragging_divider = false;
  if (s.dragging_divider) {
    if (io.DisplaySize.x > 0.0f) s.split = std::clamp(io.MousePos.x / io.DisplaySize.x, 0.0f, 1.0f);
  } else if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
    s.orbit.yaw -= io.MouseDelta.x * 0.01f;
    s.orbit.pitch = std::clamp(s.orbit.pitch + io.MouseDelta.y * 0.01f, -1.5f, 1.5f);
    s.orbit_moved = s.path_dirty = true;
  }
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
    const Camera c = s.orbit.camera();
    const glm::vec3 right(c.camera_to_world[0]), up(c.camera_to_world[1]);
    const float scale = s.orbit.distance * 0.002f;
    s.orbit.target += (-io.MouseDelta.x * right + io.MouseDelta.y * up) * scale;
    s.orbit_moved = s.path_dirty = true;
  }
  if (io.MouseWheel != 0.0f) {
    s.orbit.distance *= std::pow(0.9f, io.MouseWheel);
    s.orbit_moved = s.path_dirty = true;
  }
}

bool handle_keys(ViewerState& s, gl::Renderer& renderer, GLFWwindow* window, const ImGuiIO& io) {
  if (io.WantCaptureKeyboard) return false;
  bool screenshot = false;
  if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window, GLFW_TRUE);
  if (ImGui::IsKeyPressed(GLFW_KEY_F12) || ImGui::IsKeyPressed(GLFW_KEY_P)) screenshot = true;
  const int mode_keys[] = {GLFW_KEY_1, GLFW_KEY_2, GLFW_KEY_3, GLFW_KEY_4};
  for (int m = 0; m < 4; ++m)
    if (ImGui::IsKeyPressed(mode_keys[m])) s.mode = ViewMode(m);
  if (ImGui::IsKeyPressed(GLFW_KEY_C)) {
    // The next channel of the view shown (the raster view's debug channels, the path
    // view's features).
    if (s.mode == ViewMode::kPath) {
      s.path_channel = PathChannel((int(s.path_channel) + 1) % 4);
      s.path_display_dirty = true;
    } else if (s.mode == ViewMode::kRaster) {
      const int count = int(gl::debug_channel_names().size());
      s.channel = gl::DebugChannel((int(s.channel) + 1) % count);
    }
  }
  if (ImGui::IsKeyPressed(GLFW_KEY_D) && s.mode == ViewMode::kPath) {
    s.denoise = !s.denoise;
    s.path_display_dirty = true;
  }
  if (ImGui::IsKeyPressed(GLFW_KEY_SPACE) && s.playback.animation >= 0)
    set_playing(s, renderer, !s.playback.playing);
  if (ImGui::IsKeyPressed(GLFW_KEY_R)) {
    try {
      load_scene_into(s, renderer);
      s.message.clear();
    } catch (const Error& e) {
      s.message = std::string("reload failed: ") + e.what();
      warn("reload failed: {}", e.what());
    }
    s.path_dirty = true;
  }
  return screenshot;
}

}  // namespace pbrkit::viewer
