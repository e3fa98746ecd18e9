#pragma once
// The viewer's state, private to the viewer: the orbit camera, the panel's settings and
// overrides, the truth views' path tracer, images and textures; and what the panel, the
// input handlers, the frame loop and the screenshots share of its operations.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "path_view.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image.h"
#include "pbrkit/pt/progressive_render.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/scene.h"
#include "playback.h"
#include "truth_view.h"
#include "viewer/viewer.h"

namespace pbrkit::viewer {

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

/// Every extension off, each factor at its control's start value.
std::vector<ExtensionOverride> extension_overrides();

struct ViewerState {
  ViewerOptions options;
  Scene scene;
  std::optional<Environment> env;
  std::vector<std::string> env_choices;  // "" = the built-in default
  int env_choice = 0;
  gl::RenderSettings settings;
  int max_samples = 1;  // GL_MAX_SAMPLES of the window's context
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
  DenoiserChoice denoiser_choice;
  PathDenoiser denoiser;
  DisplayTexture path_texture, error_texture;
  bool path_display_dirty = false;
  DisplaySettings shown_display;  // what path_texture was made with
  ViewMode shown_mode = ViewMode::kRaster;
  ErrorView error;
  Clock::time_point error_time{};
  // The animation shown and its clock; the scene (and the renderer's copy) is posed at
  // its time.
  Playback playback;
  double pose_ms = 0.0;              // the last pose's cost: posing and uploading the scene
  std::vector<std::string> dropped;  // files dropped on the window, handled next frame
  std::string message;               // the last problem with a dropped file or a reload
};

/// The state's settings from the options and the context (MSAA), and the environments
/// the panel offers.
void init_state(ViewerState& s, const ViewerOptions& options);

/// The scene's materials with the panel's extension overrides: an extension turned on is
/// added where a material lacks it and its factors set to the panel's.
std::vector<Material> overridden_materials(const ViewerState& s);

/// The chosen environment (none with --no-env) and its image-based lighting, baked for the
/// raster view, into the state and the renderer.
void load_environment(ViewerState& s, gl::Renderer& renderer);

/// The options' scene into the state and the renderer, the panel's overrides applied.
void load_scene_into(ViewerState& s, gl::Renderer& renderer);

/// Switches the scene to material variant `variant` (-1: none; scene/variants.h), uploads
/// the meshes' new materials with the panel's overrides and keeps the choice for reloads.
void set_variant(ViewerState& s, gl::Renderer& renderer, int variant);

/// Poses the scene at the playback's animation and time (the rest pose for none), uploads
/// it with the panel's overrides and keeps the choice for reloads; the path view restarts
/// on the new pose unless the animation is playing (a restart every frame would never get
/// past the preview), in which case it restarts when playback stops.
void apply_pose(ViewerState& s, gl::Renderer& renderer);

/// Switches to animation `animation` (-1: the rest pose) and poses the scene at its start
/// (playing on if it was playing).
void set_animation(ViewerState& s, gl::Renderer& renderer, int animation);

/// Plays or pauses the animation (playback.h's play: from the start again after it
/// stopped at the end); paused, the path view restarts on the pose shown.
void set_playing(ViewerState& s, gl::Renderer& renderer, bool playing);

/// The initial view: the chosen glTF camera's, or the automatic framing, which fits the
/// scene into the narrower of the two fields of view of a frame of `aspect`.
void reset_orbit(ViewerState& s, float aspect);

/// The camera of this frame: the exact initial view until the user moves it, the orbit after.
Camera current_camera(const ViewerState& s, int width, int height);

/// Starts the path tracer on this frame's scene, camera, size and options: every pixel to
/// options.spp samples, on all cores but one (the window draws on it).
void start_path(ViewerState& s, int width, int height);

/// The path view's linear image: the chosen channel, or the denoised colour when the
/// toggle is on and the denoiser has finished this snapshot.
Image path_linear(const ViewerState& s);

/// The path view's image, display-referred.
Image path_display(const ViewerState& s);

/// The display transform of the raster view: the panel's, or none for a debug channel
/// (its values are shown raw).
DisplaySettings raster_display(const ViewerState& s);

/// Whether the path view shows the denoised colour (once it exists).
bool denoise_shown(const ViewerState& s);

}  // namespace pbrkit::viewer
