#include "pbrkit/viewer/viewer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <epoxy/gl.h>
// GLFW after epoxy (epoxy provides the GL declarations).
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/core/color.h"
#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/util/data_dir.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

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
  // The KHR_materials extensions' factors, each an override of every material when on
  // (issue 11); applied through Renderer::set_materials when a control changes.
  struct Extensions {
    bool ior_on = false, specular_on = false, clearcoat_on = false, sheen_on = false;
    bool anisotropy_on = false, iridescence_on = false;
    float ior = 1.5f, specular = 1.0f;
    float clearcoat = 1.0f, clearcoat_roughness = 0.1f;
    glm::vec3 sheen_color{0.5f};
    float sheen_roughness = 0.5f;
    float anisotropy = 0.5f, anisotropy_rotation_deg = 0.0f;
    float iridescence = 1.0f, iridescence_thickness = 400.0f;
    // Issue 12's: transmission, volume (thickness, attenuation), dispersion, diffuse
    // transmission.
    bool transmission_on = false, volume_on = false, dispersion_on = false;
    bool diffuse_transmission_on = false;
    float transmission = 1.0f;
    float thickness = 0.5f, attenuation_distance = 1.0f;
    glm::vec3 attenuation_color{1.0f};
    float dispersion = 0.5f;
    float diffuse_transmission = 1.0f;
    glm::vec3 diffuse_transmission_color{1.0f};
  } ext;
  Orbit orbit;
};

// The scene's materials with the panel's extension overrides.
std::vector<Material> overridden_materials(const ViewerState& s) {
  std::vector<Material> materials = s.scene.materials;
  const ViewerState::Extensions& e = s.ext;
  for (Material& m : materials) {
    if (e.ior_on) m.ior = e.ior;
    if (e.specular_on) {
      if (!m.specular) m.specular.emplace();
      m.specular->factor = e.specular;
    }
    if (e.clearcoat_on) {
      if (!m.clearcoat) m.clearcoat.emplace();
      m.clearcoat->factor = e.clearcoat;
      m.clearcoat->roughness_factor = e.clearcoat_roughness;
    }
    if (e.sheen_on) {
      if (!m.sheen) m.sheen.emplace();
      m.sheen->color_factor = e.sheen_color;
      m.sheen->roughness_factor = e.sheen_roughness;
    }
    if (e.anisotropy_on) {
      if (!m.anisotropy) m.anisotropy.emplace();
      m.anisotropy->strength = e.anisotropy;
      m.anisotropy->rotation = glm::radians(e.anisotropy_rotation_deg);
    }
    if (e.iridescence_on) {
      if (!m.iridescence) m.iridescence.emplace();
      m.iridescence->factor = e.iridescence;
      m.iridescence->thickness_max = e.iridescence_thickness;
    }
    if (e.transmission_on) {
      if (!m.transmission) m.transmission.emplace();
      m.transmission->factor = e.transmission;
    }
    if (e.volume_on) {
      if (!m.volume) m.volume.emplace();
      m.volume->thickness_factor = e.thickness;
      m.volume->attenuation_distance = e.attenuation_distance;
      m.volume->attenuation_color = e.attenuation_color;
    }
    if (e.dispersion_on) {
      if (!m.dispersion) m.dispersion.emplace();
      m.dispersion->dispersion = e.dispersion;
    }
    if (e.diffuse_transmission_on) {
      if (!m.diffuse_transmission) m.diffuse_transmission.emplace();
      m.diffuse_transmission->factor = e.diffuse_transmission;
      m.diffuse_transmission->color_factor = e.diffuse_transmission_color;
    }
  }
  return materials;
}

