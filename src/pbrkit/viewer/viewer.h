#pragma once
// `pbrkit view`: the interactive viewer. A GLFW window (X11) running the same Renderer as
// the headless path, with an orbit / pan / zoom camera and a Dear ImGui panel for the
// environment, exposure, tone mapper, model, compensation, IBL and lights, and live
// metallic / roughness overrides (the seeds' sphere-grid experiment). Keys: F12 or P saves
// a screenshot (EXR + PNG), R reloads the scene, Esc quits.
#include <optional>
#include <string>

#include "pbrkit/core/brdf.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/image/display.h"

namespace pbrkit {

struct ViewerOptions {
  std::string scene = "spheres";  ///< .gltf/.glb or a built-in scene name
  std::string env;                ///< empty: the built-in default environment
  bool no_env = false;
  std::optional<int> camera;  ///< initial glTF camera
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
  /// Automation (CI): render this many frames, save `screenshot`, quit (0: interactive).
  int frames = 0;
  std::string screenshot;  ///< PNG path (the EXR goes beside it); also the F12 target
};

/// Opens the window and runs until closed (or `frames` frames). Throws pbrkit::Error when
/// no window can be opened (e.g. no X display: run under xvfb-run).
void run_viewer(const ViewerOptions& options);

}  // namespace pbrkit
