#include "pbrkit/viewer/viewer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <epoxy/gl.h>
// GLFW after epoxy (epoxy provides the GL declarations).
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <glm/gtc/matrix_transform.hpp>

#include "path_view.h"
#include "pbrkit/core/color.h"
#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/image/compare.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/pt/progressive_render.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/util/data_dir.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "truth_view.h"

namespace pbrkit {

namespace {

using Clock = std::chrono::steady_clock;

// Orbit camera around `target`: yaw about +Y, pitch above the horizon, distance. It keeps
// a vertical field of view only: each frame's projection takes the aspect of the window's
// framebuffer at that frame (Renderer::render), so a resized window shows more or less of
// the scene sideways, never a stretched one.
struct Orbit {
  glm::vec3 target{0.0f};
  float yaw = 0.0f, pitch = 0.35f, distance = 5.0f;
  float yfov = 0.7854f;

  static Orbit from_camera(const Camera& c, const Bounds& bounds) {
    Orbit o;
    // The target on the camera's line of sight, as deep as the scene's centre, so that the
    // first view is the camera's own (a glTF camera need not look at the centre).
    const glm::vec3 centre = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    const float depth = std::max(glm::dot(centre - c.position(), c.forward()), 1e-3f);
    o.target = c.position() + depth * c.forward();
    const glm::vec3 d = c.position() - o.target;
    o.distance = std::max(glm::length(d), 1e-3f);
    o.pitch = std::asin(std::clamp(d.y / o.distance, -1.0f, 1.0f));
    o.yaw = std::atan2(d.x, d.z);
    if (c.type == Camera::Type::kPerspective) o.yfov = c.yfov;
    return o;
  }
  Camera camera() const {
    Camera c;
    c.name = "viewer";
    c.yfov = yfov;  // no aspect_ratio: the framebuffer's, frame by frame
    c.znear = std::max(1e-3f * distance, 1e-4f);
    const glm::vec3 eye =
        target + distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                      std::cos(pitch) * std::cos(yaw));
    c.camera_to_world = glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
    return c;
  }
};

// The override panel's state of one extension of the material schema: whether it overrides
// every material, and its factors' components in the schema's order.
struct ExtensionOverride {
  bool on = false;
  std::vector<float> values;
};

// Every extension off, each factor at its control's start value.
std::vector<ExtensionOverride> extension_overrides() {
  std::vector<ExtensionOverride> out;
  for (const MaterialExtension& x : material_schema()) {
    ExtensionOverride& o = out.emplace_back();
    for (const MaterialFactor& f : x.factors)
      o.values.insert(o.values.end(), f.components, f.control.start);
  }
  return out;
}

struct ViewerState {
  ViewerOptions options;
  Scene scene;
  std::optional<Environment> env;
  std::optional<gl::IblMaps> ibl;
  std::vector<std::string> env_choices;  // "" = the built-in default
  int env_choice = 0;
  gl::RenderSettings settings;
  GLint max_samples = 1;  // GL_MAX_SAMPLES of the window's context
  DisplaySettings display;
  bool override_metallic = false, override_roughness = false;
  float metallic = 1.0f, roughness = 0.5f;
  // The KHR_materials extensions' factors (material_schema() order), each extension an
  // override of every material when on; applied through Renderer::set_materials when a
  // control changes.
  std::vector<ExtensionOverride> ext = extension_overrides();
  Orbit orbit;
  // Until the user moves the camera the view is exactly the one `pbrkit render` takes
  // (select_view at the framebuffer's size), so that screenshots equal renders.
  bool orbit_moved = false;

