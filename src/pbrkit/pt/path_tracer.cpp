// render_path (path_tracer.h): the render loop. It schedules the camera samples (passes
// over tiles of ray packets), accumulates them in the film and decides when to stop
// (sample count, adaptive sampling, time limit, stop flag, progress callback), with
// checkpoints between passes. What a sample is worth is the integrator's
// (integrator.h); where it lands in the pixel, the pixel filter's (pixel_filter.h).
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/pt/observed_render.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>

#include <fmt/format.h>
#include <pmmintrin.h>
#include <tbb/blocked_range2d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include "pbrkit/core/energy.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/adaptive_sampling.h"
#include "pbrkit/pt/camera_rays.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/guiding.h"
#include "pbrkit/pt/integrator.h"
#include "pbrkit/pt/lights.h"
#include "pbrkit/pt/pixel_filter.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kTileSize = 16;
// Camera rays go in packets of kPacketSide x kPacketSide pixels (a divisor of kTileSize).
constexpr int kPacketSide = 4;
static_assert(kPacketSide * kPacketSide == SceneGeometry::kPacketSize &&
              kTileSize % kPacketSide == 0);

// Flush denormals to zero in render threads: Embree asks for it (its traversal is slower
// with denormals) and it removes a source of slow paths in shading.
void set_ftz_daz() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

// The pass schedule: pixels are brought to these sample counts in turn, so every pixel
// progresses evenly (useful for time limits and interruption) and the adaptive test runs at
// the same counts in every run (which keeps resumed and split renders identical).
std::uint32_t next_target(std::uint32_t target, std::uint32_t total, std::uint32_t first) {
  if (target == 0) return std::min(total, std::max(first, 1u));
  return std::min(total, target + std::max(1u, target / 2));
}

// The set-up a render needs before its first sample, made in the render's arena: the
// scene's geometry and BVH, its lights, and the BRDF's albedo tables; timed into `stats`.
struct RenderSetup {
  std::unique_ptr<SceneGeometry> geometry;
  std::unique_ptr<LightSet> lights;
  std::unique_ptr<PathGuide> guide;  ///< settings.guiding on (and light that bounces)
};
RenderSetup build_setup(const Scene& scene, const Environment* env,
                        const PathTracerSettings& settings, RayObserver* observer,
                        tbb::task_arena& arena, PathTracerStats& stats) {
  RenderSetup setup;
  const auto build_start = Clock::now();
  arena.execute([&] {
    set_ftz_daz();
    GeometryOptions options;
    ShutterMotion motion;
    if (settings.shutter.animation >= 0) {
      const PathTracerSettings::Shutter& sh = settings.shutter;
      motion = shutter_motion(scene, sh.animation, sh.open, sh.close, sh.steps);
      if (motion.moving()) options.motion = &motion;
    }
    setup.geometry = std::make_unique<SceneGeometry>(scene, options);
    setup.geometry->observe(observer);
    stats.bvh_seconds = std::chrono::duration<double>(Clock::now() - build_start).count();
    setup.lights = std::make_unique<LightSet>(scene, *setup.geometry, env, settings.light_sampler);
    // The BRDF's albedo tables are computed once per process on first use (about 0.15 s);
    // build them here, with the rest of the set-up, rather than inside the sampling loop,
    // where every render thread would wait for the first one to finish them.
    if (settings.max_bounces > 0) EnergyTable::get(direct_geometry(settings.brdf.model));
    // Path guiding learns from scratch in every render (a resumed one and each sample range
    // too): its guide is built from this call's own samples.
    if (settings.guiding == Guiding::kOn && settings.max_bounces > 0) {
      GuideOptions options;
      options.fixed_bsdf_fraction = settings.guiding_bsdf_fraction;
      setup.guide = std::make_unique<PathGuide>(setup.geometry->bounds(), options);
    }
  });
  stats.build_seconds = std::chrono::duration<double>(Clock::now() - build_start).count();
  return setup;
}

// Where the memory goes: what decides how large a scene fits.
void note_memory(const Scene& scene, const SceneGeometry& geometry) {
  std::size_t texture_bytes = 0;
  for (const Texture& t : scene.textures) texture_bytes += t.bytes();
  const GeometryMemory& mem = geometry.memory();
  note(
      "memory: geometry {:.1f} MB, BVH {:.1f} MB{}, textures {:.1f} MB ({} instances, {} of "
      "them of {} shared meshes)",
      double(mem.geometry) * 1e-6, double(mem.bvh) * 1e-6, mem.compact ? " (compact)" : "",
      double(texture_bytes) * 1e-6, geometry.meshes().size(), geometry.instanced(),
      geometry.shared_meshes());
}

