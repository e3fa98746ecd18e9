// The path tracer's integrator and its sampling loop. See path_tracer.h for the contract.
#include "pbrkit/pt/path_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <pmmintrin.h>
#include <tbb/blocked_range2d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/camera_rays.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/lights.h"
#include "pbrkit/pt/ray_offset.h"
#include "pbrkit/pt/shading.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

using Clock = std::chrono::steady_clock;
constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr int kTileSize = 16;
// Camera rays go in packets of kPacketSide x kPacketSide pixels (a divisor of kTileSize).
constexpr int kPacketSide = 4;
static_assert(kPacketSide * kPacketSide == SceneGeometry::kPacketSize &&
              kTileSize % kPacketSide == 0);
// Sampler dimensions, drawn as 4D Sobol blocks: block 0 the pixel filter (dims 0-1), then
// two blocks per bounce: (light choice, light point (2), BSDF lobe) and (BSDF direction
// (2), Russian roulette, spare).
constexpr std::uint32_t kFilterBlocks = 1;
constexpr std::uint32_t kBlocksPerBounce = 2;

// Power heuristic with beta = 2 (Veach 1997, eq. 9.13).
inline float power_heuristic(float f, float g) {
  const float f2 = f * f, g2 = g * g;
  if (!std::isfinite(f2)) return 1.0f;
  return f2 + g2 > 0.0f ? f2 / (f2 + g2) : 0.0f;
}

// Inverse CDF of the tent filter of radius 1 (pbrt-v3 TriangleFilter sampling):
// density 1 - |x| on [-1, 1].
inline float sample_tent(float u) {
  // -1 + sqrt(2 u) below 1/2, 1 - sqrt(2 - 2 u) above, with one square root and selects
  // (u is random: a branch here mispredicts half the time).
  const bool low = u < 0.5f;
  const float r = std::sqrt(low ? 2.0f * u : 2.0f - 2.0f * u);
  return low ? r - 1.0f : 1.0f - r;
}

// A uniform float from a hash of its arguments: decisions that need more random numbers
// than the sampler's fixed dimensions (repeated stochastic-transparency tests along one
// ray). Deterministic, so renders stay reproducible. (PCG hash, Jarzynski & Olano 2020.)
// Not inlined: the compiler would otherwise hoist the rounds that depend on the pixel and
// sample only out of the path loop and pay for them on every path, with or without alpha.
[[gnu::noinline]] float hash_float(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                   std::uint32_t d) {
  std::uint32_t h = a * 747796405u + 2891336453u;
  for (std::uint32_t x : {b, c, d}) {
    h ^= x + 0x9e3779b9u + (h << 6) + (h >> 2);
    h = h * 747796405u + 2891336453u;
    h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
    h = (h >> 22u) ^ h;
  }
  return float(h >> 8) * 0x1p-24f;
}

struct PathSample {
  glm::vec3 L{0.0f};
  glm::vec3 albedo{0.0f};
  glm::vec3 normal{0.0f};
  float depth = 0.0f;
};

class Integrator {
 public:
  Integrator(const Scene& scene, const SceneGeometry& geometry, const LightSet& lights,
             const PathTracerSettings& settings)
      : scene_(scene), geometry_(geometry), lights_(lights), settings_(settings) {}

