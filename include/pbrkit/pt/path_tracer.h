#pragma once
// The CPU path tracer: the project's ground truth. Unidirectional path tracing with
// next-event estimation and multiple importance sampling (power heuristic, Veach 1997
// ch. 9) over Embree 3 geometry, parallel over tiles with oneTBB, sampled with the
// foundation's Owen-scrambled Sobol sequence (core/sampling.h), so that a render is a
// deterministic function of (scene, camera, settings, seed): bit-identical whatever the
// thread count, splittable into sample ranges, and resumable from a checkpoint.
//
// The library never installs signal handlers; the caller passes a stop flag and/or a
// progress callback that returns false, and gets back everything rendered so far.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "pbrkit/core/brdf.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image.h"
#include "pbrkit/pt/film.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/scene.h"
#include "pbrkit/util/progress.h"

namespace pbrkit {

/// How the path tracer combines its two strategies for area and environment lights.
/// kMis is the renderer; the other two exist so tests can check that all three converge
/// to the same image (and that MIS has the lowest variance).
enum class LightStrategy { kMis, kLightOnly, kBsdfOnly };

/// How next-event estimation chooses the one light it samples at a shading point.
enum class LightSamplerKind {
  /// A light BVH (Conty Estevez & Kulla 2018; pbrt-v4's BVHLightSampler): lights near the
  /// point and facing it are chosen more often. The default.
  kBvh,
  /// In proportion to each light's emitted power, wherever the point is (pbrt-v4's
  /// PowerLightSampler): kept for comparison.
  kPower,
};
LightSamplerKind parse_light_sampler(std::string_view name);  ///< "bvh" | "power"
std::string_view light_sampler_name(LightSamplerKind kind);

/// Path guiding: learn the incident radiance while rendering and sample directions from it
/// (the SD-tree of Mueller, Gross & Novak 2017, "Practical Path Guiding for Efficient
/// Light-Transport Simulation"; docs/MODEL.md, "Path guiding").
enum class Guiding {
  kOff,  ///< BSDF sampling only: the default
  /// Passes of doubling sample counts, each sampling with what the previous one learned
  /// (one-sample MIS with BSDF sampling, half and half) at diffuse and rough vertices. Still
  /// unbiased and the same bits whatever the thread count; a resumed render or a sample range
  /// learns its own guide from its own samples.
  kOn,
};
Guiding parse_guiding(std::string_view name);  ///< "off" | "on"
std::string_view guiding_name(Guiding guiding);

/// The reconstruction filter, importance-sampled: every sample has weight 1 and lands at
/// an offset drawn from the filter, so pixels are independent (no splatting) and sample
/// ranges merge exactly.
enum class PixelFilter {
  kBox,   ///< width 1 pixel (what an unfiltered rasteriser computes with supersampling)
  kTent,  ///< triangle of radius 1 pixel (width 2); the default
};
/// The filter named `name` (one of pixel_filter_names()); an Error for any other name.
PixelFilter parse_pixel_filter(std::string_view name);
std::string_view pixel_filter_name(PixelFilter filter);
/// Every filter's name, the default first.
std::vector<std::string> pixel_filter_names();

/// A render's settings. The defaults are the product's, and `pbrkit render --renderer path`
/// takes its option defaults from here: a ground-truth render (up to 1024 spp, adaptive
/// sampling at noise 0.02, 24 bounces, the tent filter).
struct PathTracerSettings {
  int width = 512;
  int height = 512;

  // --- stopping rules -----------------------------------------------------------------
  /// Samples per pixel: the render ends when every pixel has `spp` samples (or has
  /// converged, or the time is up).
  std::uint32_t spp = 1024;
  /// Render only samples [sample_begin, sample_end) of each pixel's sequence
  /// (sample_end = 0: up to spp). Used by --sample-range to split a render over machines.
  std::uint32_t sample_begin = 0;
  std::uint32_t sample_end = 0;
  /// Wall-clock limit in seconds (0: none). The result holds what was rendered in time.
  double time_limit = 0.0;
  /// Adaptive sampling (0: off). A pixel stops receiving samples once its relative error,
  /// estimated from two interleaved half buffers as Cycles does, is below this.
  float noise_threshold = 0.02f;
  /// Samples every pixel receives before the noise test may stop it.
  std::uint32_t min_spp = 16;

