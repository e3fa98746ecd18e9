// pbrkit render: one command, two renderers (--renderer path|gl) over one scene, camera,
// environment and display transform.
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "commands.h"
#include "pbrkit/core/brdf.h"
#include "pbrkit/core/color.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/scene/variants.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "render_options.h"

namespace pbrkit::cli {

Scene load_render_scene(const RenderCommandOptions& o) {
  Scene scene = load_scene_showing_progress(o.scene);
  if (!o.variant.empty()) {
    try {
      apply_variant(scene, find_variant(scene, o.variant));
    } catch (const Error& e) {
      fail("--variant: {}", e.what());
    }
  }
  const std::size_t animations = scene.motion ? scene.motion->animations.size() : 0;
  if (o.animation.empty()) {
    if (animations > 0)
      note(
          "{}: {} animation(s); showing the rest pose (--animation NAME|INDEX and "
          "--animation-time SECONDS pose it; `pbrkit info` lists them)",
          scene.source, animations);
    return scene;
  }
  try {
    pose_scene(scene, {find_animation(scene, o.animation), o.pose_time()});
  } catch (const Error& e) {
    fail("--animation: {}", e.what());
  }
  return scene;
}

namespace {

struct FrameRange {
  int first = 0, last = 0, step = 1;
};

// START:END[:STEP], END included (as Blender's frame range).
FrameRange parse_frames(const std::string& text) {
  std::vector<int> parts;
  std::size_t begin = 0;
  while (true) {
    const std::size_t colon = text.find(':', begin);
    const std::string part = text.substr(begin, colon - begin);
    int value = 0;
    const auto r = std::from_chars(part.data(), part.data() + part.size(), value);
    if (part.empty() || r.ec != std::errc() || r.ptr != part.data() + part.size())
      fail("--frames {}: expected START:END or START:END:STEP (whole frame numbers)", text);
    parts.push_back(value);
    if (colon == std::string::npos) break;
    begin = colon + 1;
  }
  if (parts.size() < 2 || parts.size() > 3)
    fail("--frames {}: expected START:END or START:END:STEP (whole frame numbers)", text);
  const FrameRange r{parts[0], parts[1], parts.size() == 3 ? parts[2] : 1};
  if (r.first < 0 || r.last < r.first || r.step < 1)
    fail("--frames {}: needs 0 <= START <= END and STEP >= 1", text);
  if (r.last > 999999) fail("--frames {}: frame numbers above 999999", text);
  return r;
}

void render_frames(const RenderCommandOptions& o, const RenderRunner& run) {
  Scene scene = load_render_scene(o);
  if (o.frames.empty()) return run(o, scene);
  const FrameRange range = parse_frames(o.frames);
  if (o.animation.empty())
    fail("--frames {}: needs --animation (which animation the frames play)", o.frames);
  const int animation = find_animation(scene, o.animation);
  const int count = (range.last - range.first) / range.step + 1;
  int done = 0;
  for (int f = range.first; f <= range.last; f += range.step) {
    RenderCommandOptions frame = o;
    frame.animation_time = float(f) / o.fps;
    frame.outputs = frame_output_paths(o.outputs, f);
    frame.more_frames = f + range.step <= range.last;
    note("frame {} ({} of {}), t = {:.4g} s", f, ++done, count, frame.animation_time);
    pose_scene(scene, {animation, frame.pose_time()});
    run(frame, scene);
  }
}

}  // namespace

RenderView select_render_view(const Scene& scene, const RenderCommandOptions& o) {
  const RenderView view = select_view(scene, o.camera, o.width, o.height);
  const std::optional<float> authored = authored_aspect(view.camera);
  if (authored && std::abs(*authored / view.size.aspect() - 1.0f) > 1e-3f)
    note(
        "camera '{}' was made for an aspect ratio of {:.3f}; the {}x{} image keeps its "
        "vertical field of view and shows more or less at the sides (as three.js and Blender "
        "do)",
        view.camera.name, *authored, view.size.width, view.size.height);
  return view;
}

namespace {

// The options of the renderer not chosen that the command line gives (in the order of
// --help), e.g. "--denoise, --sample-range"; empty when there are none.
std::string other_renderers_options(CLI::App& cmd, const std::string& renderer) {
  const std::string other = renderer == "path" ? kGlOptionsGroup : kPathOptionsGroup;
  std::string names;
  for (const CLI::Option* opt : cmd.get_options())
    if (opt->count() > 0 && opt->get_group() == other)
      names += (names.empty() ? "" : ", ") + opt->get_name();
  return names;
}

}  // namespace

void register_render_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "render",
      "Render a glTF scene (or a built-in one) with the path tracer (ground truth) or the "
      "OpenGL renderer; writes a tone-mapped PNG and a linear EXR beside it. Each renderer's "
      "own options (the two groups below) are an error with the other renderer.");
  auto options = std::make_shared<RenderCommandOptions>();
  auto renderer = std::make_shared<std::string>("path");
  cmd->add_option("scene", options->scene,
                  "a .gltf/.glb file or a built-in scene: " + builtin_scene_list())
      ->capture_default_str();
  cmd->add_option("--renderer", *renderer, "path (Monte Carlo path tracer) or gl (OpenGL)")
      ->check(CLI::IsMember({"path", "gl"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", options->output,
                  "output .png or .exr (default out/<scene>_<renderer>.png); both are written, "
                  "the other beside it with the same name");
  cmd->add_option("--camera", options->camera,
                  "glTF camera index (default: the first camera, "
                  "or automatic framing when the file has none)");
  cmd->add_option("--variant", options->variant,
                  "a material variant of the file (KHR_materials_variants), by name or index "
                  "(`pbrkit info` lists them); default: none, each primitive's own material");
  auto* animation = cmd->add_option(
      "--animation", options->animation,
      "pose the scene by this glTF animation, by name or index (`pbrkit info` lists them); "
      "default: the rest pose");
  cmd->add_option("--animation-time", options->animation_time,
                  "the time in the animation, in seconds (clamped to its keys)")
      ->needs(animation)
      ->capture_default_str();
  auto* frames = cmd->add_option(
      "--frames", options->frames,
      "render frames START:END[:STEP] of --animation (END included; frame f at time f/fps) "
      "from one scene load, as a numbered sequence: <output>_0001.png/.exr, ...");
  frames->needs(animation);
  cmd->add_option("--fps", options->fps, "frames per second of --frames")
      ->needs(frames)
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--shutter", options->shutter,
                  "motion blur: the shutter is open from OPEN to CLOSE seconds around the pose's "
                  "time (--animation-time, or each frame's), e.g. -0.01:0.01; the path tracer "
                  "samples a time per path, the OpenGL renderer draws the shutter's centre")
      ->needs(animation);
  cmd->add_option("--width", options->width,
                  "image width in pixels (default: 512 along the longer side at the camera's "
                  "aspect ratio; with only --height, from the aspect ratio)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--height", options->height,
                  "image height in pixels (default: from the camera's aspect ratio); the "
                  "vertical field of view is kept at any size")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--env", options->env,
                  "environment map (.exr/.hdr, equirectangular 2:1); default: the built-in "
                  "city.exr");
  cmd->add_flag("--no-env", options->no_env, "no environment light (black background)");
  cmd->add_option("--env-rotation", options->env_rotation,
                  "environment rotation about +Y in degrees (counter-clockwise from above)")
      ->capture_default_str();
  cmd->add_option("--env-intensity", options->env_intensity, "environment radiance scale")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--exposure", options->exposure, "exposure in EV for the PNG")
      ->capture_default_str();
  cmd->add_option("--tonemap", options->tonemap, "tone mapper for the PNG")
      ->check(CLI::IsMember(tone_mapper_names()))
      ->capture_default_str();
  cmd->add_option("--model", options->model,
                  "BRDF model: reference (height-correlated Smith) or classic (LearnOpenGL's "
                  "Schlick-GGX)")
      ->check(CLI::IsMember(brdf_model_names()))
      ->capture_default_str();
  // (Callbacks, as add_multiscatter_flags: the optional stays unset without either.)
  auto* half = cmd->add_flag_callback(
      "--half", [options] { options->exr_float = false; },
      "write the EXR as half floats (the path tracer's default)");
  cmd->add_flag_callback(
         "--float", [options] { options->exr_float = true; },
         "write the EXR as 32-bit floats (the OpenGL renderer's default)")
      ->excludes(half);
  add_multiscatter_flags(*cmd, options->multiscatter,
                         "multiple-scattering energy compensation (Kulla-Conty / Fdez-Aguera); "
                         "default: on for the reference model, off for classic");

  const RenderRunner path = add_path_render_options(*cmd);
  const RenderRunner gl = add_gl_render_options(*cmd);
  cmd->callback([cmd, options, renderer, path, gl] {
    const std::string misplaced = other_renderers_options(*cmd, *renderer);
    if (!misplaced.empty()) {
      const bool is_path = *renderer == "path";
      fail(
          "--renderer {} does not take {}: {} option(s), which it would ignore; remove "
          "them or use --renderer {}",
          *renderer, misplaced, is_path ? "OpenGL renderer" : "path tracer",
          is_path ? "gl" : "path");
    }
    RenderCommandOptions o = *options;
    if (!o.shutter.empty()) {
      const std::size_t colon = o.shutter.find(':');
      char* end = nullptr;
      bool ok = colon != std::string::npos;
      if (ok) {
        const std::string a = o.shutter.substr(0, colon), b = o.shutter.substr(colon + 1);
        o.shutter_open = std::strtof(a.c_str(), &end);
        ok = !a.empty() && *end == '\0';
        o.shutter_close = std::strtof(b.c_str(), &end);
        ok = ok && !b.empty() && *end == '\0';
      }
      if (!ok || !std::isfinite(o.shutter_open) || !std::isfinite(o.shutter_close))
        fail("--shutter {}: expected OPEN:CLOSE in seconds, e.g. -0.01:0.01", o.shutter);
      if (!(o.shutter_open < o.shutter_close))
        fail("--shutter {}: the shutter must open before it closes", o.shutter);
    }
    if (o.output.empty()) {
      std::string stem = std::filesystem::path(o.scene).stem().string();
      o.output = "out/" + stem + "_" + *renderer + ".png";
    }
    o.outputs = image_output_paths(o.output, "-o");
    create_output_directory(o.outputs);
    render_frames(o, *renderer == "path" ? path : gl);
  });
}

}  // namespace pbrkit::cli