  // One path through pixel `pixel` for sample `index` (Veach's path tracer with NEE and
  // MIS, in pbrt-v4's PathIntegrator form). `rays` counts the rays traced.
  // `sampler` is the pixel's sequence; `primary` the camera ray's intersection.
  PathSample trace(glm::vec3 origin, glm::vec3 direction, const SceneGeometry::PacketHit& primary,
                   OwenSobolPixel& sampler, std::uint32_t pixel, std::uint32_t index,
                   std::uint64_t& rays) const {
    PathSample out;
    glm::vec3 beta(1.0f);
    float prev_pdf = 0.0f;  // BSDF pdf of the direction that led here (for MIS)
    glm::vec3 prev_p(0.0f);
    const EnvironmentSampler* env = lights_.environment_sampler();
    EnvironmentSampler::Location env_at;  // where `direction` meets the map (depth > 0)
    const LightStrategy strategy = settings_.strategy;
    for (int depth = 0;; ++depth) {
      SurfaceHit hit;
      const Material* material = nullptr;
      const bool found = closest_hit(origin, direction, pixel, index, depth, rays, hit, material,
                                     depth == 0 ? &primary : nullptr);
      if (!found) {
        if (env && (depth > 0 || settings_.env_visible)) {
          const bool mis = depth > 0 && strategy == LightStrategy::kMis;
          float env_pdf = 0.0f;
          const glm::vec3 Le =
              env->eval(depth > 0 ? env_at : env->locate(direction), mis ? &env_pdf : nullptr);
          float w = 1.0f;
          if (depth > 0) {
            if (strategy == LightStrategy::kLightOnly) w = 0.0f;
            if (mis) w = power_heuristic(prev_pdf, lights_.environment_probability() * env_pdf);
          }
          out.L += beta * Le * w;
        }
        break;
      }
      const glm::vec3 wo = -direction;
      // Double-sided materials shade the side they are seen from; single-sided back
      // faces were culled in closest_hit.
      // (shade_inputs turns the shading normal to the same side.)
      if (glm::dot(hit.ng, wo) < 0.0f) hit.ng = -hit.ng;
      // Emission (glTF emission is seen from the front, or from both sides when
      // double-sided; a culled back face never gets here).
      const glm::vec3 Le = material_emission(scene_, *material, hit);
      if (Le != glm::vec3(0.0f)) {
        float w = 1.0f;
        if (depth > 0) {
          if (strategy == LightStrategy::kLightOnly) w = 0.0f;
          if (strategy == LightStrategy::kMis)
            w = power_heuristic(prev_pdf, lights_.triangle_pdf(hit, prev_p));
        }
        out.L += beta * Le * w;
      }

      ShadingInputs in = shade_inputs(scene_, *material, hit);
      // A shading normal facing away from the viewer (interpolation or normal maps at
      // silhouettes) would make the BRDF zero; tilt it just enough towards wo.
      const float ndotv = glm::dot(in.ns, wo);
      if (ndotv < 1e-4f) in.ns = glm::normalize(in.ns + (1e-4f - ndotv) * wo);
      if (depth == 0) {
        out.albedo = in.base_color;
        out.normal = in.ns * 0.5f + 0.5f;
        out.depth = hit.t;
      }
      if (depth >= settings_.max_bounces) break;

      const Frame frame(in.ns);
      const glm::vec3 wo_local = frame.to_local(wo);
      const BoundBrdf brdf =
          Brdf(in.base_color, in.metallic, in.roughness, settings_.brdf).at(wo_local);
      const std::uint32_t block = kFilterBlocks + std::uint32_t(depth) * kBlocksPerBounce;
      const glm::vec4 u_nee = sampler.sample_block(index, block);
      const glm::vec4 u_bsdf = sampler.sample_block(index, block + 1);

      // The work below is ordered for the memory system, not by the estimator: the light
      // sample first (the environment's tables miss the caches, and the BSDF sampling that
      // follows does not wait for them), then the BSDF sample that continues the path, so
      // that the environment texels a miss of the next ray would read are prefetched
      // while the shadow ray is traced. Every value is what the plain order gives.

      // Next-event estimation: one light sample (delta lights always; area lights and the
      // environment unless BSDF sampling alone is asked for).
      LightSample ls;
      // (The light choice needs no random number when there is a single light.)
      const float u_light = lights_.size() > 1 ? u_nee.x : 0.5f;
      const glm::vec2 u_point(u_nee.y, u_nee.z);
      const bool light_sampled = lights_.sample(hit.p, u_light, u_point, ls);

      // Continue the path by sampling the BRDF (visible-normal GGX or cosine), then
      // Russian roulette (pbrt-v4): survive with probability max(beta), at most 1.
      const float u_lobe = u_nee.w;
      const glm::vec2 u_dir(u_bsdf.x, u_bsdf.y);
      const BrdfSample bs = brdf.sample(u_lobe, u_dir);
      bool next = bs.valid;
      glm::vec3 wi(0.0f), beta_next(0.0f);
      if (next) {
        wi = frame.to_world(bs.wi);
        // Reflection only: a direction below the geometric surface would leak light.
        next = glm::dot(wi, hit.ng) > 0.0f;
      }
      if (next) {
        beta_next = beta * bs.weight;
        if (depth + 1 >= settings_.rr_start) {
          const float q = std::max(beta_next.x, std::max(beta_next.y, beta_next.z));
          if (!(q > 0.0f) || (q < 1.0f && u_bsdf.z >= q))
            next = false;
          else if (q < 1.0f)
            beta_next /= q;
        }
      }
      if (next && env) {
        env_at = env->locate(wi);
        env->prefetch(env_at);
      }

      if (light_sampled && (ls.delta || strategy != LightStrategy::kBsdfOnly) &&
          ls.Li != glm::vec3(0.0f) && glm::dot(ls.wi, hit.ng) > 0.0f) {
        const glm::vec3 wi_local = frame.to_local(ls.wi);
        const bool mis = !ls.delta && strategy == LightStrategy::kMis;
        float bsdf_pdf = 0.0f;
        const glm::vec3 f =
            brdf.eval(wi_local, mis ? &bsdf_pdf : nullptr) * std::max(wi_local.z, 0.0f);
        if (f != glm::vec3(0.0f)) {
          float w = 1.0f;
          if (mis) w = power_heuristic(ls.pdf, bsdf_pdf);
          const glm::vec3 tr = transmittance(hit, ls, pixel, index, depth, rays);
          out.L += beta * f * ls.Li * tr * (w / ls.pdf);
        }
      }

      if (!next) break;
      beta = beta_next;
      prev_pdf = bs.pdf;
      prev_p = hit.p;
      origin = offset_ray_origin(hit.p, hit.ng);
      direction = wi;
    }
    if (!std::isfinite(out.L.x + out.L.y + out.L.z)) out.L = glm::vec3(0.0f);
    return out;
  }