  // The truth modes.
  ViewMode mode = ViewMode::kRaster;
  float split = 0.5f;
  bool dragging_divider = false;
  ProgressiveRender path;
  bool path_dirty = true;  // a change the path-traced image must restart for
  // The scene the path tracer renders, rebuilt only when what it holds changes (not when
  // the camera moves: a copy of a large scene per drag event would stall the window).
  std::shared_ptr<const Scene> path_scene;
  bool path_scene_dirty = true;
  std::uint64_t path_job = 0, path_seen = 0;
  std::optional<ProgressiveSnapshot> snapshot;  // the newest of the current job
  PathChannel path_channel = PathChannel::kColor;
  gl::DebugChannel channel = gl::DebugChannel::kNone;  // the raster view's
  bool denoise = false;  // the path view's colour denoised once complete
  PathDenoiser denoiser;
  DisplayTexture path_texture, error_texture;
  bool path_display_dirty = false;
  DisplaySettings shown_display;  // what path_texture was made with
  ViewMode shown_mode = ViewMode::kRaster;
  ErrorView error;
  Clock::time_point error_time{};
  std::vector<std::string> dropped;  // files dropped on the window, handled next frame
  std::string message;               // the last problem with a dropped file or a reload
};

// The scene's materials with the panel's extension overrides: an extension turned on is
// added where a material lacks it and its factors set to the panel's.
std::vector<Material> overridden_materials(const ViewerState& s) {
  std::vector<Material> materials = s.scene.materials;
  const auto schema = material_schema();
  for (Material& m : materials)
    for (std::size_t i = 0; i < schema.size(); ++i) {
      const MaterialExtension& x = schema[i];
      if (!s.ext[i].on) continue;
      if (!x.present(m)) x.add(m);
      const float* v = s.ext[i].values.data();
      for (const MaterialFactor& f : x.factors) {
        std::copy(v, v + f.components, f.values(m));
        v += f.components;
      }
    }
  return materials;
}

// The extension controls, one checkbox per extension with factors and a slider (a colour
// picker for a colour) per factor, from the material schema; true when one changed.
bool draw_extension_controls(ViewerState& s) {
  bool changed = false;
  const auto schema = material_schema();
  for (std::size_t i = 0; i < schema.size(); ++i) {
    const MaterialExtension& x = schema[i];
    ExtensionOverride& o = s.ext[i];
    if (x.factors.empty()) continue;  // KHR_materials_unlit: a shading mode, not a value
    changed |= ImGui::Checkbox(fmt::format("override {}", x.summary).c_str(), &o.on);
    if (!o.on) continue;
    float* v = o.values.data();
    for (const MaterialFactor& f : x.factors) {
      const FactorControl& c = f.control;
      if (f.components == 3)
        changed |= ImGui::ColorEdit3(f.json_name, v);
      else
        changed |= ImGui::SliderFloat(f.json_name, v, c.min, c.max, "%.3g",
                                      c.logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
      v += f.components;
    }
  }
  return changed;
}

void load_environment(ViewerState& s, gl::Renderer& renderer) {
  s.env.reset();
  s.ibl.reset();
  if (!s.options.no_env) {
    s.env = load_environment_or_default(s.env_choices[std::size_t(s.env_choice)], 0.0f, 1.0f);
    const BakeOptions bake = gl::realtime_bake_options(s.options.bake_size, s.options.bake_samples);
    s.ibl = gl::ibl_maps_from_bake(bake_environment(*s.env, bake), *s.env);
  }
  renderer.set_environment(s.env ? &*s.env : nullptr);
  renderer.set_ibl(s.ibl ? &*s.ibl : nullptr);
}

void load_scene_into(ViewerState& s, gl::Renderer& renderer) {
  Scene scene = load_scene(s.options.scene);
  renderer.set_scene(scene);  // a scene too large is refused here, the previous one kept
  s.scene = std::move(scene);
  renderer.set_materials(overridden_materials(s));  // the panel's overrides survive a reload
  s.settings.light_enabled.assign(s.scene.lights.size(), true);
  s.path_scene_dirty = true;
}

// The window's framebuffer aspect, width / height: what the frames are rendered at, which
// need not be the size asked for (a window manager may place the window at another size).
// The size asked for while the window has no area (minimised).
float framebuffer_aspect(GLFWwindow* window, const ViewerOptions& options) {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window, &width, &height);
  if (width <= 0 || height <= 0) return float(options.width) / float(options.height);
  return float(width) / float(height);
}

// The initial view: the chosen glTF camera's, or the automatic framing, which fits the
// scene into the narrower of the two fields of view of a frame of `aspect`.
void reset_orbit(ViewerState& s, float aspect) {
  s.orbit =
      Orbit::from_camera(select_camera(s.scene, s.options.camera, aspect), s.scene.world_bounds());
}

// The camera of this frame: the exact initial view until the user moves it, the orbit after.
Camera current_camera(const ViewerState& s, int width, int height) {
  if (!s.orbit_moved) return select_view(s.scene, s.options.camera, width, height).camera;
  return s.orbit.camera();
}

// Writes `linear` as a float EXR and, through the display transform, a PNG (or, for the
// error view, `display` as is).
void save_screenshot(const std::string& png, const Image& linear, const DisplaySettings& settings,
                     const Image* display = nullptr) {
  const std::filesystem::path parent = std::filesystem::path(png).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const std::string exr = std::filesystem::path(png).replace_extension(".exr").string();
  write_exr(exr, linear.channels == 1 ? linear : rgb_channels(linear), ExrPixelType::kFloat);
  if (display)
    write_png(png, *display);
  else
    write_display_png(png, linear, settings);
  note("wrote {} and {}", png, exr);
}

// The scene the path tracer renders: the panel's material overrides applied to the
// materials (metallic and roughness replace the factor and the texture's value, as the
// raster shader's overrides do) and the lights the panel turned off left out.
std::shared_ptr<const Scene> make_path_scene(const ViewerState& s) {
  auto scene = std::make_shared<Scene>(s.scene);
  scene->materials = overridden_materials(s);
  for (Material& m : scene->materials) {
    if (s.override_metallic || s.override_roughness) m.metallic_roughness_texture = {};
    if (s.override_metallic) m.metallic_factor = s.metallic;
    if (s.override_roughness) m.roughness_factor = s.roughness;
  }
  scene->lights.clear();
  for (std::size_t i = 0; i < s.scene.lights.size(); ++i)
    if (i >= s.settings.light_enabled.size() || s.settings.light_enabled[i])
      scene->lights.push_back(s.scene.lights[i]);
  return scene;
}

// Starts the path tracer on this frame's scene, camera, size and options: every pixel to
// options.spp samples, on all cores but one (the window draws on it).
void start_path(ViewerState& s, int width, int height) {
  ProgressiveJob job;
  if (!s.path_scene || s.path_scene_dirty) {
    s.path_scene = make_path_scene(s);
    s.path_scene_dirty = false;
  }
  job.scene = s.path_scene;
  if (s.env) {
    auto env = std::make_shared<Environment>(*s.env);
    env->rotation_deg = s.settings.env_rotation_deg;
    env->intensity = s.settings.env_intensity;
    job.env = std::move(env);
  }
  job.camera = current_camera(s, width, height);
  PathTracerSettings& p = job.settings;
  p.width = width;
  p.height = height;
  p.spp = s.options.spp;
  p.min_spp = 1;
  p.noise_threshold = 0.0f;
  p.seed = s.options.seed;
  p.brdf = s.settings.brdf;
  p.threads = std::max(1, int(std::thread::hardware_concurrency()) - 1);
  p.checkpoint_interval = 0.1;
  s.path_job = s.path.start(std::move(job));
  s.snapshot.reset();
  s.path_dirty = false;
}

// The channel the path texture shows: the panel's in the path view; the split and the
// error compare colours.
PathChannel shown_path_channel(const ViewerState& s) {
  if (s.mode != ViewMode::kPath || s.snapshot->preview) return PathChannel::kColor;
  return s.path_channel;
}

// The path view's linear image: the chosen channel, or the denoised colour when the
// toggle is on and the denoiser has finished this snapshot.
Image path_linear(const ViewerState& s) {
  const ProgressiveSnapshot& snap = *s.snapshot;
  if (s.denoise && s.mode == ViewMode::kPath && s.path_channel == PathChannel::kColor)
    if (const Image* denoised = s.denoiser.result(snap.serial)) return *denoised;
  return path_channel_image(snap, shown_path_channel(s));
}

// The path view's image, display-referred.
Image path_display(const ViewerState& s) {
  return path_channel_display(path_linear(s), shown_path_channel(s), s.display);
}

// The display transform of the raster view: the panel's, or none for a debug channel
// (its values are shown raw).
DisplaySettings raster_display(const ViewerState& s) {
  if (s.channel != gl::DebugChannel::kNone) return {0.0f, ToneMapper::kNone};
  return s.display;
}

// Whether the path view shows the denoised colour (once it exists).
bool denoise_shown(const ViewerState& s) {
  return s.denoise && s.path_channel == PathChannel::kColor;
}

// A combo over `names`; true when the choice changed.
bool name_combo(const char* label, int& choice, const std::vector<std::string>& names) {
  const auto getter = [](void* data, int i, const char** out) {
    *out = static_cast<const std::vector<std::string>*>(data)->at(std::size_t(i)).c_str();
    return true;
  };
  return ImGui::Combo(label, &choice, getter, const_cast<std::vector<std::string>*>(&names),
                      int(names.size()));
}

// The error view's colour bar: the viridis ramp from 0 to `scale` (and above).
void draw_colour_bar(float scale) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float w = ImGui::GetContentRegionAvail().x, h = 12.0f;
  const int steps = 32;
  for (int i = 0; i < steps; ++i) {
    const glm::vec3 c = viridis((float(i) + 0.5f) / float(steps));
    draw->AddRectFilled(ImVec2(p.x + w * float(i) / steps, p.y),
                        ImVec2(p.x + w * float(i + 1) / steps, p.y + h),
                        ImGui::GetColorU32(ImVec4(c.r, c.g, c.b, 1.0f)));
  }
  ImGui::Dummy(ImVec2(w, h));
  ImGui::Text("0%%%*s%.0f%%+", int(w / ImGui::CalcTextSize(" ").x) - 8, "", 100.0f * scale);
}

