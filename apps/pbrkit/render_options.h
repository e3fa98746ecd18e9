#pragma once
// `pbrkit render`: the options both renderers share (so the two images of one scene are
// made with the same camera, environment, exposure and tone mapper), and the hooks through
// which each renderer adds its own options (cmd_render_path.cpp, cmd_render_gl.cpp).
#include <functional>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace pbrkit::cli {

struct RenderCommandOptions {
  std::string scene = "spheres";  ///< .gltf/.glb path or a built-in scene name
  std::optional<int> camera;      ///< glTF camera index
  int width = 512;
  int height = 512;
  std::string env;            ///< environment .exr/.hdr; empty = built-in default
  bool no_env = false;        ///< no environment light (black background)
  float env_rotation = 0.0f;  ///< degrees about +Y
  float env_intensity = 1.0f;
  float exposure = 0.0f;  ///< EV
  std::string tonemap = "pbr-neutral";
  std::string model = "reference";
  bool multiscatter = false;
  std::string output;  ///< PNG path; the linear EXR is written beside it (.exr)
};

/// Called once the command line is parsed; renders and writes the outputs.
using RenderRunner = std::function<void(const RenderCommandOptions&)>;

/// Each renderer adds its own options to `render` (in its own option group) and returns
/// the function that runs it.
RenderRunner add_path_render_options(CLI::App& render);
RenderRunner add_gl_render_options(CLI::App& render);

/// "out/x.png" -> "out/x.exr" (and vice versa for the PNG).
std::string replace_extension(const std::string& path, const std::string& extension);

}  // namespace pbrkit::cli
