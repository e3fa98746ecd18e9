// pbrkit render --renderer gl: the OpenGL renderer's own options (IBL bake size, irradiance
// form, MSAA, background, Fresnel form, debug channel) and the runner: load the scene and
// environment, bake the IBL maps through the library, render headless through EGL, write the linear
// EXR and the tone-mapped PNG with the same display transform as the path tracer.
#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "gl_options.h"
#include "pbrkit/core/color.h"
#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "render_options.h"

namespace pbrkit::cli {

namespace {

struct GlOptions {
  std::string irradiance = "sh";
  int msaa = 4;
  std::string background = "env";
  std::string fresnel = "schlick";
  int bake_size = gl::realtime_bake_options().face_size;
  int bake_samples = gl::realtime_bake_options().samples;
  bool no_ibl = false;
  bool no_lights = false;
  bool no_glass_shadows = false;
  bool no_glass_reflections = false;
  bool opaque_shadows = false;
  std::string channel{gl::debug_channel_name(gl::DebugChannel::kNone)};
};

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace

RenderRunner add_gl_render_options(CLI::App& render) {
  auto g = std::make_shared<GlOptions>();
  const std::string group = kGlOptionsGroup;
  render
      .add_option("--irradiance", g->irradiance, "diffuse irradiance: sh (9 coefficients) or cube")
      ->check(CLI::IsMember({"sh", "cube"}))
      ->capture_default_str()
      ->group(group);
  render.add_option("--msaa", g->msaa, "multisample anti-aliasing samples per pixel (1 = off)")
      ->check(CLI::Range(1, 16))
      ->capture_default_str()
      ->group(group);
  render
      .add_option("--background", g->background,
                  "env (the environment, sharp), blur:<mip> (the prefiltered cube's mip) or "
                  "color:<r>,<g>,<b> (linear)")
      ->capture_default_str()
      ->group(group);
  render.add_option("--fresnel", g->fresnel, "schlick, or sg (UE4's spherical-Gaussian form)")
      ->check(CLI::IsMember({"schlick", "sg"}))
      ->capture_default_str()
      ->group(group);
  render.add_option("--bake-size", g->bake_size, "IBL bake: specular cube face size (power of 2)")
      ->capture_default_str()
      ->group(group);
  render.add_option("--bake-samples", g->bake_samples, "IBL bake: GGX samples per texel")
      ->capture_default_str()
      ->group(group);
  render.add_flag("--no-ibl", g->no_ibl, "no image-based lighting (background still shown)")
      ->group(group);
  render.add_flag("--no-lights", g->no_lights, "ignore the scene's punctual lights")->group(group);
  render
      .add_flag("--no-glass-shadows", g->no_glass_shadows,
                "transmissive objects do not shadow the environment's light on other surfaces "
                "(the Khronos Sample Viewer's image)")
      ->group(group);
  render
      .add_flag("--opaque-shadows", g->opaque_shadows,
                "opaque objects shadow the environment's light on other surfaces too, and light "
                "them with their own (a proxy per object, the 16 largest spheres and boxes; "
                "closer to the path tracer, further from the Khronos Sample Viewer)")
      ->group(group);
  render
      .add_flag("--no-glass-reflections", g->no_glass_reflections,
                "thick glass reflects the environment alone, not the scene around it on the "
                "screen (the Khronos Sample Viewer's image)")
      ->group(group);
  render
      .add_option("--channel", g->channel,
                  "a debug channel instead of the shaded image, raw (no exposure, no tone map): "
                  "a material input (base-color, metallic, roughness, normal as n*0.5+0.5, "
                  "occlusion, emissive) or one lobe's share of the radiance (diffuse, specular, "
                  "clearcoat, sheen, transmission)")
      ->check(CLI::IsMember(gl::debug_channel_names()))
      ->capture_default_str()
      ->group(group);

  // What the frames of a sequence share: one context, renderer and IBL bake (the scene is
  // uploaded again per frame); released after the last frame, before main() returns.
  struct Session {
    std::optional<gl::HeadlessContext> context;
    std::optional<gl::Renderer> renderer;
    bool lit = false;
  };
  auto session = std::make_shared<Session>();
  return [g, session](const RenderCommandOptions& o, const Scene& scene) {
    if (!o.shutter.empty())
      note(
          "--shutter: the OpenGL renderer has no motion blur; it draws the shutter's centre "
          "(t = {:.4g} s); the path tracer renders the blur",
          o.pose_time());
    const auto t_start = Clock::now();
    gl::RenderSettings settings;
    const BrdfModel model = parse_brdf_model(o.model);
    settings.brdf = {model, o.multiscatter.value_or(default_multiscatter(model))};
    settings.fresnel =
        g->fresnel == "sg" ? gl::FresnelMode::kSphericalGaussian : gl::FresnelMode::kSchlick;
    settings.irradiance = parse_irradiance_mode(g->irradiance);
    settings.msaa = g->msaa;
    settings.background = parse_background(g->background);
    settings.env_rotation_deg = o.env_rotation;
    settings.env_intensity = o.env_intensity;
    settings.ibl = !g->no_ibl;
    settings.lights = !g->no_lights;
    settings.transmissive_shadows = !g->no_glass_shadows;
    settings.transmissive_reflections = !g->no_glass_reflections;
    settings.opaque_shadows = g->opaque_shadows;
    settings.debug_channel = gl::parse_debug_channel(g->channel);
    // A debug channel's values are shown as they are (the Sample Viewer's debug outputs).
    const bool raw = settings.debug_channel != gl::DebugChannel::kNone;
    const ToneMapper tone_mapper = raw ? ToneMapper::kNone : parse_tone_mapper(o.tonemap);

    const RenderView view = select_render_view(scene, o);
    const int width = view.size.width, height = view.size.height;

    const auto t_gl = Clock::now();
    if (!session->renderer) {
      session->context.emplace();
      session->renderer.emplace();
    }
    gl::HeadlessContext& context = *session->context;
    gl::Renderer& renderer = *session->renderer;
    renderer.set_scene(scene);
    double bake_ms = 0.0;
    if (!session->lit) {
      std::optional<Environment> env;
      if (!o.no_env) env = load_environment_or_default(o.env, o.env_rotation, o.env_intensity);
      std::optional<BakeOptions> bake;
      if (settings.ibl) {
        bake = gl::realtime_bake_options(g->bake_size, g->bake_samples);
        bake->model = settings.brdf.model;
      }
      const auto t_bake = Clock::now();
      renderer.set_environment_light(env ? &*env : nullptr, bake);
      bake_ms = env && bake ? ms_since(t_bake) : 0.0;
      session->lit = true;
    }
    renderer.render(view.camera, width, height, settings);
    const Image frame = renderer.read_back();
    const double gpu_ms = renderer.gpu_time_ms();
    const double gl_ms = ms_since(t_gl) - bake_ms;

    write_exr(o.outputs.exr, rgb_channels(frame),
              o.exr_float.value_or(true) ? ExrPixelType::kFloat : ExrPixelType::kHalf);
    write_display_png(o.outputs.png, frame, {raw ? 0.0f : o.exposure, tone_mapper});
    note(
        "OpenGL ({}, {} context): {} at {}x{}: bake {:.0f} ms, GL {:.0f} ms (frame {:.1f} ms on "
        "the GPU), total {:.0f} ms; wrote {} and {}",
        gl::describe_current_context(), context.platform(), scene.source, width, height, bake_ms,
        gl_ms, gpu_ms, ms_since(t_start), o.outputs.png, o.outputs.exr);
    if (!o.more_frames) {
      session->renderer.reset();
      session->context.reset();
      session->lit = false;
    }
  };
}

}  // namespace pbrkit::cli
