// Path tracer throughput: the built-in `spheres` scene under the shipped HDRI
// (data/env/city.exr) at 256x256, max 8 bounces, 256 spp, no adaptive stopping.
// Reports samples x pixels per second (sampling loop only, excluding scene loading and the
// BVH build), rays per second (camera + bounce + shadow rays) and the BVH build time.
//
//   build/<dir>/bin/path_bench --benchmark_filter='Spheres/threads:2'
//
// Counters: Msamples_px_per_s, Mrays_per_s, bvh_build_s (setup_s: with the rest of the
// set-up), rays_per_sample, and
// Msamples_px_per_cpu_s / cpu_utilisation (throughput per CPU-second, for loaded machines).
// EmbreeReplay: Embree's raw rate for the very rays of a render (renderer_over_embree is
// the "ray rate against Embree's raw rate for the same mix of rays").
#include <benchmark/benchmark.h>
#include <pmmintrin.h>
#include <sys/resource.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include <chrono>
#include <vector>

#include "pbrkit/image/environment.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/observed_render.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/util/parallel.h"

namespace {

// Process CPU time (all threads), so that throughput per CPU-second can be reported even
// when the shared machine is loaded and wall-clock figures are not representative.
double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void BM_PathTraceSpheres(benchmark::State& state) {
  const int threads = int(state.range(0));
  const int size = int(state.range(1));
  const auto spp = std::uint32_t(state.range(2));
  const pbrkit::Scene scene = pbrkit::builtin_scene("spheres");
  const pbrkit::Environment env = pbrkit::load_environment_or_default("", 0.0f, 1.0f);
  const pbrkit::Camera camera = pbrkit::select_camera(scene, std::nullopt, 1.0f);
  pbrkit::PathTracerSettings s;
  s.width = s.height = size;
  s.spp = spp;
  s.noise_threshold = 0.0f;  // no adaptive stopping (the library's default is on)
  s.max_bounces = 8;
  s.threads = threads;
  // A fourth argument 0 turns compensation off (to compare like with like with renders
  // made without it).
  if (state.range(3) == 0) s.brdf.multiscatter = false;
  double samples = 0, rays = 0, seconds = 0, build = 0, bvh = 0, cpu = 0;
  for (auto _ : state) {
    const double cpu0 = process_cpu_seconds();
    const pbrkit::PathTracerResult r = pbrkit::render_path(scene, &env, camera, s);
    cpu += process_cpu_seconds() - cpu0;
    samples += double(r.stats.samples);
    rays += double(r.stats.rays);
    seconds += r.stats.render_seconds;
    build += r.stats.build_seconds;
    bvh += r.stats.bvh_seconds;
    state.SetIterationTime(r.stats.render_seconds);
  }
  state.counters["Msamples_px_per_s"] = samples / seconds * 1e-6;
  state.counters["Mrays_per_s"] = rays / seconds * 1e-6;
  state.counters["rays_per_sample"] = rays / samples;
  state.counters["bvh_build_s"] = bvh / double(state.iterations());
  // The whole set-up: BVH, lights, and the BRDF's tables in the process's first render.
  state.counters["setup_s"] = build / double(state.iterations());
  // Includes the set-up's CPU time (the BVH and, in the process's first render, the BRDF
  // tables: small against the 256-spp render, not against the 32-spp ones).
  state.counters["Msamples_px_per_cpu_s"] = samples / cpu * 1e-6;
  state.counters["cpu_utilisation"] = cpu / (seconds + build);
}

// threads, resolution, spp. The full benchmark of the issue, and a quick 1-vs-2-thread
// scaling pair at lower spp.
BENCHMARK(BM_PathTraceSpheres)
    ->Name("Spheres/threads:2/256x256/256spp")
    ->Args({2, 256, 256, 1})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_PathTraceSpheres)
    ->Name("Spheres/threads:1/256x256/32spp")
    ->Args({1, 256, 32, 1})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_PathTraceSpheres)
    ->Name("Spheres/threads:2/256x256/32spp")
    ->Args({2, 256, 32, 1})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_PathTraceSpheres)
    ->Name("Spheres/threads:2/256x256/256spp/no-multiscatter")
    ->Args({2, 256, 256, 0})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// Transmission: the built-in `glass` scene (smooth, rough, tinted, thin-walled and dispersive