// The film the samples go to: the checkpoint to resume, or a new one.
void start_film(Film& film, const PathTracerSettings& settings, std::uint32_t begin) {
  if (settings.resume) {
    film = *settings.resume;
    if (film.width != settings.width || film.height != settings.height)
      fail("resume: the checkpoint is {}x{} but the render is {}x{}", film.width, film.height,
           settings.width, settings.height);
  } else {
    film = Film(settings.width, settings.height);
  }
  film.sample_begin = begin;
  film.seed = settings.seed;
}

// The mean of the pixels' noise estimates (those that have one).
double mean_pixel_noise(const Film& film) {
  double noise = 0.0;
  std::size_t counted = 0;
  for (std::size_t i = 0; i < film.pixel_count(); ++i) {
    const float e = film.pixel_noise(i);
    if (std::isfinite(e)) {
      noise += e;
      ++counted;
    }
  }
  return counted ? noise / double(counted) : 0.0;
}

// Per-thread counts, summed after the render: rays traced, and the camera paths the
// integrator could not represent (PathSample).
struct PathCounts {
  std::uint64_t rays = 0, non_finite = 0, medium_overflows = 0;
};

// The sampling loop of one render over a prepared scene: passes over tiles of ray packets
// until every pixel has its samples or converged, or a stop (flag, time limit, progress
// callback) comes; progress reports, and checkpoints between passes.
class SampleLoop {
 public:
  SampleLoop(const Scene& scene, const RenderSetup& setup, const Camera& camera,
             const PathTracerSettings& settings, const ProgressCallback& progress,
             tbb::task_arena& arena, Film& film, std::uint32_t begin, std::uint32_t total)
      : settings_(settings),
        progress_(progress),
        arena_(arena),
        geometry_(*setup.geometry),
        film_(film),
        begin_(begin),
        total_(total),
        camera_rays_(camera, float(settings.width) / float(settings.height)),
        guide_(setup.guide.get()),
        integrator_(scene, *setup.geometry, *setup.lights, settings,
                    camera_rays_.pixel_cone(settings.height), setup.guide.get()),
        sampler_(settings.seed),
        tiles_x_((settings.width + kTileSize - 1) / kTileSize),
        tiles_y_((settings.height + kTileSize - 1) / kTileSize),
        resumed_non_finite_(film.non_finite_samples),
        resumed_medium_overflows_(film.medium_overflows),
        work_total_(double(film.pixel_count()) * double(total)) {}

  // Runs the passes; true when every pixel got its samples (or converged).
  bool run();
  // The counts of the samples taken, into `stats` (render time, rays, samples, the
  // samples the integrator could not represent), with a warning for the latter.
  void finish(PathTracerStats& stats);

 private:
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  bool should_stop();
  void update_film_counts();
  void pass_statistics();
  void report(bool force);
  void render_pass();
  std::uint64_t render_packet(int bx, int by, PathCounts& counts);
  void checkpoint_if_due();
  bool every_pixel_done() const;

  const PathTracerSettings& settings_;
  const ProgressCallback& progress_;
  tbb::task_arena& arena_;
  const SceneGeometry& geometry_;
  Film& film_;
  const std::uint32_t begin_, total_;
  const CameraRays camera_rays_;
  PathGuide* const guide_;
  const Integrator integrator_;
  const OwenSobolSampler sampler_;
  const int tiles_x_, tiles_y_;
  // The film's counts are those of every sample in it: the resumed film's, plus this
  // call's, brought up to date before each checkpoint and at the end.
  const std::uint64_t resumed_non_finite_, resumed_medium_overflows_;
  const double work_total_;
  const Clock::time_point start_ = Clock::now();
  std::atomic<bool> stop_{false};
  tbb::enumerable_thread_specific<PathCounts> path_counts_;
  // Progress state shared with the worker threads: atomics only (the film itself is read
  // by the reporter only between passes).
  std::atomic<std::uint64_t> samples_taken_{0};
  std::atomic<double> work_done_{0.0};
  std::atomic<double> mean_noise_{0.0};
  std::mutex progress_mutex_;
  double last_progress_ = -1.0;
  double last_checkpoint_ = 0.0;
  std::uint32_t target_ = 0;       // the sample count of the current pass
  std::uint32_t guided_step_ = 1;  // with guiding: the samples per pixel of the next pass
  double guide_seconds_ = 0.0;
};

