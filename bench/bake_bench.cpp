// The IBL bake of data/env/studio.exr at the settings (256 px faces, full mip chain
// to 8 px, 1024 samples, SH9, 32 px irradiance cube, 128x128 LUT for both models) on 1 and
// 2 threads, with the time of every stage as counters. Figures go to BENCHMARKS.md.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>

#include "pbrkit/ibl/bake.h"
#include "pbrkit/image/environment.h"

namespace {

const pbrkit::Environment& studio() {
  static const pbrkit::Environment env =
      pbrkit::Environment::load(std::string(PBRKIT_DATA_DIR) + "/env/studio.exr");
  return env;
}

void BM_BakeStudio(benchmark::State& state) {
  const int threads = int(state.range(0));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const pbrkit::Environment& env = studio();
  pbrkit::BakeOptions options;  // defaults: 256 px, down to 8 px, 1024 samples, 32 px, 128
  pbrkit::BakeTimings sum;
  double other_lut = 0.0;
  for (auto _ : state) {
    const pbrkit::BakeResult r = pbrkit::bake_environment(env, options);
    const auto t0 = std::chrono::steady_clock::now();
    const pbrkit::Image classic = pbrkit::compute_brdf_lut(pbrkit::BrdfModel::kClassic, 128);
    other_lut += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(classic.data.data());
    benchmark::DoNotOptimize(r.specular.mips.data());
    sum.cube_s += r.timings.cube_s;
    sum.specular_s += r.timings.specular_s;
    sum.irradiance_s += r.timings.irradiance_s;
    sum.sh_s += r.timings.sh_s;
    sum.lut_s += r.timings.lut_s;
  }
  const double n = double(state.iterations());
  state.counters["cube_s"] = sum.cube_s / n;
  state.counters["specular_s"] = sum.specular_s / n;
  state.counters["irradiance_s"] = sum.irradiance_s / n;
  state.counters["sh_s"] = sum.sh_s / n;
  state.counters["lut_2models_s"] = (sum.lut_s + other_lut) / n;
}
BENCHMARK(BM_BakeStudio)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
