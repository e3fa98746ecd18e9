// Denoiser-driven adaptive sampling (denoiser_driven_sampling.h): passes of render_path
// resumed from the previous film, the pixels left out of a pass marked `done`.
#include "pbrkit/denoise/denoiser_driven_sampling.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include "pbrkit/denoise/inputs.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

void check(const PathTracerSettings& settings, const DenoiserDrivenSamplingOptions& options) {
  if (settings.sample_begin != 0 || settings.sample_end != 0)
    fail(
        "denoiser-driven sampling: a sample range cannot be rendered alone (each pass's "
        "choice of pixels depends on every sample before it)");
  if (settings.resume && settings.resume->denoiser_passes == 0)
    fail(
        "denoiser-driven sampling: the film to resume was not rendered by it (it records no "
        "passes)");
  if (settings.resume &&
      (settings.resume->width != settings.width || settings.resume->height != settings.height))
    fail("denoiser-driven sampling: the film to resume is {}x{} but the render is {}x{}",
         settings.resume->width, settings.resume->height, settings.width, settings.height);
  if (settings.noise_threshold > 0.0f)
    fail(
        "denoiser-driven sampling: noise_threshold must be 0 (the denoised error decides "
        "where samples go; it is {})",
        settings.noise_threshold);
  if (settings.spp < 1 || settings.width < 1 || settings.height < 1)
    fail("denoiser-driven sampling: the image and spp must not be empty ({}x{}, {} spp)",
         settings.width, settings.height, settings.spp);
  if (!(options.initial_fraction > 0.0f && options.initial_fraction <= 1.0f))
    fail("denoiser-driven sampling: initial_fraction must be in (0, 1] (it is {})",
         options.initial_fraction);
  if (!(options.pass_fraction > 0.0f && options.pass_fraction <= 1.0f))
    fail("denoiser-driven sampling: pass_fraction must be in (0, 1] (it is {})",
         options.pass_fraction);
  if (!(options.max_spp_factor >= 1.0f))
    fail("denoiser-driven sampling: max_spp_factor must be >= 1 (it is {})",
         options.max_spp_factor);
  if (options.max_passes < 1)
    fail("denoiser-driven sampling: max_passes must be >= 1 (it is {})", options.max_passes);
}

void add_stats(PathTracerStats& total, const PathTracerStats& pass) {
  total.render_seconds += pass.render_seconds;
  total.build_seconds += pass.build_seconds;
  total.bvh_seconds += pass.bvh_seconds;
  total.samples += pass.samples;
  total.rays += pass.rays;
  total.non_finite_samples += pass.non_finite_samples;
  total.medium_overflows += pass.medium_overflows;
  total.stopped = total.stopped || pass.stopped;
  total.noise = pass.noise;
}

}  // namespace

