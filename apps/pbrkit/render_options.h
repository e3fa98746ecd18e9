#pragma once
// `pbrkit render`: the options both renderers share (so the two images of one scene are
// made with the same camera, environment, exposure and tone mapper), and the hooks through
// which each renderer adds its own options (cmd_render_path.cpp, cmd_render_gl.cpp).
#include <functional>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "pbrkit/image/output_paths.h"
#include "pbrkit/scene/camera.h"

namespace pbrkit::cli {

struct RenderCommandOptions {
  std::string scene = "spheres";  ///< .gltf/.glb path or a built-in scene name
  std::optional<int> camera;      ///< glTF camera index
  std::optional<int> width;       ///< from the camera's aspect ratio when absent
  std::optional<int> height;
  std::string env;            ///< environment .exr/.hdr; empty = built-in default
  bool no_env = false;        ///< no environment light (black background)
  float env_rotation = 0.0f;  ///< degrees about +Y
  float env_intensity = 1.0f;
  float exposure = 0.0f;  ///< EV
  std::string tonemap = "pbr-neutral";
  std::string model = "reference";
  /// Multiple-scattering compensation; unset: default_multiscatter(model) (on for reference).
  std::optional<bool> multiscatter;
  /// --float / --half: the EXR's pixel type; unset: the renderer's default (half for the
  /// path tracer, float for the OpenGL renderer).
  std::optional<bool> exr_float;
  /// --variant: a KHR_materials_variants name or index; empty: each primitive's own material.
  std::string variant;
  /// --animation: a glTF animation by name or index; empty: the rest pose.
  std::string animation;
  float animation_time = 0.0f;  ///< --animation-time, seconds
  /// --frames START:END[:STEP] (frames numbered from 0 at time 0, END included) at --fps:
  /// a numbered image sequence from one scene load; empty: one image.
  std::string frames;
  float fps = 24.0f;
  /// Set on every frame of a sequence but the last: a runner may keep what the next frame
  /// reuses (the environment, the OpenGL context and its IBL bake) until then.
  bool more_frames = false;
  /// --shutter OPEN:CLOSE: motion blur over [time + OPEN, time + CLOSE] (seconds, around the
  /// pose's time); the scene is posed at the shutter's centre. Empty: no motion blur.
  std::string shutter;
  float shutter_open = 0.0f, shutter_close = 0.0f;  ///< parsed from `shutter`
  /// The time the scene is posed at: the animation time, plus the shutter's centre offset.
  float pose_time() const {
    return animation_time + (shutter.empty() ? 0.0f : 0.5f * (shutter_open + shutter_close));
  }
  std::string output;        ///< -o: a .png or .exr path (or empty: out/<scene>_<renderer>.png)
  ImageOutputPaths outputs;  ///< resolved from `output` before rendering
};

/// The --help groups of each renderer's own options. An option of one renderer given with
/// the other is an error naming it (cmd_render.cpp): a user who passes --denoise to the
/// OpenGL renderer, or --msaa to the path tracer, would otherwise get an image made without
/// it and no word.
inline constexpr const char* kPathOptionsGroup = "Path tracer (--renderer path only)";
inline constexpr const char* kGlOptionsGroup = "OpenGL renderer (--renderer gl only)";

/// Called once the command line is parsed and the scene loaded and posed; renders it and
/// writes the outputs (once per frame of a sequence, on the same scene posed anew).
using RenderRunner = std::function<void(const RenderCommandOptions&, const Scene&)>;

/// Each renderer adds its own options to `render` (in its own option group) and returns
/// the function that runs it.
RenderRunner add_path_render_options(CLI::App& render);
RenderRunner add_gl_render_options(CLI::App& render);

/// The scene of a render, loaded with a progress bar, the --variant applied, posed at
/// --animation-time of --animation (or at rest, with a note when the file animates).
Scene load_render_scene(const RenderCommandOptions& o);

/// The camera and image size of a render (scene/camera.h select_view), with a note when
/// the image's aspect differs from the one the glTF camera was authored for.
RenderView select_render_view(const Scene& scene, const RenderCommandOptions& o);

}  // namespace pbrkit::cli
