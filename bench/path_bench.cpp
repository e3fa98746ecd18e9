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
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "pbrkit/image/environment.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"

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
  s.max_bounces = 8;
  s.threads = threads;
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
    ->Args({2, 256, 256})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_PathTraceSpheres)
    ->Name("Spheres/threads:1/256x256/32spp")
    ->Args({1, 256, 32})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_PathTraceSpheres)
    ->Name("Spheres/threads:2/256x256/32spp")
    ->Args({2, 256, 32})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