// The truth modes' part of the panel: the mode, the path tracer's progress, the error.
// Returns true when the path-traced image must restart.
bool draw_truth_panel(ViewerState& s) {
  bool changed = false;
  int mode = int(s.mode);
  const char* modes[] = {"1 raster", "2 path", "3 split", "4 difference"};
  if (ImGui::Combo("view", &mode, modes, 4)) s.mode = ViewMode(mode);
  if (s.mode == ViewMode::kRaster) {
    static const std::vector<std::string> names = gl::debug_channel_names();
    int channel = int(s.channel);
    if (name_combo("channel (C)", channel, names)) s.channel = gl::DebugChannel(channel);
    if (s.channel != gl::DebugChannel::kNone)
      ImGui::TextUnformatted("raw values: no exposure, no tone map");
    return false;
  }
  if (s.snapshot) {
    const ProgressiveSnapshot& p = *s.snapshot;
    ImGui::Text("path: %.1f / %u spp, %.1f s, noise %.4f%s", p.spp, s.options.spp, p.seconds,
                p.noise,
                p.complete  ? " (done)"
                : p.preview ? " (preview)"
                            : "");
  } else {
    ImGui::TextUnformatted("path: starting");
  }
  if (const auto error = s.path.error()) ImGui::TextWrapped("path tracer: %s", error->c_str());
  if (s.mode == ViewMode::kPath) {
    static const std::vector<std::string> names = path_channel_names();
    int channel = int(s.path_channel);
    if (name_combo("channel (C)", channel, names)) {
      s.path_channel = PathChannel(channel);
      s.path_display_dirty = true;
    }
    if (s.path_channel == PathChannel::kColor) {
      if (ImGui::Checkbox("denoise (D)", &s.denoise)) s.path_display_dirty = true;
      if (s.denoise) {
        const bool shown = s.snapshot && s.denoiser.result(s.snapshot->serial);
        ImGui::TextUnformatted(shown                                ? "showing the denoised image"
                               : s.denoiser.busy()                  ? "denoising..."
                               : s.snapshot && s.snapshot->complete ? "denoise failed"
                                                                    : "denoises at the target spp");
        if (const auto& error = s.denoiser.error()) ImGui::TextWrapped("%s", error->c_str());
      }
    }
  }
  if (s.mode == ViewMode::kSplit) ImGui::SliderFloat("split", &s.split, 0.0f, 1.0f);
  if (s.mode == ViewMode::kDifference) {
    ImGui::Text("relative luminance error: mean %.1f%%, 95th pct %.1f%%", 100.0 * s.error.mean,
                100.0 * s.error.p95);
    ImGui::Text("(against a path-traced image of noise %.4f)",
                s.snapshot ? s.snapshot->noise : 0.0);
    draw_colour_bar(0.5f);
  }
  int spp = int(s.options.spp);
  if (ImGui::InputInt("target spp", &spp, 64, 1024) && spp >= 1) {
    s.options.spp = std::uint32_t(spp);
    changed = true;
  }
  return changed;
}