bool SampleLoop::should_stop() {
  if (stop_.load(std::memory_order_relaxed)) return true;
  if ((settings_.stop && settings_.stop->load(std::memory_order_relaxed)) ||
      (settings_.time_limit > 0.0 && elapsed() >= settings_.time_limit)) {
    stop_ = true;
    return true;
  }
  return false;
}

void SampleLoop::update_film_counts() {
  film_.non_finite_samples = resumed_non_finite_;
  film_.medium_overflows = resumed_medium_overflows_;
  for (const PathCounts& c : path_counts_) {
    film_.non_finite_samples += c.non_finite;
    film_.medium_overflows += c.medium_overflows;
  }
}

// Work done (a stopped pixel counts as finished) and the mean noise estimate.
void SampleLoop::pass_statistics() {
  double done = 0.0;
  for (std::size_t i = 0; i < film_.pixel_count(); ++i)
    done += film_.done[i] > 0.0f ? double(total_) : double(film_.count[i]);
  work_done_ = done;
  mean_noise_ = mean_pixel_noise(film_);
}

void SampleLoop::report(bool force) {
  if (!progress_) return;
  std::lock_guard<std::mutex> lock(progress_mutex_);
  const double now = elapsed();
  if (!force && now - last_progress_ < 0.25) return;
  last_progress_ = now;
  const double rate = now > 0.0 ? double(samples_taken_.load()) / now : 0.0;
  const std::string detail =
      fmt::format("{:.2f} M samples*px/s, noise {:.4f}", rate * 1e-6, mean_noise_.load());
  if (!progress_(std::min(1.0, work_done_.load() / work_total_), detail)) stop_ = true;
}

// One block of kPacketSide x kPacketSide pixels brought to `target_` samples. Camera rays
// are traced as packets of the block's pixels at one sample index (coherent rays: about
// 2.5x Embree's single-ray rate). A packet depends only on (block, index): lanes outside
// the image (repeating the last column or row) or whose pixel needs no sample at this
// index are traced all the same, so every camera ray is intersected in the same packet
// whatever the thread count, sample range or checkpoint, and renders stay bit-identical
// (a lane's hit can depend on the rest of its packet; see intersect_packet).
std::uint64_t SampleLoop::render_packet(int bx, int by, PathCounts& counts) {
  constexpr int kLanes = SceneGeometry::kPacketSize;
  const int width = settings_.width, height = settings_.height;
  std::size_t pixel_of[kLanes];
  int px[kLanes], py[kLanes];
  bool inside[kLanes];
  std::uint32_t first = target_;  // the lowest sample any pixel of the block still needs
  for (int k = 0; k < kLanes; ++k) {
    const int x = bx + k % kPacketSide, y = by + k / kPacketSide;
    inside[k] = x < width && y < height;
    px[k] = std::min(x, width - 1);
    py[k] = std::min(y, height - 1);
    pixel_of[k] = std::size_t(py[k]) * std::size_t(width) + std::size_t(px[k]);
    if (inside[k] && !(film_.done[pixel_of[k]] > 0.0f))
      first = std::min(first, std::uint32_t(film_.count[pixel_of[k]]));
  }
  if (first >= target_) return 0;
  std::optional<OwenSobolPixel> samplers[kLanes];
  for (int k = 0; k < kLanes; ++k) samplers[k].emplace(sampler_, std::uint32_t(pixel_of[k]));
  glm::vec3 origins[kLanes], directions[kLanes];
  float times[kLanes];
  const bool moving = geometry_.moving();
  SceneGeometry::PacketHit hits[kLanes];
  std::uint64_t taken = 0;
  for (std::uint32_t s = first; s < target_; ++s) {
    const std::uint32_t index = begin_ + s;
    for (int k = 0; k < kLanes; ++k) {
      // The pixel filter's block has two dimensions to spare: the third is the shutter time.
      const glm::vec4 block = samplers[k]->sample_block(index, kPixelFilterBlock);
      const glm::vec2 off = sample_pixel_filter(settings_.filter, glm::vec2(block));
      times[k] = moving ? block.z : 0.0f;
      const glm::vec2 ndc((float(px[k]) + 0.5f + off.x) / float(width) * 2.0f - 1.0f,
                          1.0f - (float(py[k]) + 0.5f + off.y) / float(height) * 2.0f);
      const Ray ray = camera_rays_.generate(ndc);
      origins[k] = ray.origin;
      directions[k] = ray.direction;
    }
    geometry_.intersect_packet(origins, directions, hits, moving ? times : nullptr);
    // The paths below are traced one after the other; the cache misses of their first
    // hits' vertex data are started here together, so that they overlap.
    for (int k = 0; k < kLanes; ++k)
      if (hits[k].geom != SceneGeometry::kNoHit) geometry_.prefetch(hits[k].geom, hits[k].prim);
    for (int k = 0; k < kLanes; ++k) {
      const std::size_t i = pixel_of[k];
      if (!inside[k] || film_.done[i] > 0.0f || s < std::uint32_t(film_.count[i])) continue;
      const PathSample ps = integrator_.Li(origins[k], directions[k], hits[k], *samplers[k],
                                           std::uint32_t(i), index, counts.rays, times[k]);
      counts.non_finite += ps.non_finite ? 1 : 0;
      counts.medium_overflows += ps.medium_overflow ? 1 : 0;
      film_.sum[i] += ps.L;
      film_.albedo[i] += ps.albedo;
      film_.normal[i] += ps.normal;
      film_.depth[i] += ps.depth;
      if (in_half_buffer(index)) {
        film_.sum_even[i] += ps.L;
        film_.albedo_even[i] += ps.albedo;
        film_.normal_even[i] += ps.normal;
        film_.depth_even[i] += ps.depth;
      }
      film_.count[i] = float(s + 1);
      ++taken;
    }
  }
  return taken;
}