DenoiserDrivenSamplingResult render_denoiser_driven(const Scene& scene, const Environment* env,
                                                    const Camera& camera,
                                                    const PathTracerSettings& settings,
                                                    const DenoiserDrivenSamplingOptions& options,
                                                    const ProgressCallback& progress) {
  check(settings, options);
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  DenoiserDrivenSamplingResult out;
  const std::size_t n = std::size_t(settings.width) * std::size_t(settings.height);
  const std::uint64_t budget = std::uint64_t(settings.spp) * n;
  out.budget = budget;
  // Counts are exact in the film's floats up to 2^24.
  const std::uint32_t cap =
      std::uint32_t(std::clamp(std::floor(double(settings.spp) * double(options.max_spp_factor)),
                               double(settings.spp), double(1u << 24)));
  std::uint32_t target = std::min(
      settings.spp,
      std::max(2u, std::uint32_t(std::floor(double(settings.spp) * options.initial_fraction))));

  bool stopped = false, asked_to_stop = false;
  std::uint64_t taken = 0;
  double last_checkpoint = 0.0;
  // One pass: render_path brings every pixel not marked done to `pass_target` samples.
  auto render_pass = [&](std::uint32_t pass_target, const Film* resume, std::uint64_t cost) {
    PathTracerSettings s = settings;
    s.spp = pass_target;
    s.min_spp = pass_target;  // one internal pass: the counts are ours to choose
    s.noise_threshold = 0.0f;
    s.resume = resume;
    s.checkpoint = nullptr;  // ours come at pass boundaries, where they can be resumed
    if (settings.time_limit > 0.0) s.time_limit = std::max(1e-9, settings.time_limit - elapsed());
    const std::uint64_t before = taken;
    ProgressCallback inner;
    if (progress)
      inner = [&](double fraction, const std::string& detail) {
        // render_path counts the pixels marked done as finished: its work is
        // n x target, of which n x target - cost was done before the pass.
        const double whole = double(n) * double(pass_target);
        const double pass = std::max(0.0, fraction * whole - (whole - double(cost)));
        if (!progress(std::min(1.0, (double(before) + pass) / double(budget)), detail))
          asked_to_stop = true;
        return !asked_to_stop;
      };
    PathTracerResult r = render_path(scene, env, camera, s, inner);
    taken += r.stats.samples;
    add_stats(out.render.stats, r.stats);
    stopped = stopped || r.stats.stopped;
    out.render.film = std::move(r.film);
    ++out.passes;
    out.render.film.denoiser_passes = std::uint32_t(out.passes);
    // A checkpoint after a whole pass holds all a resume needs: the counts (their sum is
    // the samples taken, their largest the pass's target) and the number of passes.
    if (settings.checkpoint && !r.stats.stopped &&
        elapsed() - last_checkpoint >= settings.checkpoint_interval) {
      settings.checkpoint(out.render.film);
      last_checkpoint = elapsed();
    }
  };
  const auto keep_going = [&] {
    return !asked_to_stop && !(settings.stop && settings.stop->load()) &&
           !(settings.time_limit > 0.0 && elapsed() >= settings.time_limit);
  };
  auto run_denoiser = [&](Image* error) {
    DenoiseStats stats;
    ProgressCallback check_stop = [&](double, const std::string&) { return keep_going(); };
    Image image =
        denoise(denoise_input(out.render.film), options.denoise, check_stop, &stats, error);
    out.denoised_ok = !stats.interrupted;
    return image;
  };

  if (settings.resume) {
    // Where the checkpoint's run stood: each pass brings at least one pixel exactly to its
    // target, the targets never fall, and the first pass gave every pixel its target.
    out.render.film = *settings.resume;
    out.passes = int(settings.resume->denoiser_passes);
    taken = 0;
    float largest = 0.0f;
    for (float c : out.render.film.count) {
      taken += std::uint64_t(c);
      largest = std::max(largest, c);
    }
    target = std::max(target, std::uint32_t(largest));
  } else {
    render_pass(target, nullptr, std::uint64_t(target) * n);
  }
  Image error;
  std::vector<std::size_t> order(n);
  std::vector<double> priority(n);
  bool current = false;  // out.denoised is the denoised current film
  while (!stopped && keep_going() && out.passes < options.max_passes && taken < budget) {
    out.denoised = run_denoiser(&error);
    current = out.denoised_ok;
    if (!out.denoised_ok) break;
    Film& film = out.render.film;
    // Priority: the estimated error of the denoised pixel over its sample count. With a
    // pixel's variance going as 1/n the error e(n) ~ C/n, and an extra sample removes
    // about e/n (Li et al. 2012 spend samples where the estimated error falls most).
    for (std::size_t i = 0; i < n; ++i)
      priority[i] = double(error.data[i]) / double(std::max(1.0f, film.count[i]));
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return priority[a] > priority[b]; });
    // The highest-ranked pixels below the target, within the pass's share of the pixels
    // and the budget left; a pixel whose samples do not fit is passed over for cheaper
    // ones. The target doubles every pass (and again while no ranked pixel is below it).
    const std::size_t quota =
        std::max<std::size_t>(1, std::size_t(std::ceil(double(n) * options.pass_fraction)));
    const std::uint64_t left = budget - taken;
    std::uint64_t cost = 0;
    std::size_t chosen = 0;
    do {
      target = std::min(cap, target * 2);
      std::fill(film.done.begin(), film.done.end(), 1.0f);
      for (std::size_t k = 0; k < n && chosen < quota; ++k) {
        const std::size_t i = order[k];
        const auto count = std::uint32_t(film.count[i]);
        if (count >= target) continue;
        const std::uint64_t need = target - count;
        if (cost + need > left) continue;
        cost += need;
        film.done[i] = 0.0f;
        ++chosen;
      }
    } while (chosen == 0 && target < cap);
    if (chosen == 0) break;
    const Film resume = std::move(film);  // render_path starts from a copy
    render_pass(target, &resume, cost);
    current = false;
  }
  Film& film = out.render.film;
  std::fill(film.done.begin(), film.done.end(), 0.0f);
  out.render.color = film.color();
  if (!current && !stopped && keep_going()) {
    out.denoised = run_denoiser(nullptr);
    current = out.denoised_ok;
  }
  out.denoised_ok = current;
  if (!current) out.denoised = out.render.color;
  out.render.stats.stopped = !current;
  out.render.stats.complete = current;
  if (progress) progress(1.0, {});
  return out;
}

}  // namespace pbrkit
