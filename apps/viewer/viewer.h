#pragma once
// `pbrkit view`: the interactive viewer. A GLFW window (X11) running the same Renderer as
// the headless path, with an orbit / pan / zoom camera and a Dear ImGui panel for the
// environment, exposure, tone mapper, model, compensation, IBL and lights, and live
// metallic / roughness overrides (LearnOpenGL's sphere-grid experiment). Four views of the
// same scene and camera (keys 1-4): the raster image, the path-traced truth converging on
// worker threads, a draggable split between them, and the per-pixel error of the raster
// image against the truth. Keys: F12 or P saves a screenshot (EXR + PNG), R reloads the
// scene, Esc quits; a .gltf/.glb dropped on the window loads it, an .hdr/.exr becomes the
// environment.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pbrkit/core/brdf.h"
#include "pbrkit/denoise/denoiser_choice.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/image/display.h"
#include "pbrkit/pt/path_tracer.h"

namespace pbrkit {

/// What the window shows: the OpenGL image, the path-traced one, the two split by a
/// divider (raster left), or the raster image's relative error against the path-traced one.
enum class ViewMode { kRaster, kPath, kSplit, kDifference };
ViewMode parse_view_mode(std::string_view name);  ///< raster | path | split | difference
std::string_view view_mode_name(ViewMode mode);

/// What the path view shows: the path-traced colour, or one of the film's first-hit
/// features the denoiser reads (pt/film.h): the albedo, the shading normal (as
/// n * 0.5 + 0.5) or the distance along the camera ray (displayed over the farthest).
enum class PathChannel { kColor, kAlbedo, kNormal, kDepth };
PathChannel parse_path_channel(std::string_view name);  ///< color | albedo | normal | depth
std::string_view path_channel_name(PathChannel channel);
std::vector<std::string> path_channel_names();

struct ViewerOptions {
  std::string scene = "spheres";  ///< .gltf/.glb or a built-in scene name
  std::string env;                ///< empty: the built-in default environment
  bool no_env = false;
  std::optional<int> camera;  ///< initial glTF camera
  /// A KHR_materials_variants variant by name or index (the panel switches them); empty:
  /// each primitive's own material.
  std::string variant;
  /// A glTF animation to start posed by, by name or index (the panel plays and scrubs
  /// them), at `animation_time` seconds (clamped to its keys); empty: the rest pose.
  std::string animation;
  float animation_time = 0.0f;
  /// The window asked for; every frame is rendered at the framebuffer's size, and the
  /// projection and the first view's framing take its aspect.
  int width = 1280, height = 720;
  DisplaySettings display;  ///< the initial exposure and tone mapper
  BrdfOptions brdf;         ///< the initial model and multiple-scattering compensation
  gl::Background background;
  /// MSAA samples; 0: interactive_msaa (4 on a GPU, 1 on a software rasteriser).
  int msaa = 0;
  int bake_size = gl::realtime_bake_options().face_size;
  int bake_samples = gl::realtime_bake_options().samples;
  ViewMode mode = ViewMode::kRaster;
  float split = 0.5f;  ///< the divider of the split view, as a fraction of the width
  /// The path tracer's target and seed in the path views; it renders every pixel to `spp`
  /// samples (no adaptive stopping), so a finished view equals `pbrkit render --spp N
  /// --noise-threshold 0 --seed S` of the same scene, camera and size.
  std::uint32_t spp = 1024;
  std::uint32_t seed = 0;
  /// The path views' path guiding (pt/path_tracer.h), off by default as in `render`.
  Guiding guiding = PathTracerSettings{}.guiding;
  /// The raster view's debug channel (gl/debug_channels.h): a material input or one lobe's
  /// share of the shaded colour, shown raw (no exposure, no tone mapping; the PNG is the
  /// sRGB encoding of the values, the EXR the values).
  gl::DebugChannel channel = gl::DebugChannel::kNone;
  PathChannel path_channel = PathChannel::kColor;  ///< the path view's
  /// The path view's colour denoised once the path tracer has reached `spp` (the panel's
  /// toggle); the accumulated image until then.
  bool denoise = false;
  /// Which denoiser (denoise/denoiser_choice.h): the learned one by default; its network
  /// when the caller loaded it (load_denoiser), otherwise loaded by the first denoise.
  LoadedDenoiser denoiser;
  /// Automation: once the mode's image is final (the path tracer at `spp`; the raster view
  /// after `frames` frames, at least 2), save `screenshot` and quit.
  bool exit_when_done = false;
  /// Automation (CI): render this many frames, save `screenshot`, quit (0: interactive).
  int frames = 0;
  /// A .png or .exr path: both are written, the other beside it (image/output_paths.h); also
  /// the F12 target.
  std::string screenshot;
};

/// Opens the window and runs until closed (or `frames` frames). Throws pbrkit::Error when
/// no window can be opened (e.g. no X display: run under xvfb-run), or, before opening
/// one, when `screenshot` is not a .png or .exr name.
void run_viewer(const ViewerOptions& options);

}  // namespace pbrkit