// The extension controls; true when one changed.
bool draw_extension_controls(ViewerState& s) {
  ViewerState::Extensions& e = s.ext;
  bool changed = false;
  changed |= ImGui::Checkbox("override ior", &e.ior_on);
  if (e.ior_on) changed |= ImGui::SliderFloat("ior", &e.ior, 1.0f, 3.0f);
  changed |= ImGui::Checkbox("override specular", &e.specular_on);
  if (e.specular_on) changed |= ImGui::SliderFloat("specular", &e.specular, 0.0f, 1.0f);
  changed |= ImGui::Checkbox("override clearcoat", &e.clearcoat_on);
  if (e.clearcoat_on) {
    changed |= ImGui::SliderFloat("clearcoat", &e.clearcoat, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat("clearcoat roughness", &e.clearcoat_roughness, 0.0f, 1.0f);
  }
  changed |= ImGui::Checkbox("override sheen", &e.sheen_on);
  if (e.sheen_on) {
    changed |= ImGui::ColorEdit3("sheen colour", &e.sheen_color.x);
    changed |= ImGui::SliderFloat("sheen roughness", &e.sheen_roughness, 0.0f, 1.0f);
  }
  changed |= ImGui::Checkbox("override anisotropy", &e.anisotropy_on);
  if (e.anisotropy_on) {
    changed |= ImGui::SliderFloat("anisotropy", &e.anisotropy, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat("anisotropy rotation", &e.anisotropy_rotation_deg, -180.0f,
                                  180.0f, "%.0f deg");
  }
  changed |= ImGui::Checkbox("override iridescence", &e.iridescence_on);
  if (e.iridescence_on) {
    changed |= ImGui::SliderFloat("iridescence", &e.iridescence, 0.0f, 1.0f);
    changed |=
        ImGui::SliderFloat("film thickness", &e.iridescence_thickness, 0.0f, 1200.0f, "%.0f nm");
  }
  changed |= ImGui::Checkbox("override transmission", &e.transmission_on);
  if (e.transmission_on) changed |= ImGui::SliderFloat("transmission", &e.transmission, 0.0f, 1.0f);
  changed |= ImGui::Checkbox("override volume", &e.volume_on);
  if (e.volume_on) {
    changed |= ImGui::SliderFloat("thickness", &e.thickness, 0.0f, 5.0f);
    changed |= ImGui::SliderFloat("attenuation distance", &e.attenuation_distance, 0.01f, 10.0f,
                                  "%.2f", ImGuiSliderFlags_Logarithmic);
    changed |= ImGui::ColorEdit3("attenuation colour", &e.attenuation_color.x);
  }
  changed |= ImGui::Checkbox("override dispersion", &e.dispersion_on);
  if (e.dispersion_on) changed |= ImGui::SliderFloat("dispersion", &e.dispersion, 0.0f, 5.0f);
  changed |= ImGui::Checkbox("override diffuse transmission", &e.diffuse_transmission_on);
  if (e.diffuse_transmission_on) {
    changed |= ImGui::SliderFloat("diffuse transmission", &e.diffuse_transmission, 0.0f, 1.0f);
    changed |= ImGui::ColorEdit3("diffuse transmission colour", &e.diffuse_transmission_color.x);
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
  s.scene = load_scene(s.options.scene);
  renderer.set_scene(s.scene);
  renderer.set_materials(overridden_materials(s));  // the panel's overrides survive a reload
  s.settings.light_enabled.assign(s.scene.lights.size(), true);
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

void save_screenshot(const std::string& png, const Image& frame, const ViewerState& s) {
  const std::filesystem::path parent = std::filesystem::path(png).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const std::string exr = std::filesystem::path(png).replace_extension(".exr").string();
  write_exr(exr, rgb_channels(frame), ExrPixelType::kFloat);
  write_display_png(png, frame, s.display);
  note("wrote {} and {}", png, exr);
}

void draw_panel(ViewerState& s, gl::Renderer& renderer, double cpu_ms, double gpu_ms) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(320, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("pbrkit view");
  ImGui::Text("frame %.1f ms (GPU %.1f ms)", cpu_ms, gpu_ms);
  ImGui::Text("%s", s.scene.source.c_str());
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
      }
    }
    ImGui::EndCombo();
  }
  ImGui::SliderFloat("rotation", &s.settings.env_rotation_deg, -180.0f, 180.0f, "%.0f deg");
  ImGui::SliderFloat("intensity", &s.settings.env_intensity, 0.0f, 4.0f);
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
  int model = s.settings.brdf.model == BrdfModel::kReference ? 0 : 1;
  const char* models[] = {"reference", "classic"};
  if (ImGui::Combo("model", &model, models, 2))
    s.settings.brdf.model = model == 0 ? BrdfModel::kReference : BrdfModel::kClassic;
  ImGui::Checkbox("multiple scattering", &s.settings.brdf.multiscatter);
  // Choice k is 2^k samples, up to what the context supports (the renderer clamps to it).
  const char* msaa_modes[] = {"off", "2x", "4x", "8x"};
  int msaa = 0, msaa_choices = 1;
  while (msaa < 3 && (2 << msaa) <= s.settings.msaa) ++msaa;
  while (msaa_choices < 4 && (1 << msaa_choices) <= s.max_samples) ++msaa_choices;
  if (ImGui::Combo("MSAA", &msaa, msaa_modes, msaa_choices)) s.settings.msaa = 1 << msaa;
  ImGui::Checkbox("image-based lighting", &s.settings.ibl);
  int irradiance = int(s.settings.irradiance);
  const char* irradiance_modes[] = {"SH9", "cube"};
  if (ImGui::Combo("irradiance", &irradiance, irradiance_modes, 2))
    s.settings.irradiance = gl::IrradianceMode(irradiance);
  for (std::size_t i = 0; i < s.scene.lights.size() && i < 16; ++i) {
    bool on = s.settings.light_enabled[i];
    const std::string label = "light " + std::to_string(i) + " " + s.scene.lights[i].name;
    if (ImGui::Checkbox(label.c_str(), &on)) s.settings.light_enabled[i] = on;
  }
  ImGui::Separator();
  ImGui::Checkbox("override metallic", &s.override_metallic);
  if (s.override_metallic) ImGui::SliderFloat("metallic", &s.metallic, 0.0f, 1.0f);
  ImGui::Checkbox("override roughness", &s.override_roughness);
  if (s.override_roughness) ImGui::SliderFloat("roughness", &s.roughness, 0.0f, 1.0f);
  if (draw_extension_controls(s)) renderer.set_materials(overridden_materials(s));
  ImGui::TextUnformatted("drag: orbit, right drag: pan, wheel: zoom");
  ImGui::TextUnformatted("F12/P: screenshot, R: reload, Esc: quit");
  ImGui::End();
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
  glfwSwapInterval(options.frames > 0 ? 0 : 1);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's working directory
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 450");

  {
    ViewerState s;
    s.options = options;
    s.settings.brdf = options.brdf;
    s.settings.background = options.background;
    s.settings.msaa = options.msaa;
    glGetIntegerv(GL_MAX_SAMPLES, &s.max_samples);
    if (s.settings.msaa <= 0) {
      const std::string gpu = gl::current_renderer();
      s.settings.msaa = gl::interactive_msaa(gpu);
      if (s.settings.msaa == 1)
        note("view: MSAA off on {}, a software rasteriser (--msaa 4 or the panel turns it on)",
             gpu);
    }
    s.display = options.display;
    s.env_choices.push_back(options.env);
    // The environments pbrkit ships (data/env/), offered in the panel by name order.
    std::vector<std::string> shipped;
    for (const auto& entry : std::filesystem::directory_iterator(data_dir() / "env"))
      if (entry.path().extension() == ".exr") shipped.push_back(entry.path().string());
    std::sort(shipped.begin(), shipped.end());
    s.env_choices.insert(s.env_choices.end(), shipped.begin(), shipped.end());
    gl::Renderer renderer;
    load_scene_into(s, renderer);
    reset_orbit(s, framebuffer_aspect(window, options));
    load_environment(s, renderer);

    double cpu_ms = 0.0, gpu_ms = 0.0;
    Image frame;
    for (int frame_index = 0; !glfwWindowShouldClose(window); ++frame_index) {
      const auto t0 = Clock::now();
      glfwPollEvents();
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      ImGuiIO& io = ImGui::GetIO();

      // Camera controls (when the panel does not want the mouse).
      if (!io.WantCaptureMouse) {
        if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
          s.orbit.yaw -= io.MouseDelta.x * 0.01f;
          s.orbit.pitch = std::clamp(s.orbit.pitch + io.MouseDelta.y * 0.01f, -1.5f, 1.5f);
        }
        if (ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
          const Camera c = s.orbit.camera();
          const glm::vec3 right(c.camera_to_world[0]), up(c.camera_to_world[1]);
          const float scale = s.orbit.distance * 0.002f;
          s.orbit.target += (-io.MouseDelta.x * right + io.MouseDelta.y * up) * scale;
        }
        if (io.MouseWheel != 0.0f) s.orbit.distance *= std::pow(0.9f, io.MouseWheel);
      }
      bool screenshot = false;
      const bool last_frame = options.frames > 0 && frame_index + 1 >= options.frames;
      if (!io.WantCaptureKeyboard) {
        if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window, GLFW_TRUE);
        if (ImGui::IsKeyPressed(GLFW_KEY_F12) || ImGui::IsKeyPressed(GLFW_KEY_P)) screenshot = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_R)) {
          try {
            load_scene_into(s, renderer);
          } catch (const Error& e) {
            warn("reload failed: {}", e.what());
          }
        }
      }
      draw_panel(s, renderer, cpu_ms, gpu_ms);
      s.settings.metallic_override = s.override_metallic ? s.metallic : -1.0f;
      s.settings.roughness_override = s.override_roughness ? s.roughness : -1.0f;

      int fb_w = 0, fb_h = 0;
      glfwGetFramebufferSize(window, &fb_w, &fb_h);
      if (fb_w > 0 && fb_h > 0) {
        // At the framebuffer's size of this frame, so the projection has the window's
        // aspect, also right after a resize.
        Camera camera = s.orbit.camera();
        renderer.render(camera, fb_w, fb_h, s.settings);
        gpu_ms = renderer.latest_gpu_time_ms();
        // The display transform on the GPU, straight into the window (display.glsl, the
        // PNG outputs' code, held to it by tests/gl/display_glsl_test.cpp); the float
        // frame is read back only for a screenshot.
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        renderer.display(s.display.exposure_ev, s.display.tone_mapper);
        if (screenshot || last_frame) frame = renderer.read_back();
      }
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      glViewport(0, 0, fb_w, fb_h);
      ImGui::Render();
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

      if (screenshot && !frame.empty()) {
        const std::string path = options.screenshot.empty()
                                     ? "out/view_" + std::to_string(frame_index) + ".png"
                                     : options.screenshot;
        save_screenshot(path, frame, s);
      }
      glfwSwapBuffers(window);
      cpu_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      if (last_frame) {
        if (!options.screenshot.empty() && !frame.empty())
          save_screenshot(options.screenshot, frame, s);
        break;
      }
    }
  }  // the renderer's GL objects go before the context
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
}

}  // namespace pbrkit
