// render_path (path_tracer.h): the render loop. It schedules the camera samples (passes
// over tiles of ray packets), accumulates them in the film and decides when to stop
// (sample count, adaptive sampling, time limit, stop flag, progress callback), with
// checkpoints between passes. What a sample is worth is the integrator's
// (integrator.h); where it lands in the pixel, the pixel filter's (pixel_filter.h).
#include "pbrkit/pt/path_tracer.h"

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

}  // namespace

PathTracerResult render_path(const Scene& scene, const Environment* env, const Camera& camera,
                             const PathTracerSettings& settings, const ProgressCallback& progress) {
  if (settings.width <= 0 || settings.height <= 0)
    fail("render: image size {}x{} is not positive", settings.width, settings.height);
  const std::uint32_t begin = settings.sample_begin;
  const std::uint32_t end = settings.sample_end > 0 ? settings.sample_end : settings.spp;
  if (end <= begin) fail("render: empty sample range {}:{}", begin, end);
  const std::uint32_t total = end - begin;

  PathTracerResult result;
  const auto build_start = Clock::now();
  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
  std::unique_ptr<SceneGeometry> geometry;
  std::unique_ptr<LightSet> lights;
  arena.execute([&] {
    set_ftz_daz();
    geometry = std::make_unique<SceneGeometry>(scene);
    geometry->observe(settings.ray_observer);
    result.stats.bvh_seconds = std::chrono::duration<double>(Clock::now() - build_start).count();
    lights = std::make_unique<LightSet>(scene, *geometry, env, settings.light_sampler);
    // The BRDF's albedo tables are computed once per process on first use (about 0.15 s);
    // build them here, with the rest of the set-up, rather than inside the sampling loop,
    // where every render thread would wait for the first one to finish them.
    if (settings.max_bounces > 0) EnergyTable::get(direct_geometry(settings.brdf.model));
  });
  result.stats.build_seconds = std::chrono::duration<double>(Clock::now() - build_start).count();
  {
    std::size_t texture_bytes = 0;
    for (const Texture& t : scene.textures) texture_bytes += t.bytes();
    const GeometryMemory& mem = geometry->memory();
    // Where the memory goes: what decides how large a scene fits.
    note(
        "memory: geometry {:.1f} MB, BVH {:.1f} MB, textures {:.1f} MB ({} instances, {} of "
        "them of {} shared meshes)",
        double(mem.geometry) * 1e-6, double(mem.bvh) * 1e-6, double(texture_bytes) * 1e-6,
        geometry->meshes().size(), geometry->instanced(), geometry->shared_meshes());
  }

  Film& film = result.film;
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

  const CameraRays camera_rays(camera, float(settings.width) / float(settings.height));
  const Integrator integrator(scene, *geometry, *lights, settings,
                              camera_rays.pixel_cone(settings.height));
  const OwenSobolSampler sampler(settings.seed);
  const int tiles_x = (settings.width + kTileSize - 1) / kTileSize;
  const int tiles_y = (settings.height + kTileSize - 1) / kTileSize;

  const auto start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  std::atomic<bool> stop{false};
  auto should_stop = [&] {
    if (stop.load(std::memory_order_relaxed)) return true;
    if ((settings.stop && settings.stop->load(std::memory_order_relaxed)) ||
        (settings.time_limit > 0.0 && elapsed() >= settings.time_limit)) {
      stop = true;
      return true;
    }
    return false;
  };
  // Per-thread counts, summed after the render: rays traced, and the camera paths the
  // integrator could not represent (PathSample).
  struct PathCounts {
    std::uint64_t rays = 0, non_finite = 0, medium_overflows = 0;
  };
  tbb::enumerable_thread_specific<PathCounts> path_counts;
  // The film's counts are those of every sample in it: the resumed film's, plus this call's,
  // brought up to date before each checkpoint and at the end.
  const std::uint64_t resumed_non_finite = film.non_finite_samples;
  const std::uint64_t resumed_medium_overflows = film.medium_overflows;
  auto update_film_counts = [&] {
    film.non_finite_samples = resumed_non_finite;
    film.medium_overflows = resumed_medium_overflows;
    for (const PathCounts& c : path_counts) {
      film.non_finite_samples += c.non_finite;
      film.medium_overflows += c.medium_overflows;
    }
  };
  // Progress state shared with the worker threads: atomics only (the film itself is read
  // by the reporter only between passes).
  std::atomic<std::uint64_t> samples_taken{0};
  std::atomic<double> work_done{0.0};
  std::atomic<double> mean_noise{0.0};
  std::mutex progress_mutex;
  double last_progress = -1.0;
  const double work_total = double(film.pixel_count()) * double(total);
  auto pass_statistics = [&] {
    // Work done (a stopped pixel counts as finished) and the mean noise estimate.
    double done = 0.0, noise = 0.0;
    std::size_t noisy = 0;
    for (std::size_t i = 0; i < film.pixel_count(); ++i) {
      done += film.done[i] > 0.0f ? double(total) : double(film.count[i]);
      const float e = film.pixel_noise(i);
      if (std::isfinite(e)) {
        noise += double(e);
        ++noisy;
      }
    }
    work_done = done;
    mean_noise = noisy ? noise / double(noisy) : 0.0;
  };
  pass_statistics();
  auto report = [&](bool force) {
    if (!progress) return;
    std::lock_guard<std::mutex> lock(progress_mutex);
    const double now = elapsed();
    if (!force && now - last_progress < 0.25) return;
    last_progress = now;
    const double rate = now > 0.0 ? double(samples_taken.load()) / now : 0.0;
    const std::string detail =
        fmt::format("{:.2f} M samples*px/s, noise {:.4f}", rate * 1e-6, mean_noise.load());
    if (!progress(std::min(1.0, work_done.load() / work_total), detail)) stop = true;
  };

  double last_checkpoint = 0.0;
  std::uint32_t target = 0;

  // One block of kPacketSide x kPacketSide pixels brought to `target` samples. Camera rays
  // are traced as packets of the block's pixels at one sample index (coherent rays: about
  // 2.5x Embree's single-ray rate). A packet depends only on (block, index): lanes outside
  // the image (repeating the last column or row) or whose pixel needs no sample at this
  // index are traced all the same, so every camera ray is intersected in the same packet
  // whatever the thread count, sample range or checkpoint, and renders stay bit-identical
  // (a lane's hit can depend on the rest of its packet; see intersect_packet).
  auto render_packet = [&](int bx, int by, PathCounts& counts) -> std::uint64_t {
    constexpr int kLanes = SceneGeometry::kPacketSize;
    std::size_t pixel_of[kLanes];
    int px[kLanes], py[kLanes];
    bool inside[kLanes];
    std::uint32_t first = target;  // the lowest sample any pixel of the block still needs
    for (int k = 0; k < kLanes; ++k) {
      const int x = bx + k % kPacketSide, y = by + k / kPacketSide;
      inside[k] = x < settings.width && y < settings.height;
      px[k] = std::min(x, settings.width - 1);
      py[k] = std::min(y, settings.height - 1);
      pixel_of[k] = std::size_t(py[k]) * std::size_t(settings.width) + std::size_t(px[k]);
      if (inside[k] && !(film.done[pixel_of[k]] > 0.0f))
        first = std::min(first, std::uint32_t(film.count[pixel_of[k]]));
    }
    if (first >= target) return 0;
    std::optional<OwenSobolPixel> samplers[kLanes];
    for (int k = 0; k < kLanes; ++k) samplers[k].emplace(sampler, std::uint32_t(pixel_of[k]));
    glm::vec3 origins[kLanes], directions[kLanes];
    SceneGeometry::PacketHit hits[kLanes];
    std::uint64_t taken = 0;
    for (std::uint32_t s = first; s < target; ++s) {
      const std::uint32_t index = begin + s;
      for (int k = 0; k < kLanes; ++k) {
        const glm::vec2 off = sample_pixel_filter(
            settings.filter, glm::vec2(samplers[k]->sample_block(index, kPixelFilterBlock)));
        const glm::vec2 ndc((float(px[k]) + 0.5f + off.x) / float(settings.width) * 2.0f - 1.0f,
                            1.0f - (float(py[k]) + 0.5f + off.y) / float(settings.height) * 2.0f);
        const Ray ray = camera_rays.generate(ndc);
        origins[k] = ray.origin;
        directions[k] = ray.direction;
      }
      geometry->intersect_packet(origins, directions, hits);
      // The paths below are traced one after the other; the cache misses of their first
      // hits' vertex data are started here together, so that they overlap.
      for (int k = 0; k < kLanes; ++k)
        if (hits[k].geom != SceneGeometry::kNoHit) geometry->prefetch(hits[k].geom, hits[k].prim);
      for (int k = 0; k < kLanes; ++k) {
        const std::size_t i = pixel_of[k];
        if (!inside[k] || film.done[i] > 0.0f || s < std::uint32_t(film.count[i])) continue;
        const PathSample ps = integrator.Li(origins[k], directions[k], hits[k], *samplers[k],
                                            std::uint32_t(i), index, counts.rays);
        counts.non_finite += ps.non_finite ? 1 : 0;
        counts.medium_overflows += ps.medium_overflow ? 1 : 0;
        film.sum[i] += ps.L;
        film.albedo[i] += ps.albedo;
        film.normal[i] += ps.normal;
        film.depth[i] += ps.depth;
        if (in_half_buffer(index)) {
          film.sum_even[i] += ps.L;
          film.albedo_even[i] += ps.albedo;
          film.normal_even[i] += ps.normal;
          film.depth_even[i] += ps.depth;
        }
        film.count[i] = float(s + 1);
        ++taken;
      }
    }
    return taken;
  };

  bool complete = false;
  while (!complete && !should_stop()) {
    target = next_target(target, total, settings.min_spp);
    arena.execute([&] {
      pbrkit::parallel_for(tbb::blocked_range2d<int>(0, tiles_y, 1, 0, tiles_x, 1),
                           [&](const tbb::blocked_range2d<int>& r) {
                             set_ftz_daz();
                             PathCounts& counts = path_counts.local();
                             for (int ty = r.rows().begin(); ty < r.rows().end(); ++ty)
                               for (int tx = r.cols().begin(); tx < r.cols().end(); ++tx) {
                                 if (should_stop()) return;
                                 std::uint64_t tile_samples = 0;
                                 const int x1 = std::min(settings.width, (tx + 1) * kTileSize);
                                 const int y1 = std::min(settings.height, (ty + 1) * kTileSize);
                                 for (int by = ty * kTileSize; by < y1; by += kPacketSide)
                                   for (int bx = tx * kTileSize; bx < x1; bx += kPacketSide)
                                     tile_samples += render_packet(bx, by, counts);
                                 // Shared counters are touched once per tile, not per sample.
                                 samples_taken.fetch_add(tile_samples, std::memory_order_relaxed);
                                 work_done.fetch_add(double(tile_samples),
                                                     std::memory_order_relaxed);
                                 report(false);
                               }
                           });
    });
    if (should_stop()) break;
    // Adaptive sampling: pixels whose two half-buffer estimates agree (and their
    // neighbours') stop here.
    stop_converged_pixels(film, target, settings.noise_threshold, settings.min_spp);
    complete = target >= total;
    pass_statistics();
    if (!complete && settings.checkpoint && settings.checkpoint_interval > 0.0 &&
        elapsed() - last_checkpoint >= settings.checkpoint_interval) {
      update_film_counts();
      settings.checkpoint(film);
      last_checkpoint = elapsed();
    }
  }
  if (!complete) {
    // Complete when every pixel got its samples (a stop may come after the last tile).
    complete = true;
    for (std::size_t i = 0; i < film.pixel_count() && complete; ++i)
      complete = film.done[i] > 0.0f || film.count[i] >= float(total);
  }
  pass_statistics();
  report(true);

  result.stats.render_seconds = elapsed();
  for (const PathCounts& c : path_counts) {
    result.stats.rays += c.rays;
    result.stats.non_finite_samples += c.non_finite;
    result.stats.medium_overflows += c.medium_overflows;
  }
  update_film_counts();
  // Once per render: what the image could not represent, with the limit it reached.
  if (result.stats.non_finite_samples > 0)
    warn(
        "path tracer: {} of {} samples had a radiance that was not finite (NaN or infinite) and "
        "were set to 0: the image is darker there; this is a bug, please report it with the "
        "scene",
        result.stats.non_finite_samples, samples_taken.load());
  if (result.stats.medium_overflows > 0)
    warn(
        "path tracer: {} paths entered more than {} nested volumes (the path tracer's "
        "limit); inside the deeper ones they took the enclosing medium's ior and absorption",
        result.stats.medium_overflows, kMaxNestedVolumes);
  result.stats.samples = samples_taken.load();
  result.stats.complete = complete;
  result.stats.stopped = !complete;
  double noise = 0.0;
  std::size_t counted = 0;
  for (std::size_t i = 0; i < film.pixel_count(); ++i) {
    const float e = film.pixel_noise(i);
    if (std::isfinite(e)) {
      noise += e;
      ++counted;
    }
  }
  result.stats.noise = counted ? noise / double(counted) : 0.0;
  result.color = film.color();
  return result;
}

}  // namespace pbrkit