 private:
  // Closest hit, skipping culled back faces, alpha-masked and stochastically transparent
  // surfaces (glTF alphaMode MASK: alpha < cutoff is a hole; BLEND: transparent with
  // probability 1 - alpha, an unbiased stand-in for blending).
  // `first`, when given, is the intersection of the first pass (from a packet).
  bool closest_hit(glm::vec3& origin, glm::vec3 direction, std::uint32_t pixel, std::uint32_t index,
                   int depth, std::uint64_t& rays, SurfaceHit& hit, const Material*& material,
                   const SceneGeometry::PacketHit* first = nullptr) const {
    for (std::uint32_t pass = 0; pass < 256; ++pass) {
      std::uint32_t geom = 0, prim = 0;
      float t = 0.0f, u = 0.0f, v = 0.0f;
      ++rays;
      if (pass == 0 && first) {
        if (first->geom == SceneGeometry::kNoHit) return false;
        geom = first->geom;
        prim = first->prim;
        t = first->t;
        u = first->u;
        v = first->v;
      } else if (!geometry_.intersect(origin, direction, kInfinity, 0xffffffffu, geom, prim, t, u,
                                      v)) {
        return false;
      }
      hit = geometry_.resolve(geom, prim, t, u, v);
      const WorldMesh& wm = geometry_.meshes()[geom];
      material = wm.material;
      bool skip = !material->double_sided && glm::dot(hit.ng, direction) > 0.0f;
      if (!skip && wm.has_alpha) {
        const float alpha = material_alpha(scene_, *material, hit);
        if (material->alpha_mode == AlphaMode::kMask)
          skip = alpha < material->alpha_cutoff;
        else
          skip = hash_float(pixel, index, std::uint32_t(depth), pass) >= alpha;
      }
      if (!skip) return true;
      origin = offset_ray_origin(hit.p, glm::dot(hit.ng, direction) > 0.0f ? hit.ng : -hit.ng);
    }
    return false;
  }

  // Visibility of a light sample: 0 or 1 through opaque geometry; through alpha-tested
  // and blended surfaces the expected transmittance (MASK: 0 or 1, BLEND: 1 - alpha).
  glm::vec3 transmittance(const SurfaceHit& hit, const LightSample& ls, std::uint32_t,
                          std::uint32_t, int, std::uint64_t& rays) const {
    const glm::vec3 o = offset_ray_origin(hit.p, hit.ng);
    float tfar;
    if (ls.infinite) {
      tfar = kInfinity;
    } else {
      // Stop just short of the light point (offset towards us for area lights).
      const glm::vec3 target =
          ls.delta ? ls.light_point : offset_ray_origin(ls.light_point, ls.light_normal);
      tfar = glm::length(target - o) * (1.0f - 1e-4f);
    }
    ++rays;
    if (geometry_.occluded(o, ls.wi, tfar)) return glm::vec3(0.0f);
    if (!geometry_.has_alpha()) return glm::vec3(1.0f);
    float tr = 1.0f;
    glm::vec3 origin = o;
    float remaining = tfar;
    for (int pass = 0; pass < 256 && tr > 0.0f; ++pass) {
      std::uint32_t geom = 0, prim = 0;
      float t = 0.0f, u = 0.0f, v = 0.0f;
      ++rays;
      if (!geometry_.intersect(origin, ls.wi, remaining, kMaskAlpha, geom, prim, t, u, v)) break;
      const SurfaceHit h = geometry_.resolve(geom, prim, t, u, v);
      const Material& m = *geometry_.meshes()[geom].material;
      const float alpha = material_alpha(scene_, m, h);
      if (m.alpha_mode == AlphaMode::kMask)
        tr *= alpha < m.alpha_cutoff ? 1.0f : 0.0f;
      else
        tr *= 1.0f - saturate(alpha);
      const glm::vec3 next = offset_ray_origin(h.p, glm::dot(h.ng, ls.wi) > 0.0f ? h.ng : -h.ng);
      if (std::isfinite(remaining)) remaining -= glm::length(next - origin);
      origin = next;
      if (!(remaining > 0.0f)) break;
    }
    return glm::vec3(tr);
  }