// Every pixel brought to `target_` samples, tiles in parallel (each tile's packets in
// order); a stop ends it at the next tile.
void SampleLoop::render_pass() {
  arena_.execute([&] {
    pbrkit::parallel_for(tbb::blocked_range2d<int>(0, tiles_y_, 1, 0, tiles_x_, 1),
                         [&](const tbb::blocked_range2d<int>& r) {
                           set_ftz_daz();
                           PathCounts& counts = path_counts_.local();
                           for (int ty = r.rows().begin(); ty < r.rows().end(); ++ty)
                             for (int tx = r.cols().begin(); tx < r.cols().end(); ++tx) {
                               if (should_stop()) return;
                               std::uint64_t tile_samples = 0;
                               const int x1 = std::min(settings_.width, (tx + 1) * kTileSize);
                               const int y1 = std::min(settings_.height, (ty + 1) * kTileSize);
                               for (int by = ty * kTileSize; by < y1; by += kPacketSide)
                                 for (int bx = tx * kTileSize; bx < x1; bx += kPacketSide)
                                   tile_samples += render_packet(bx, by, counts);
                               // Shared counters are touched once per tile, not per sample.
                               samples_taken_.fetch_add(tile_samples, std::memory_order_relaxed);
                               work_done_.fetch_add(double(tile_samples),
                                                    std::memory_order_relaxed);
                               report(false);
                             }
                         });
  });
}

void SampleLoop::checkpoint_if_due() {
  if (!settings_.checkpoint || settings_.checkpoint_interval <= 0.0 ||
      elapsed() - last_checkpoint_ < settings_.checkpoint_interval)
    return;
  update_film_counts();
  settings_.checkpoint(film_);
  last_checkpoint_ = elapsed();
}

// Whether every pixel got its samples (a stop may come after the last tile).
bool SampleLoop::every_pixel_done() const {
  for (std::size_t i = 0; i < film_.pixel_count(); ++i)
    if (!(film_.done[i] > 0.0f || film_.count[i] >= float(total_))) return false;
  return true;
}

