// pbrkit render --renderer path: the path tracer's own options (stopping rules, sampling,
// threads, sample ranges, checkpoints, AOVs) and the runner that loads the scene, installs
// the SIGINT/SIGTERM handlers, renders and writes the outputs atomically.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "accumulation.h"
#include "commands.h"
#include "denoising.h"
#include "pbrkit/core/color.h"
#include "pbrkit/denoise/denoiser_driven_sampling.h"
#include "pbrkit/denoise/inputs.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/pt/film.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "pbrkit/util/progress.h"
#include "render_options.h"

namespace pbrkit::cli {

namespace {

// Set by the signal handler, polled by the renderer between tiles. Lock-free atomics are
// async-signal-safe.
std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};

extern "C" void on_stop_signal(int sig) {
  g_signal.store(sig);
  g_stop.store(true);
}

// Installs the handlers for the lifetime of a render and restores the previous ones.
class StopSignals {
 public:
  StopSignals() {
    g_stop = false;
    g_signal = 0;
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~StopSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

// The options of --renderer path. Those that set a PathTracerSettings field start from a
// default-constructed one: the library and the CLI have one set of defaults.
struct PathOptions {
  std::uint32_t spp = PathTracerSettings{}.spp;
  double time = PathTracerSettings{}.time_limit;
  float noise_threshold = PathTracerSettings{}.noise_threshold;
  std::uint32_t min_spp = PathTracerSettings{}.min_spp;
  int max_bounces = PathTracerSettings{}.max_bounces;
  std::uint32_t seed = PathTracerSettings{}.seed;
  int threads = PathTracerSettings{}.threads;
  std::string sample_range;
  std::string checkpoint;
  double checkpoint_interval = PathTracerSettings{}.checkpoint_interval;
  std::string resume;
  std::vector<std::string> aovs;
  bool denoise = false;
  DenoiserFlags denoiser;
  std::string adaptive = "noise";
  bool noise_threshold_given = false;
  std::string filter{pixel_filter_name(PathTracerSettings{}.filter)};
  std::string light_sampler{light_sampler_name(PathTracerSettings{}.light_sampler)};
  std::string guiding{guiding_name(PathTracerSettings{}.guiding)};
  std::optional<float> guiding_bsdf_share;
};

std::pair<std::uint32_t, std::uint32_t> parse_sample_range(const std::string& text) {
  const auto colon = text.find(':');
  auto parse = [&](const std::string& part) -> std::uint32_t {
    std::size_t used = 0;
    unsigned long v = 0;
    try {
      v = std::stoul(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (part.empty() || used != part.size() || v > 0xffffffffUL)
      fail("--sample-range '{}': expected A:B with whole numbers 0 <= A < B", text);
    return std::uint32_t(v);
  };
  if (colon == std::string::npos)
    fail("--sample-range '{}': expected A:B with whole numbers 0 <= A < B", text);
  const std::uint32_t a = parse(text.substr(0, colon)), b = parse(text.substr(colon + 1));
  if (a >= b) fail("--sample-range '{}': the range is empty (A must be below B)", text);
  return {a, b};
}

}  // namespace

RenderRunner add_path_render_options(CLI::App& render) {
  auto p = std::make_shared<PathOptions>();
  const std::string group = kPathOptionsGroup;
  render
      .add_option("--spp", p->spp,
                  "samples per pixel (the most any pixel gets; with --noise-threshold "
                  "converged pixels stop earlier)")
      ->check(CLI::Range(1u, 1u << 24))
      ->capture_default_str()
      ->group(group);
  render.add_option("--time", p->time, "stop after this many seconds (0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str()
      ->group(group);
  CLI::Option* noise_threshold_option =
      render
          .add_option("--noise-threshold", p->noise_threshold,
                      "adaptive sampling: a pixel stops once its estimated relative error (two "
                      "interleaved half buffers, as in Cycles) is below this; 0 turns it off")
          ->check(CLI::NonNegativeNumber)
          ->capture_default_str()
          ->group(group);
  render
      .add_option("--adaptive", p->adaptive,
                  "where samples go: 'noise' (each pixel stops by its own noise, "
                  "--noise-threshold) or 'denoised' (passes of samples sent where the denoised "
                  "image's estimated error falls most per sample, --spp x pixels samples in "
                  "all; implies --denoise; docs/DENOISER.md)")
      ->check(CLI::IsMember({"noise", "denoised"}))
      ->capture_default_str()
      ->group(group);
  render.add_option("--min-spp", p->min_spp, "samples every pixel gets before it may stop")
      ->check(CLI::Range(1u, 1u << 24))
      ->capture_default_str()
      ->group(group);
  render
      .add_option("--max-bounces", p->max_bounces,
                  "surface interactions that gather light (1: direct lighting only)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str()
      ->group(group);
  render.add_option("--seed", p->seed, "sampler seed (same seed: bit-identical image)")
      ->capture_default_str()
      ->group(group);
  render.add_option("--threads", p->threads, "render threads (0: all cores)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str()
      ->group(group);
  render
      .add_option("--sample-range", p->sample_range,
                  "A:B renders only samples A..B-1 of every pixel and writes an accumulation "
                  "EXR (sums and counts) for 'pbrkit merge' instead of the PNG")
      ->group(group);
  render
      .add_option("--checkpoint", p->checkpoint,
                  "save the accumulation buffers to this EXR every --checkpoint-interval "
                  "seconds and when interrupted")
      ->group(group);
  render.add_option("--checkpoint-interval", p->checkpoint_interval, "seconds between checkpoints")
      ->check(CLI::PositiveNumber)
      ->capture_default_str()
      ->group(group);
  render
      .add_option("--resume", p->resume,
                  "continue from a checkpoint of the same scene and options (the result "
                  "equals an uninterrupted render)")
      ->check(CLI::ExistingFile)
      ->group(group);
  render
      .add_option("--aov", p->aovs,
                  "extra EXR layers: albedo, normal, depth, samples, noise, denoise (the half "
                  "buffers 'pbrkit denoise' reads) (repeat or comma separate)")
      ->delimiter(',')
      ->check(CLI::IsMember(render_aov_names()))
      ->group(group);
  render
      .add_flag("--denoise", p->denoise,
                "denoise the image (--denoiser); the EXR keeps the raw image (layer 'raw') and "
                "the albedo, normal and depth as layers")
      ->group(group);
  add_denoiser_options(render, &p->denoiser, group);
  render.add_option("--filter", p->filter, "pixel filter: tent (radius 1 px) or box (1 px)")
      ->check(CLI::IsMember(pixel_filter_names()))
      ->capture_default_str()
      ->group(group);
  render
      .add_option("--light-sampler", p->light_sampler,
                  "how each shading point picks the light it samples: bvh (a light tree: "
                  "near lights facing the point more often) or power (by emitted power alone)")
      ->check(CLI::IsMember({"bvh", "power"}))
      ->capture_default_str()
      ->group(group);
  render
      .add_option("--guiding", p->guiding,
                  "path guiding: on learns the incident light while rendering (passes of "
                  "doubling sample counts) and sends a share of the bounces of diffuse and rough "
                  "surfaces where it comes from, learned per region (unbiased; a resumed render or "
                  "a --sample-range "
                  "part learns its own guide, so its bits differ from an uninterrupted render's)")
      ->check(CLI::IsMember({"off", "on"}))
      ->capture_default_str()
      ->group(group);
  render
      .add_option("--guiding-bsdf-share", p->guiding_bsdf_share,
                  "with --guiding on: the probability a guided bounce samples the BSDF rather "
                  "than the guide, fixed (default: learned per region of space, 1 where the "
                  "guide does not pay)")
      ->check(CLI::Range(0.0f, 1.0f))
      ->group(group);

  // The environment the frames of a sequence share (loaded once).
  auto shared_env = std::make_shared<std::optional<Environment>>();
  return [p, noise_threshold_option, shared_env](const RenderCommandOptions& o,
                                                 const Scene& scene) {
    const PathOptions& po = *p;
    std::optional<Environment>& env = *shared_env;
    if (!o.no_env && !env)
      env = load_environment_or_default(o.env, o.env_rotation, o.env_intensity);
    const RenderView view = select_render_view(scene, o);
    const Camera& camera = view.camera;

    PathTracerSettings s;
    s.width = view.size.width;
    s.height = view.size.height;
    s.spp = po.spp;
    s.time_limit = po.time;
    s.noise_threshold = po.noise_threshold;
    s.min_spp = std::min(po.min_spp, po.spp);
    s.max_bounces = po.max_bounces;
    s.seed = po.seed;
    s.threads = po.threads;
    s.filter = parse_pixel_filter(po.filter);
    s.light_sampler = parse_light_sampler(po.light_sampler);
    s.guiding = parse_guiding(po.guiding);
    if (po.guiding_bsdf_share) s.guiding_bsdf_fraction = *po.guiding_bsdf_share;
    if (!o.shutter.empty()) {
      s.shutter.animation = find_animation(scene, o.animation);
      s.shutter.open = o.animation_time + o.shutter_open;
      s.shutter.close = o.animation_time + o.shutter_close;
    }
    s.brdf.model = parse_brdf_model(o.model);
    s.brdf.multiscatter = o.multiscatter.value_or(default_multiscatter(s.brdf.model));
    const bool partial = !po.sample_range.empty();
    const bool driven = po.adaptive == "denoised";
    if (driven) {
      if (partial)
        fail(
            "--adaptive denoised with --sample-range: each pass's choice of pixels depends on "
            "every sample before it, so a range cannot be rendered alone");
      if (noise_threshold_option->count() > 0 && po.noise_threshold > 0.0f)
        fail(
            "--adaptive denoised with --noise-threshold: the denoised error decides where "
            "samples go (use --adaptive noise for the per-pixel rule)");
      s.noise_threshold = 0.0f;
    }
    // The weights are loaded before the render, not after it, and once.
    const LoadedDenoiser denoiser = po.denoise || driven ? po.denoiser.load() : LoadedDenoiser{};
    if (partial && po.denoise)
      fail(
          "--denoise with --sample-range: a part cannot be denoised alone; denoise when "
          "merging the parts ('pbrkit merge --denoise')");
    if (partial) {
      std::tie(s.sample_begin, s.sample_end) = parse_sample_range(po.sample_range);
      // Adaptive stopping depends on all of a pixel's samples; a part cannot decide it.
      s.noise_threshold = 0.0f;
    }
    std::optional<Film> resume;
    if (!po.resume.empty()) {
      resume = read_accumulation(po.resume);
      if (!driven && resume->denoiser_passes > 0)
        fail("--resume {}: the film was rendered with --adaptive denoised; resume it with that",
             po.resume);
      s.resume = &*resume;
    }
    if (!po.checkpoint.empty()) {
      s.checkpoint_interval = po.checkpoint_interval;
      const std::string path = po.checkpoint;
      s.checkpoint = [path](const Film& film) { write_film(path, film); };
    }
    StopSignals signals;
    s.stop = &g_stop;

    ProgressBar bar("render");
    note("path tracing {} ({} triangles) at {}x{}, {} {} spp{}, {} bounces", scene.source,
         scene.triangle_count(), s.width, s.height, driven ? "on average" : "up to",
         partial ? s.sample_end - s.sample_begin : s.spp,
         driven                     ? ", denoiser-driven"
         : s.noise_threshold > 0.0f ? fmt::format(", noise threshold {}", s.noise_threshold)
                                    : "",
         s.max_bounces);
    std::optional<Image> driven_denoised;
    const PathTracerResult result = [&] {
      if (!driven) return render_path(scene, env ? &*env : nullptr, camera, s, bar.callback());
      DenoiserDrivenSamplingResult r =
          render_denoiser_driven(scene, env ? &*env : nullptr, camera, s, {}, bar.callback());
      note("denoiser-driven sampling: {} passes, {} of {} samples", r.passes,
           r.render.stats.samples, r.budget);
      if (r.denoised_ok) driven_denoised = std::move(r.denoised);
      return std::move(r.render);
    }();
    const auto& st = result.stats;
    bar.finish(fmt::format(
        "{:.1f} s, {:.2f} M samples*px/s, {:.2f} M rays/s, BVH {:.2f} s", st.render_seconds,
        st.render_seconds > 0 ? st.samples / st.render_seconds * 1e-6 : 0.0,
        st.render_seconds > 0 ? st.rays / st.render_seconds * 1e-6 : 0.0, st.build_seconds));

    const std::string& exr = o.outputs.exr;
    if (!po.checkpoint.empty() && !st.complete) write_film(po.checkpoint, result.film);
    if (partial) {
      write_film(exr, result.film);
      note("wrote {} (samples {}:{}; combine the parts with 'pbrkit merge')", exr, s.sample_begin,
           s.sample_end);
    } else {
      const auto type = o.exr_float.value_or(false) ? ExrPixelType::kFloat : ExrPixelType::kHalf;
      // Denoising is skipped when the render was interrupted, and stops (leaving the raw
      // image to be written) when Ctrl-C comes while it runs.
      // Denoiser-driven passes choose their pixels from the classic denoiser's own error
      // estimate (docs/DENOISER.md); the learned denoiser then denoises the final film.
      std::optional<Image> denoised;
      if (driven && denoiser.choice.kind == DenoiserKind::kClassic)
        denoised = std::move(driven_denoised);
      if ((po.denoise || driven) && !denoised && !g_stop.load())
        denoised = run_denoiser(denoise_input(result.film), denoiser, &g_stop);
      if ((po.denoise || driven) && !denoised)
        warn("interrupted: not denoised, wrote the raw image");
      if (denoised) {
        write_render_exr(exr, result.film, with_denoise_aovs(po.aovs), type, &*denoised);
        write_display_png(o.outputs.png, *denoised, {o.exposure, parse_tone_mapper(o.tonemap)});
      } else {
        write_render_exr(exr, result.film, po.aovs, type);
        write_display_png(o.outputs.png, result.color, {o.exposure, parse_tone_mapper(o.tonemap)});
      }
      note("wrote {} and {}{}", o.outputs.png, exr, denoised ? " (denoised)" : "");
    }
    if (g_stop.load()) {
      const int sig = g_signal.load();
      warn("interrupted by signal {}: wrote the image rendered so far", sig);
      throw ExitRequest{128 + (sig > 0 ? sig : SIGINT)};
    }
    if (!st.complete) note("stopped at the time limit: wrote the image rendered so far");
    if (!o.more_frames) env.reset();
  };
}

}  // namespace pbrkit::cli