  // --- light transport ----------------------------------------------------------------
  /// Surface interactions that gather light. 1 = direct lighting only (camera ray, one
  /// light sample and one BSDF sample at the first hit, no further bounces); 0 = only
  /// emission seen directly. 24 keeps every built-in scene's mean within 1% of a 64-bounce
  /// render (README, "Bounces": a filled tumbler needs many, 8 left `liquid` 6% dark) and
  /// costs opaque scenes nothing measurable, Russian roulette ending their paths first.
  int max_bounces = 24;
  /// Russian roulette starts after this many bounces.
  int rr_start = 3;
  LightStrategy strategy = LightStrategy::kMis;
  /// How a light is chosen for next-event estimation (both are unbiased; with a single
  /// light they give bit-identical images).
  LightSamplerKind light_sampler = LightSamplerKind::kBvh;
  /// Path guiding (Guiding): off by default (BENCHMARKS.md, "Path guiding", says why).
  Guiding guiding = Guiding::kOff;
  /// With guiding, the probability that a guided vertex samples its BSDF rather than the
  /// guide: negative (the default) learns it per region (docs/MODEL.md, "Path guiding"); a
  /// value in (0, 1] fixes it everywhere (Mueller et al. 2017 fix it at 0.5).
  float guiding_bsdf_fraction = -1.0f;
  BrdfOptions brdf;
  PixelFilter filter = PixelFilter::kTent;
  /// Show the environment to camera rays (false: black background, light still counts).
  bool env_visible = true;
  /// Texture level of detail from ray cones (Akenine-Moller et al., "Improved Shader and
  /// Texture Level of Detail Using Ray Cones", JCGT 2021): lookups are filtered to the
  /// pixel's footprint, through specular bounces (false: every lookup reads level 0).
  bool texture_lod = true;

  // --- motion blur --------------------------------------------------------------------
  /// The camera's shutter over one of the scene's animations (scene/pose.h), the truth that
  /// raster renderers approximate: each camera path samples a time in [open, close]
  /// (seconds of the animation) and every ray of the path sees the scene at that time;
  /// moving geometry is built at `steps` times across the shutter and interpolated between
  /// them. `animation` -1: no motion blur. The scene should be posed at the shutter's centre:
  /// its cameras and lights stay where the scene has them, and lights on moving geometry are
  /// sampled there.
  struct Shutter {
    int animation = -1;
    float open = 0.0f;
    float close = 0.0f;
    int steps = 9;
  };
  Shutter shutter;

  // --- execution ----------------------------------------------------------------------
  std::uint32_t seed = 0;
  int threads = 0;  ///< 0: all hardware threads
  /// Set by the caller (e.g. a signal handler) to stop early; polled between tiles.
  const std::atomic<bool>* stop = nullptr;
  /// When set, `checkpoint` is called (from the calling thread) with a snapshot every
  /// `checkpoint_interval` seconds (0: never) at a pass boundary, so long renders can be
  /// resumed.
  double checkpoint_interval = 60.0;
  std::function<void(const Film&)> checkpoint;
  /// Continue from this state (a checkpoint of the same scene and settings) instead of
  /// starting empty; the final result equals an uninterrupted render.
  const Film* resume = nullptr;
};

struct PathTracerStats {
  double render_seconds = 0.0;  ///< the sampling loop only (no loading, no BVH build)
  double build_seconds = 0.0;   ///< set-up: BVH build, lights, BRDF tables (first render)
  double bvh_seconds = 0.0;     ///< of which the Embree BVH build
  std::uint64_t samples = 0;    ///< camera samples taken in this call
  std::uint64_t rays = 0;       ///< rays traced in this call (camera, bounce, shadow)
  bool stopped = false;         ///< stopped early (flag, callback or time limit)
  bool complete = false;        ///< every pixel reached its target or converged
  double noise = 0.0;           ///< mean per-pixel noise estimate (0 when unknown)
  /// Camera samples whose radiance came out NaN or infinite in this call: each was replaced
  /// by 0 (so the image stays finite, a little darker). A correct integrator makes none;
  /// render_path warns when there are any, and the film carries the count into its EXRs.
  std::uint64_t non_finite_samples = 0;
  /// Camera paths in this call that entered more nested volumes than the integrator tracks
  /// (kMaxNestedVolumes): the innermost ones were not entered. Warned about, with the limit.
  std::uint64_t medium_overflows = 0;
  /// Path guiding (settings.guiding): the guide's bytes at the end (both trees and the
  /// accumulators), its regions and directional nodes, the regions that sampled from their
  /// guide in the last pass (the others' BSDF share was 1: their guide did not pay), the passes it
  /// learned from, and the seconds spent building it between passes (the recording and sampling in
  /// the paths are in render_seconds).
  std::size_t guide_bytes = 0;
  std::size_t guide_regions = 0, guide_nodes = 0, guide_guided_regions = 0;
  int guide_passes = 0;
  double guide_seconds = 0.0;
};

/// The deepest nesting of volumes (KHR_materials_volume) a path tracks.
inline constexpr int kMaxNestedVolumes = 8;

struct PathTracerResult {
  Film film;    ///< the accumulation buffers (sums and counts): merge/resume input
  Image color;  ///< RGB mean radiance (linear)
  PathTracerStats stats;
};

/// Renders `scene` seen from `camera`, lit by `env` (nullptr: no environment), the
/// scene's KHR_lights_punctual lights and its emissive triangles. `progress` may be empty;
/// it receives the fraction done and a detail line and may return false to stop.
PathTracerResult render_path(const Scene& scene, const Environment* env, const Camera& camera,
                             const PathTracerSettings& settings,
                             const ProgressCallback& progress = {});

}  // namespace pbrkit