bool SampleLoop::run() {
  pass_statistics();
  bool complete = false;
  if (guide_) {
    // Path guiding trains in passes of doubling sample counts (Mueller et al. 2017's
    // "binary doubling": pass k takes 2^k samples per pixel, sampling with what pass k - 1
    // learned) from where this call starts: a resumed film's fewest samples in a pixel
    // still going.
    std::uint32_t start = total_;
    for (std::size_t i = 0; i < film_.pixel_count(); ++i)
      if (!(film_.done[i] > 0.0f)) start = std::min(start, std::uint32_t(film_.count[i]));
    target_ = std::min(start, total_);
  }
  while (!complete && !should_stop()) {
    if (guide_) {
      target_ = std::min(total_, target_ + guided_step_);
      guided_step_ = std::min(guided_step_, 1u << 30) * 2;
    } else {
      target_ = next_target(target_, total_, settings_.min_spp);
    }
    render_pass();
    if (should_stop()) break;
    // The guide learns from the pass (between passes: the paths record into it with integer
    // atomics, read here in a fixed order).
    if (guide_ && target_ < total_) {
      const auto t0 = Clock::now();
      guide_->end_pass();
      guide_seconds_ += std::chrono::duration<double>(Clock::now() - t0).count();
    }
    // Adaptive sampling: pixels whose two half-buffer estimates agree (and their
    // neighbours') stop here.
    stop_converged_pixels(film_, target_, settings_.noise_threshold, settings_.min_spp);
    complete = target_ >= total_;
    pass_statistics();
    if (!complete) checkpoint_if_due();
  }
  if (!complete) complete = every_pixel_done();
  pass_statistics();
  report(true);
  return complete;
}

void SampleLoop::finish(PathTracerStats& stats) {
  stats.render_seconds = elapsed();
  for (const PathCounts& c : path_counts_) {
    stats.rays += c.rays;
    stats.non_finite_samples += c.non_finite;
    stats.medium_overflows += c.medium_overflows;
  }
  update_film_counts();
  // Once per render: what the image could not represent, with the limit it reached.
  if (stats.non_finite_samples > 0)
    warn(
        "path tracer: {} of {} samples had a radiance that was not finite (NaN or infinite) and "
        "were set to 0: the image is darker there; this is a bug, please report it with the "
        "scene",
        stats.non_finite_samples, samples_taken_.load());
  if (stats.medium_overflows > 0)
    warn(
        "path tracer: {} paths entered more than {} nested volumes (the path tracer's "
        "limit); inside the deeper ones they took the enclosing medium's ior and absorption",
        stats.medium_overflows, kMaxNestedVolumes);
  stats.samples = samples_taken_.load();
  if (guide_) {
    stats.guide_bytes = guide_->bytes();
    stats.guide_regions = guide_->region_count();
    stats.guide_guided_regions = guide_->guided_regions();
    stats.guide_nodes = guide_->directional_nodes();
    stats.guide_passes = guide_->passes();
    stats.guide_seconds = guide_seconds_;
  }
}

}  // namespace

PathTracerResult render_path_observed(const Scene& scene, const Environment* env,
                                      const Camera& camera, const PathTracerSettings& settings,
                                      RayObserver* observer, const ProgressCallback& progress) {
  if (settings.width <= 0 || settings.height <= 0)
    fail("render: image size {}x{} is not positive", settings.width, settings.height);
  const std::uint32_t begin = settings.sample_begin;
  const std::uint32_t end = settings.sample_end > 0 ? settings.sample_end : settings.spp;
  if (end <= begin) fail("render: empty sample range {}:{}", begin, end);

  PathTracerResult result;
  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
  const RenderSetup setup = build_setup(scene, env, settings, observer, arena, result.stats);
  note_memory(scene, *setup.geometry);
  start_film(result.film, settings, begin);
  SampleLoop loop(scene, setup, camera, settings, progress, arena, result.film, begin, end - begin);
  const bool complete = loop.run();
  loop.finish(result.stats);
  result.stats.complete = complete;
  result.stats.stopped = !complete;
  result.stats.noise = mean_pixel_noise(result.film);
  if (setup.guide)
    note(
        "memory: path guide {:.1f} MB ({} regions, {} of them sampling their guide in the last "
        "pass, {} directional nodes, learned over {} passes; building it took {:.2f} s of the "
        "render's {:.1f} s)",
        double(result.stats.guide_bytes) * 1e-6, result.stats.guide_regions,
        result.stats.guide_guided_regions, result.stats.guide_nodes, result.stats.guide_passes,
        result.stats.guide_seconds, result.stats.render_seconds);
  result.color = result.film.color();
  return result;
}

PathTracerResult render_path(const Scene& scene, const Environment* env, const Camera& camera,
                             const PathTracerSettings& settings, const ProgressCallback& progress) {
  return render_path_observed(scene, env, camera, settings, nullptr, progress);
}

}  // namespace pbrkit