// glass before a checker backdrop) at 512x512, 2 threads, max 16 bounces (light crosses
// several interfaces). Reports samples x pixels per second and the mean per-pixel relative
// noise after `spp` samples; the time to a mean relative noise of 2% is extrapolated from
// it as t (noise / 0.02)^2 (Monte Carlo noise falls as 1 / sqrt(spp); a full run to 2%
// needs ~1500 spp, about 20 minutes on this machine).
void BM_PathTraceGlass(benchmark::State& state) {
  const auto spp = std::uint32_t(state.range(0));
  const pbrkit::Scene scene = pbrkit::builtin_scene("glass");
  const pbrkit::Environment env = pbrkit::load_environment_or_default("", 0.0f, 1.0f);
  const pbrkit::Camera camera = pbrkit::select_camera(scene, std::nullopt, 1.0f);
  pbrkit::PathTracerSettings s;
  s.width = s.height = 512;
  s.spp = spp;
  s.noise_threshold = 0.0f;
  s.max_bounces = 16;
  s.threads = 2;
  double samples = 0, seconds = 0, noise = 0, cpu = 0;
  for (auto _ : state) {
    const double cpu0 = process_cpu_seconds();
    const pbrkit::PathTracerResult r = pbrkit::render_path(scene, &env, camera, s);
    cpu += process_cpu_seconds() - cpu0;
    samples += double(r.stats.samples);
    seconds += r.stats.render_seconds;
    noise = r.stats.noise;
    state.SetIterationTime(r.stats.render_seconds);
  }
  state.counters["Msamples_px_per_s"] = samples / seconds * 1e-6;
  state.counters["Msamples_px_per_cpu_s"] = samples / cpu * 1e-6;
  state.counters["noise"] = noise;
  const double t = seconds / double(state.iterations());
  state.counters["s_to_2pct_noise"] = t * (noise / 0.02) * (noise / 0.02);
}
BENCHMARK(BM_PathTraceGlass)
    ->Name("Glass/threads:2/512x512/32spp")
    ->Args({32})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// Embree's raw rate for the renderer's own mix of rays (the integrator's target is a ray rate of
// at least 70% of it): a render's every ray query (camera packets, closest-hit bounce rays,
// shadow rays, with their origins, directions, extents and masks) is recorded, then the
// same queries are replayed through the same SceneGeometry calls, with no shading in
// between, on the same number of threads. Replayed back to back, the queries find the BVH
// warmer in the caches than the render does, so the raw rate is an upper bound.
class RayRecorder final : public pbrkit::RayObserver {
 public:
  enum class Kind : std::uint8_t { kPacket, kClosest, kOccluded };
  struct Query {
    glm::vec3 o, d;
    float tfar;
    unsigned mask;
    Kind kind;
    std::uint8_t lane;  // packets: 16 consecutive queries, lanes 0..15
  };
  void packet(const glm::vec3* origins, const glm::vec3* directions) override {
    auto& log = logs_.local();
    for (int k = 0; k < 16; ++k)
      log.push_back({origins[k], directions[k], 0.0f, ~0u, Kind::kPacket, std::uint8_t(k)});
  }
  void closest(glm::vec3 o, glm::vec3 d, float tfar, unsigned mask) override {
    logs_.local().push_back({o, d, tfar, mask, Kind::kClosest, 0});
  }
  void occluded(glm::vec3 o, glm::vec3 d, float tfar) override {
    logs_.local().push_back({o, d, tfar, 0u, Kind::kOccluded, 0});
  }
  std::vector<Query> all() const {
    std::vector<Query> out;
    for (const auto& log : logs_) out.insert(out.end(), log.begin(), log.end());
    return out;
  }

 private:
  tbb::enumerable_thread_specific<std::vector<Query>> logs_;
};

