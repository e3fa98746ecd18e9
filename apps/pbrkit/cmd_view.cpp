// pbrkit view: the interactive OpenGL viewer (GLFW + Dear ImGui) over the library's
// run_viewer. --frames/--screenshot automate it for CI (render N frames, save, quit).
#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "gl_options.h"
#include "pbrkit/core/brdf.h"
#include "pbrkit/core/color.h"
#include "pbrkit/viewer/viewer.h"

namespace pbrkit::cli {

namespace {

// The options the command line spells as names, parsed into ViewerOptions' typed values
// once CLI11 has read them. The defaults are the names of ViewerOptions' defaults.
struct ViewNames {
  std::string tonemap{tone_mapper_name(ViewerOptions{}.display.tone_mapper)};
  std::string model{brdf_model_name(ViewerOptions{}.brdf.model)};
  std::optional<bool> multiscatter;
  std::string background = "env";
};

}  // namespace

void register_view_command(CLI::App& app) {
  auto o = std::make_shared<ViewerOptions>();
  auto names = std::make_shared<ViewNames>();
  auto* cmd = app.add_subcommand(
      "view",
      "Interactive OpenGL viewer: orbit (drag), pan (right drag), zoom (wheel); a panel for "
      "environment, exposure, tone mapper, model, compensation, IBL, lights and material "
      "overrides; F12/P screenshot (PNG + EXR), R reload, Esc quit. Needs an X display.");
  cmd->add_option("scene", o->scene,
                  "a .gltf/.glb file or a built-in scene: " + builtin_scene_list())
      ->capture_default_str();
  cmd->add_option("--env", o->env, "environment map (.exr/.hdr); default: the built-in city.exr");
  cmd->add_flag("--no-env", o->no_env, "no environment light");
  cmd->add_option("--camera", o->camera, "initial glTF camera index");
  cmd->add_option("--width", o->width, "window width")
      ->check(CLI::Range(64, 8192))
      ->capture_default_str();
  cmd->add_option("--height", o->height, "window height")
      ->check(CLI::Range(64, 8192))
      ->capture_default_str();
  cmd->add_option("--exposure", o->display.exposure_ev, "exposure in EV")->capture_default_str();
  cmd->add_option("--tonemap", names->tonemap, "tone mapper")
      ->check(CLI::IsMember(tone_mapper_names()))
      ->capture_default_str();
  cmd->add_option("--model", names->model, "BRDF model: reference or classic")
      ->check(CLI::IsMember({"reference", "classic"}))
      ->capture_default_str();
  add_multiscatter_flags(*cmd, names->multiscatter,
                         "multiple-scattering compensation (default: on for reference, off for "
                         "classic)");
  cmd->add_option("--background", names->background, "env, blur:<mip> or color:<r>,<g>,<b>")
      ->capture_default_str();
  cmd->add_option("--msaa", o->msaa,
                  "MSAA samples (default: 4 on a GPU, 1 on a software rasteriser such as llvmpipe)")
      ->check(CLI::Range(1, 16));
  cmd->add_option("--frames", o->frames,
                  "automation: render this many frames, save --screenshot, and quit")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--screenshot", o->screenshot,
                  "screenshot PNG path (the linear EXR goes beside it); default out/view_<n>.png");
  cmd->callback([o, names] {
    o->display.tone_mapper = parse_tone_mapper(names->tonemap);
    o->brdf.model = parse_brdf_model(names->model);
    o->brdf.multiscatter = names->multiscatter.value_or(default_multiscatter(o->brdf.model));
    o->background = parse_background(names->background);
    run_viewer(*o);
  });
}

}  // namespace pbrkit::cli