  const Scene& scene_;
  const SceneGeometry& geometry_;
  const LightSet& lights_;
  const PathTracerSettings& settings_;
};

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
    lights = std::make_unique<LightSet>(scene, *geometry, env);
    // The BRDF's albedo tables are computed once per process on first use (about 0.15 s);
    // build them here, with the rest of the set-up, rather than inside the sampling loop,
    // where every render thread would wait for the first one to finish them.
    if (settings.max_bounces > 0) EnergyTable::get(direct_geometry(settings.brdf.model));
  });
  result.stats.build_seconds = std::chrono::duration<double>(Clock::now() - build_start).count();

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

  const Integrator integrator(scene, *geometry, *lights, settings);
  const OwenSobolSampler sampler(settings.seed);
  const CameraRays camera_rays(camera, float(settings.width) / float(settings.height));
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
  tbb::enumerable_thread_specific<std::uint64_t> ray_counts(0);
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
  auto render_packet = [&](int bx, int by, std::uint64_t& rays) -> std::uint64_t {
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
        const glm::vec2 uf(samplers[k]->sample_block(index, 0));
        const glm::vec2 off = settings.filter == PixelFilter::kTent
                                  ? glm::vec2(sample_tent(uf.x), sample_tent(uf.y))
                                  : uf - 0.5f;
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
        const PathSample ps = integrator.trace(origins[k], directions[k], hits[k], *samplers[k],
                                               std::uint32_t(i), index, rays);
        film.sum[i] += ps.L;
        if ((index & 1u) == 0u) film.sum_even[i] += ps.L;
        film.albedo[i] += ps.albedo;
        film.normal[i] += ps.normal;
        film.depth[i] += ps.depth;
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
      tbb::parallel_for(tbb::blocked_range2d<int>(0, tiles_y, 1, 0, tiles_x, 1),
                        [&](const tbb::blocked_range2d<int>& r) {
                          set_ftz_daz();
                          std::uint64_t& rays = ray_counts.local();
                          for (int ty = r.rows().begin(); ty < r.rows().end(); ++ty)
                            for (int tx = r.cols().begin(); tx < r.cols().end(); ++tx) {
                              if (should_stop()) return;
                              std::uint64_t tile_samples = 0;
                              const int x1 = std::min(settings.width, (tx + 1) * kTileSize);
                              const int y1 = std::min(settings.height, (ty + 1) * kTileSize);
                              for (int by = ty * kTileSize; by < y1; by += kPacketSide)
                                for (int bx = tx * kTileSize; bx < x1; bx += kPacketSide)
                                  tile_samples += render_packet(bx, by, rays);
                              // Shared counters are touched once per tile, not per sample.
                              samples_taken.fetch_add(tile_samples, std::memory_order_relaxed);
                              work_done.fetch_add(double(tile_samples), std::memory_order_relaxed);
                              report(false);
                            }
                        });
    });
    if (should_stop()) break;
    // Adaptive sampling: pixels whose two half-buffer estimates agree stop here. As in
    // Cycles (adaptive_sampling_filter_x/y), a pixel only stops when its 3x3 neighbours
    // agree too: a pixel whose few samples all missed a small bright light looks
    // "converged" at 0, and its noisier neighbours keep it going.
    if (settings.noise_threshold > 0.0f && target >= settings.min_spp) {
      const int w = settings.width, h = settings.height;
      std::vector<std::uint8_t> converged(film.pixel_count(), 0);
      for (std::size_t i = 0; i < film.pixel_count(); ++i)
        converged[i] = film.done[i] > 0.0f || (film.count[i] >= float(target) &&
                                               film.pixel_noise(i) < settings.noise_threshold);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const std::size_t i = std::size_t(y) * w + x;
          if (film.done[i] > 0.0f || !converged[i]) continue;
          bool all = true;
          for (int dy = -1; dy <= 1 && all; ++dy)
            for (int dx = -1; dx <= 1 && all; ++dx) {
              const int xx = x + dx, yy = y + dy;
              if (xx >= 0 && xx < w && yy >= 0 && yy < h)
                all = converged[std::size_t(yy) * w + xx] != 0;
            }
          if (all) film.done[i] = 1.0f;
        }
    }
    complete = target >= total;
    pass_statistics();
    if (!complete && settings.checkpoint && settings.checkpoint_interval > 0.0 &&
        elapsed() - last_checkpoint >= settings.checkpoint_interval) {
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
  for (auto c : ray_counts) result.stats.rays += c;
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