// Replays `queries` on `threads` threads; returns the seconds taken.
double replay(const pbrkit::SceneGeometry& geometry, const std::vector<RayRecorder::Query>& queries,
              int threads) {
  using Kind = RayRecorder::Kind;
  // Chunks of about 4096 queries, never splitting a packet.
  std::vector<std::size_t> bounds{0};
  while (bounds.back() < queries.size()) {
    std::size_t b = std::min(queries.size(), bounds.back() + 4096);
    while (b < queries.size() && queries[b].kind == Kind::kPacket && queries[b].lane != 0) ++b;
    bounds.push_back(b);
  }
  tbb::task_arena arena(threads);
  const auto start = std::chrono::steady_clock::now();
  arena.execute([&] {
    pbrkit::parallel_for(std::size_t(0), bounds.size() - 1, [&](std::size_t c) {
      _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
      _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
      std::uint32_t geom, prim, hits = 0;
      float t, u, v;
      glm::vec3 origins[16], directions[16];
      pbrkit::SceneGeometry::PacketHit packet[16];
      for (std::size_t i = bounds[c]; i < bounds[c + 1]; ++i) {
        const RayRecorder::Query& q = queries[i];
        if (q.kind == Kind::kClosest) {
          hits += geometry.intersect(q.o, q.d, q.tfar, q.mask, geom, prim, t, u, v);
        } else if (q.kind == Kind::kOccluded) {
          hits += geometry.occluded(q.o, q.d, q.tfar);
        } else {
          origins[q.lane] = q.o;
          directions[q.lane] = q.d;
          if (q.lane == 15) {
            geometry.intersect_packet(origins, directions, packet);
            hits += packet[0].geom != pbrkit::SceneGeometry::kNoHit;
          }
        }
      }
      benchmark::DoNotOptimize(hits);
    });
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_EmbreeReplay(benchmark::State& state) {
  const int threads = int(state.range(0));
  const pbrkit::Scene scene = pbrkit::builtin_scene("spheres");
  const pbrkit::Environment env = pbrkit::load_environment_or_default("", 0.0f, 1.0f);
  const pbrkit::Camera camera = pbrkit::select_camera(scene, std::nullopt, 1.0f);
  pbrkit::PathTracerSettings s;
  s.width = s.height = 256;
  s.spp = 32;  // the same mix as 256 spp, and a log of ~4 M queries (128 MB)
  s.noise_threshold = 0.0f;
  s.max_bounces = 8;
  s.threads = threads;
  double render_rays = 0, render_seconds = 0, replay_rays = 0, replay_seconds = 0;
  std::size_t packets = 0, closest = 0, occluded = 0;
  for (auto _ : state) {
    // The renderer's rate, from a render without the recorder.
    const pbrkit::PathTracerResult r = pbrkit::render_path(scene, &env, camera, s);
    render_rays += double(r.stats.rays);
    render_seconds += r.stats.render_seconds;
    RayRecorder recorder;
    pbrkit::render_path_observed(scene, &env, camera, s, &recorder);
    const std::vector<RayRecorder::Query> queries = recorder.all();
    const pbrkit::SceneGeometry geometry(scene);
    replay(geometry, queries, threads);  // warm-up
    const double seconds = replay(geometry, queries, threads);
    replay_rays += double(queries.size());
    replay_seconds += seconds;
    packets = closest = occluded = 0;
    for (const auto& q : queries)
      (q.kind == RayRecorder::Kind::kPacket    ? packets
       : q.kind == RayRecorder::Kind::kClosest ? closest
                                               : occluded)++;
    state.SetIterationTime(seconds);
  }
  const double renderer = render_rays / render_seconds, raw = replay_rays / replay_seconds;
  state.counters["renderer_Mrays_per_s"] = renderer * 1e-6;
  state.counters["embree_Mrays_per_s"] = raw * 1e-6;
  state.counters["renderer_over_embree"] = renderer / raw;
  const double n = double(packets + closest + occluded);
  state.counters["camera_share"] = double(packets) / n;
  state.counters["closest_share"] = double(closest) / n;
  state.counters["shadow_share"] = double(occluded) / n;
}
BENCHMARK(BM_EmbreeReplay)
    ->Name("EmbreeReplay/threads:2/256x256/32spp")
    ->Args({2})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
