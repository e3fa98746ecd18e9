// pbrkit view: the interactive OpenGL viewer (GLFW + Dear ImGui) over the library's
// run_viewer. --frames/--screenshot automate it for CI (render N frames, save, quit).
#include <algorithm>
#include <memory>
#include <optional>
#include <string>

#include <fmt/ranges.h>

#include "commands.h"
#include "denoising.h"
#include "gl_options.h"
#include "pbrkit/core/brdf.h"
#include "pbrkit/core/color.h"
#include "pbrkit/image/output_paths.h"
#include "pbrkit/util/error.h"
#include "viewer/viewer.h"

namespace pbrkit::cli {

namespace {

// The options the command line spells as names, parsed into ViewerOptions' typed values
// once CLI11 has read them. The defaults are the names of ViewerOptions' defaults.
struct ViewNames {
  std::string tonemap{tone_mapper_name(ViewerOptions{}.display.tone_mapper)};
  std::string model{brdf_model_name(ViewerOptions{}.brdf.model)};
  std::optional<bool> multiscatter;
  std::string background = "env";
  std::string mode{view_mode_name(ViewerOptions{}.mode)};
  std::optional<std::string> channel;
  std::string guiding{guiding_name(ViewerOptions{}.guiding)};
  DenoiserFlags denoiser;
};

// --channel: a debug channel of the raster view, or a feature of the path view.
void parse_channel(const std::string& name, ViewerOptions& o) {
  if (o.mode == ViewMode::kPath) {
    const auto names = path_channel_names();
    if (std::find(names.begin(), names.end(), name) == names.end())
      fail("--channel: the path view shows color, albedo, normal or depth, got '{}'", name);
    o.path_channel = parse_path_channel(name);
    return;
  }
  if (o.mode != ViewMode::kRaster)
    fail("--channel: only the raster and path views show channels (--mode {})",
         view_mode_name(o.mode));
  const auto names = gl::debug_channel_names();
  if (std::find(names.begin(), names.end(), name) == names.end())
    fail("--channel: the raster view shows {}, got '{}'", fmt::join(names, ", "), name);
  o.channel = gl::parse_debug_channel(name);
}

}  // namespace

void register_view_command(CLI::App& app) {
  auto o = std::make_shared<ViewerOptions>();
  auto names = std::make_shared<ViewNames>();
  auto* cmd = app.add_subcommand(
      "view",
      "Interactive viewer: the OpenGL image and the path-traced truth of the same view (keys "
      "1-4: raster, path, split, difference); orbit (drag), pan (right drag), zoom (wheel); a "
      "panel for environment, exposure, tone mapper, model, compensation, IBL, lights and "
      "material overrides; F12/P screenshot (PNG + EXR), R reload, Space play / pause an "
      "animation, Esc quit; drop a "
      ".gltf/.glb or .hdr/.exr on the window. Needs an X display (xvfb-run for scripts).");
  cmd->add_option("scene", o->scene,
                  "a .gltf/.glb file or a built-in scene: " + builtin_scene_list())
      ->capture_default_str();
  cmd->add_option("--env", o->env, "environment map (.exr/.hdr); default: the built-in city.exr");
  cmd->add_flag("--no-env", o->no_env, "no environment light");
  cmd->add_option("--camera", o->camera, "initial glTF camera index");
  cmd->add_option("--variant", o->variant,
                  "initial material variant (KHR_materials_variants), by name or index; the "
                  "panel switches them");
  auto* animation = cmd->add_option(
      "--animation", o->animation,
      "start posed by this glTF animation, by name or index (`pbrkit info` lists them); the "
      "panel's Animation section plays and scrubs them");
  cmd->add_option("--animation-time", o->animation_time,
                  "the time in the animation, in seconds (clamped to its keys)")
      ->needs(animation)
      ->capture_default_str();
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
      ->check(CLI::IsMember(brdf_model_names()))
      ->capture_default_str();
  add_multiscatter_flags(*cmd, names->multiscatter,
                         "multiple-scattering compensation (default: on for reference, off for "
                         "classic)");
  cmd->add_option("--background", names->background, "env, blur:<mip> or color:<r>,<g>,<b>")
      ->capture_default_str();
  cmd->add_option("--msaa", o->msaa,
                  "MSAA samples (default: 4 on a GPU, 1 on a software rasteriser such as llvmpipe)")
      ->check(CLI::Range(1, 16));
  cmd->add_option("--mode", names->mode,
                  "raster (OpenGL), path (the path tracer converging), split (raster left, path "
                  "right of a draggable divider) or difference (the raster image's relative "
                  "luminance error against the path-traced one)")
      ->check(CLI::IsMember({"raster", "path", "split", "difference"}))
      ->capture_default_str();
  cmd->add_option("--split", o->split, "the split view's divider, a fraction of the width")
      ->check(CLI::Range(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--spp", o->spp,
                  "path views: samples per pixel the path tracer renders every pixel to (as "
                  "'pbrkit render --spp N --noise-threshold 0')")
      ->check(CLI::Range(1u, 1u << 24))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "path views: the path tracer's seed")->capture_default_str();
  cmd->add_option("--guiding", names->guiding,
                  "path views: path guiding, as 'pbrkit render --guiding' (the panel's toggle)")
      ->check(CLI::IsMember({"off", "on"}))
      ->capture_default_str();
  cmd->add_option("--channel", names->channel,
                  "raster view: a debug channel, raw (base-color, metallic, roughness, normal, "
                  "occlusion, emissive; the lobes diffuse, specular, clearcoat, sheen, "
                  "transmission); path view: color, albedo, normal or depth");
  cmd->add_flag("--denoise", o->denoise,
                "path view: denoise the image once the path tracer reaches --spp (the panel's "
                "toggle, key D)");
  add_denoiser_options(*cmd, &names->denoiser);
  cmd->add_flag("--exit", o->exit_when_done,
                "automation: once the view is final (the path tracer at --spp; raster: after "
                "--frames, at least 2), save --screenshot and quit");
  cmd->add_option("--frames", o->frames,
                  "automation: render this many frames, save --screenshot, and quit")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--screenshot", o->screenshot,
                  "screenshot .png or .exr; both are written, the other beside it with the same "
                  "name (default out/view_<n>.png)");
  cmd->callback([o, names] {
    o->display.tone_mapper = parse_tone_mapper(names->tonemap);
    o->brdf.model = parse_brdf_model(names->model);
    o->brdf.multiscatter = names->multiscatter.value_or(default_multiscatter(o->brdf.model));
    o->background = parse_background(names->background);
    o->mode = parse_view_mode(names->mode);
    o->guiding = parse_guiding(names->guiding);
    if (names->channel) parse_channel(*names->channel, *o);
    // A bad name is refused by its flag's name before a window opens.
    if (!o->screenshot.empty()) image_output_paths(o->screenshot, "--screenshot");
    // With --denoise the weights are loaded before the window opens (a bad file is an
    // error here); without it, they are loaded when the toggle is turned on, and a bad file
    // is reported in the panel.
    o->denoiser =
        o->denoise ? names->denoiser.load() : LoadedDenoiser{names->denoiser.choice(), {}};
    run_viewer(*o);
  });
}

}  // namespace pbrkit::cli