// The panel; returns true when something the path-traced image depends on changed.
bool draw_panel(ViewerState& s, gl::Renderer& renderer, double cpu_ms, double gpu_ms) {
  bool changed = false;
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("pbrkit view");
  ImGui::Text("frame %.1f ms (GPU %.1f ms)", cpu_ms, gpu_ms);
  ImGui::Text("%s", s.scene.source.c_str());
  if (!s.message.empty()) ImGui::TextWrapped("%s", s.message.c_str());
  changed |= draw_truth_panel(s);
  ImGui::Separator();
  if (!s.options.no_env &&
      ImGui::BeginCombo("environment",
                        s.env_choices[std::size_t(s.env_choice)].empty()
                            ? "default"
                            : std::filesystem::path(s.env_choices[std::size_t(s.env_choice)])
                                  .filename()
                                  .c_str())) {
    for (std::size_t i = 0; i < s.env_choices.size(); ++i) {
      const std::string label = s.env_choices[i].empty()
                                    ? "default"
                                    : std::filesystem::path(s.env_choices[i]).filename().string();
      if (ImGui::Selectable(label.c_str(), int(i) == s.env_choice) && int(i) != s.env_choice) {
        s.env_choice = int(i);
        load_environment(s, renderer);
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  changed |=
      ImGui::SliderFloat("rotation", &s.settings.env_rotation_deg, -180.0f, 180.0f, "%.0f deg");
  changed |= ImGui::SliderFloat("intensity", &s.settings.env_intensity, 0.0f, 4.0f);
  ImGui::SliderFloat("exposure", &s.display.exposure_ev, -6.0f, 6.0f, "%.1f EV");
  int tm = int(s.display.tone_mapper);
  static const std::vector<std::string> names = tone_mapper_names();
  const auto getter = [](void* data, int i, const char** out) {
    *out = static_cast<const std::vector<std::string>*>(data)->at(std::size_t(i)).c_str();
    return true;
  };
  if (ImGui::Combo("tone mapper", &tm, getter, const_cast<std::vector<std::string>*>(&names),
                   int(names.size())))
    s.display.tone_mapper = ToneMapper(tm);
  int model = int(s.settings.brdf.model);
  static const std::vector<std::string> model_names = brdf_model_names();
  if (ImGui::Combo("model", &model, getter, const_cast<std::vector<std::string>*>(&model_names),
                   int(model_names.size()))) {
    s.settings.brdf.model = BrdfModel(model);
    changed = true;
  }
  changed |= ImGui::Checkbox("multiple scattering", &s.settings.brdf.multiscatter);
  // Choice k is 2^k samples, up to what the context supports (the renderer clamps to it).
  const char* msaa_modes[] = {"off", "2x", "4x", "8x"};
  int msaa = 0, msaa_choices = 1;
  while (msaa < 3 && (2 << msaa) <= s.settings.msaa) ++msaa;
  while (msaa_choices < 4 && (1 << msaa_choices) <= s.max_samples) ++msaa_choices;
  if (ImGui::Combo("MSAA", &msaa, msaa_modes, msaa_choices)) s.settings.msaa = 1 << msaa;
  ImGui::Checkbox("image-based lighting", &s.settings.ibl);
  ImGui::Checkbox("glass shadows", &s.settings.transmissive_shadows);
  ImGui::Checkbox("opaque shadows", &s.settings.opaque_shadows);
  ImGui::Checkbox("glass reflections", &s.settings.transmissive_reflections);
  int irradiance = int(s.settings.irradiance);
  const char* irradiance_modes[] = {"SH9", "cube"};
  if (ImGui::Combo("irradiance", &irradiance, irradiance_modes, 2))
    s.settings.irradiance = gl::IrradianceMode(irradiance);
  // Every punctual light (the renderer shades them all, clustered), folded away when many.
  const std::size_t lights = s.scene.lights.size();
  if (lights > 0 && (lights <= 8 || ImGui::TreeNode("lights", "lights (%zu)", lights))) {
    for (std::size_t i = 0; i < lights; ++i) {
      bool on = s.settings.light_enabled[i];
      const std::string label = "light " + std::to_string(i) + " " + s.scene.lights[i].name;
      if (ImGui::Checkbox(label.c_str(), &on)) {
        s.settings.light_enabled[i] = on;
        changed = true;
      }
    }
    if (lights > 8) ImGui::TreePop();
  }
  ImGui::Separator();
  changed |= ImGui::Checkbox("override metallic", &s.override_metallic);
  if (s.override_metallic) changed |= ImGui::SliderFloat("metallic", &s.metallic, 0.0f, 1.0f);
  changed |= ImGui::Checkbox("override roughness", &s.override_roughness);
  if (s.override_roughness) changed |= ImGui::SliderFloat("roughness", &s.roughness, 0.0f, 1.0f);
  if (draw_extension_controls(s)) {
    renderer.set_materials(overridden_materials(s));
    changed = true;
  }
  ImGui::TextUnformatted("drag: orbit, right drag: pan, wheel: zoom");
  ImGui::TextUnformatted("1-4: raster, path, split, difference");
  ImGui::TextUnformatted("C: next channel, D: denoise (path)");
  ImGui::TextUnformatted("F12/P: screenshot, R: reload, Esc: quit");
  ImGui::TextUnformatted("drop a .gltf/.glb or an .hdr/.exr on the window");
  ImGui::End();
  return changed;
}

// Files dropped on the window: a scene or an environment; a bad file leaves the current
// one in place and says why in the panel.
void handle_drops(ViewerState& s, gl::Renderer& renderer, float aspect) {
  for (const std::string& path : s.dropped) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".gltf" || ext == ".glb") {
      const std::string previous = s.options.scene;
      try {
        s.options.scene = path;
        s.options.camera.reset();
        load_scene_into(s, renderer);
        reset_orbit(s, aspect);
        s.orbit_moved = false;
        s.message.clear();
      } catch (const Error& e) {
        s.options.scene = previous;
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

// An OpenGL 4.5 core window of the asked size, its context current (GLFW initialised).
GLFWwindow* create_window(const ViewerOptions& options) {
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window =
      glfwCreateWindow(options.width, options.height, "pbrkit view", nullptr, nullptr);
  if (!window)
    fail("pbrkit view: cannot create a {}x{} OpenGL 4.5 core window", options.width,
         options.height);
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.frames > 0 || options.exit_when_done ? 0 : 1);
  return window;
}

void init_imgui(GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's working directory
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 450");
}

void shutdown_imgui() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

// The state's settings from the options and the context (MSAA), and the environments
// the panel offers.
void init_state(ViewerState& s, const ViewerOptions& options) {
  s.options = options;
  s.settings.brdf = options.brdf;
  s.settings.background = options.background;
  s.settings.msaa = options.msaa;
  glGetIntegerv(GL_MAX_SAMPLES, &s.max_samples);
  if (s.settings.msaa <= 0) {
    const std::string gpu = gl::current_renderer();
    s.settings.msaa = gl::interactive_msaa(gpu);
    if (s.settings.msaa == 1)
      note("view: MSAA off on {}, a software rasteriser (--msaa 4 or the panel turns it on)", gpu);
  }
  s.display = options.display;
  s.env_choices.push_back(options.env);
  // The environments pbrkit ships (data/env/), offered in the panel by name order.
  std::vector<std::string> shipped;
  for (const auto& entry : std::filesystem::directory_iterator(data_dir() / "env"))
    if (entry.path().extension() == ".exr") shipped.push_back(entry.path().string());
  std::sort(shipped.begin(), shipped.end());
  s.env_choices.insert(s.env_choices.end(), shipped.begin(), shipped.end());
  s.mode = options.mode;
  s.channel = options.channel;
  s.path_channel = options.path_channel;
  s.denoise = options.denoise;
  s.split = std::clamp(options.split, 0.0f, 1.0f);
}

// Camera controls (when the panel does not want the mouse); in the split view a drag
// that starts on the divider moves the divider.
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

// The keys (when the panel does not want the keyboard): Esc, the view modes 1-4, C the
// next channel, D the denoiser, R reload; true when F12 or P asks for a screenshot.
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
  if (s.denoise && s.snapshot) s.denoiser.request(*s.snapshot);
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

// The view shown, saved as `path` (PNG and EXR): the raster frame, the path-traced image,
// the split of the two, or the raster image's error against the truth.
void save_view(const ViewerState& s, const std::string& path, const Image& frame, int fb_w) {
  if (s.mode == ViewMode::kRaster && !frame.empty()) {
    save_screenshot(path, frame, raster_display(s));
  } else if (s.mode == ViewMode::kPath && s.snapshot) {
    const Image linear = path_linear(s);
    const Image shown = path_display(s);
    save_screenshot(path, linear, s.display, &shown);
  } else if (s.mode == ViewMode::kSplit && s.snapshot && !frame.empty()) {
    save_screenshot(
        path, split_image(rgb_channels(frame), s.snapshot->color, split_column(s.split, fb_w)),
        s.display);
  } else if (s.mode == ViewMode::kDifference && s.snapshot && !frame.empty()) {
    const ErrorView e = luminance_error(frame, s.snapshot->color);
    const Image heat = error_heatmap(e.error, 0.5f);
    save_screenshot(path, e.error, s.display, &heat);
    note("view: relative luminance error mean {:.4f}, 95th percentile {:.4f}", e.mean, e.p95);
  }
}

// The window's frames until it closes (or automation is done).
void run_frames(ViewerState& s, gl::Renderer& renderer, GLFWwindow* window) {
  const ViewerOptions& options = s.options;
  double cpu_ms = 0.0, gpu_ms = 0.0;
  int last_w = 0, last_h = 0;
  for (int frame_index = 0; !glfwWindowShouldClose(window); ++frame_index) {
    const auto t0 = Clock::now();
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

}  // namespace

void run_viewer(const ViewerOptions& options) {
  if (!glfwInit())
    fail(
        "pbrkit view: cannot open a window (GLFW could not initialise; is there an X display? "
        "For a headless machine use xvfb-run, or 'pbrkit render --renderer gl')");
  struct GlfwGuard {
    ~GlfwGuard() { glfwTerminate(); }
  } glfw_guard;
  GLFWwindow* window = create_window(options);
  init_imgui(window);
  {
    ViewerState s;
    init_state(s, options);
    gl::Renderer renderer;
    load_scene_into(s, renderer);
    reset_orbit(s, framebuffer_aspect(window, options));
    load_environment(s, renderer);
    glfwSetWindowUserPointer(window, &s);
    glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
      auto* state = static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
      for (int i = 0; i < count; ++i) state->dropped.emplace_back(paths[i]);
    });
    run_frames(s, renderer, window);
    s.path.stop();
  }  // the renderer's GL objects go before the context
  shutdown_imgui();
  glfwDestroyWindow(window);
}

}  // namespace pbrkit
