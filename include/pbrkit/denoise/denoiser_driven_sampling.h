#pragma once
// Adaptive sampling driven by the denoiser's estimate of its own error, after Li, Wu and
// Chuang 2012, "SURE-based Optimization for Adaptive Sampling and Reconstruction" (SIGGRAPH
// Asia 2012) and Rousselle, Knaus and Zwicker 2012, "Adaptive Rendering with Non-Local
// Means Filtering" (SIGGRAPH Asia 2012): the image is rendered in passes; after each pass
// it is denoised, and the next pass's samples go where the estimated error of the DENOISED
// image falls most per sample, until the sample budget is spent. The path tracer's own
// rule (pt/adaptive_sampling.h) stops pixels by their raw noise, which the denoiser may
// already remove; this one spends samples where the filter cannot (docs/DENOISER.md,
// "Denoiser-driven adaptive sampling").
//
// Deterministic for a fixed seed: every decision comes from render_path and denoise, both
// bit-identical whatever the thread count, and ties are broken by pixel index.
#include <cstdint>

#include "pbrkit/denoise/denoiser.h"
#include "pbrkit/pt/path_tracer.h"

namespace pbrkit {

struct DenoiserDrivenSamplingOptions {
  /// The first pass gives every pixel this fraction of the average budget (at least 2
  /// samples: the denoiser needs both half buffers). A quarter left too many pixels at 4
  /// spp in the test scene, where the denoiser is much worse (docs/DENOISER.md)
  float initial_fraction = 0.5f;
  /// Each later pass brings at most this fraction of the pixels (those of highest
  /// priority that still lack samples) to the pass's target
  float pass_fraction = 0.5f;
  /// A pixel gets at most this many times the average budget
  float max_spp_factor = 4.0f;
  /// At most this many passes (the first included)
  int max_passes = 12;
  DenoiseOptions denoise;
};

struct DenoiserDrivenSamplingResult {
  /// The film (per-pixel counts vary; no `done` flag is left set), its raw colour and the
  /// statistics summed over the passes (samples, rays, render and build seconds)
  PathTracerResult render;
  /// The last pass's denoised image; the film's raw mean when a stop came before it
  Image denoised;
  bool denoised_ok = false;  ///< false: a stop came, `denoised` is the raw mean
  int passes = 0;
  std::uint64_t budget = 0;  ///< settings.spp x pixels; render.stats.samples <= budget
};

/// Renders with settings.spp x width x height camera samples in all, distributed by the
/// denoiser's error estimate (denoise()'s `error`): pass 0 gives every pixel
/// max(2, initial_fraction spp) samples; each later pass denoises the film, ranks the
/// pixels by priority = estimated relative error / samples so far (with variance going as
/// 1/n, the error an extra sample removes), and brings the highest-ranked ones (up to
/// pass_fraction of the pixels, within the budget left) to a target that doubles every
/// pass (at most max_spp_factor spp). The last denoise is the output.
///
/// Checkpoints (settings.checkpoint, at most every checkpoint_interval seconds) come after
/// whole passes, with the film's denoiser_passes set; settings.resume continues from one
/// exactly as the run that wrote it would have gone on (same seed and threads: the same
/// bits).
///
/// Throws pbrkit::Error for settings it cannot honour: a sample range (split renders
/// cannot share the decisions: each pass's pixels depend on every sample before it), a
/// resume film not made by it or of another size, noise_threshold > 0 (a second stopping
/// rule), or options out of range. settings.min_spp is not used. A stop (settings.stop,
/// the time limit, `progress` returning false) ends it with the samples taken so far.
DenoiserDrivenSamplingResult render_denoiser_driven(
    const Scene& scene, const Environment* env, const Camera& camera,
    const PathTracerSettings& settings, const DenoiserDrivenSamplingOptions& options = {},
    const ProgressCallback& progress = {});

}  // namespace pbrkit
