// The IBL bake of data/env/studio.exr at the settings (256 px faces, full mip chain
// to 8 px, 1024 samples, SH9, 32 px irradiance cube, 128x128 LUT for both models) on 1 and
// 2 threads, with the wall and process CPU time of every stage as counters (*_s and
// *_cpu_s) and, at the end, a summary with the 1 -> 2 thread speed-up. On a shared machine
// only the CPU times are meaningful. Figures go to BENCHMARKS.md.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>

#include "pbrkit/ibl/bake.h"
#include "pbrkit/ibl/brdf_lut.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/util/data_dir.h"

namespace {

const pbrkit::Environment& studio() {
  static const pbrkit::Environment env =
      pbrkit::Environment::load(pbrkit::data_dir() / "env" / "studio.exr");
  return env;
}

double cpu_seconds() {
  return double(std::clock()) / CLOCKS_PER_SEC;
}

struct Run {
  double wall_s = 0, cpu_s = 0;
};
std::map<int, Run>& runs() {  // by thread count, for the summary
  static std::map<int, Run> r;
  return r;
}

void BM_BakeStudio(benchmark::State& state) {
  const int threads = int(state.range(0));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const pbrkit::Environment& env = studio();
  pbrkit::BakeOptions options;  // defaults: 256 px, down to 8 px, 1024 samples, 32 px, 128
  pbrkit::BakeTimings sum;
  double other_lut = 0.0, other_lut_cpu = 0.0;
  Run run;
  for (auto _ : state) {
    const auto w0 = std::chrono::steady_clock::now();
    const double c0 = cpu_seconds();
    const pbrkit::BakeResult r = pbrkit::bake_environment(env, options);
    const auto t0 = std::chrono::steady_clock::now();
    const double tc0 = cpu_seconds();
    const pbrkit::Image classic = pbrkit::compute_brdf_lut(pbrkit::BrdfModel::kClassic, 128);
    const auto t1 = std::chrono::steady_clock::now();
    const double tc1 = cpu_seconds();
    other_lut += std::chrono::duration<double>(t1 - t0).count();
    other_lut_cpu += tc1 - tc0;
    run.wall_s += std::chrono::duration<double>(t1 - w0).count();
    run.cpu_s += tc1 - c0;
    benchmark::DoNotOptimize(classic.data.data());
    benchmark::DoNotOptimize(r.specular.mips.data());
    const pbrkit::BakeTimings& t = r.timings;
    sum.cube_s += t.cube_s, sum.cube_cpu_s += t.cube_cpu_s;
    sum.specular_s += t.specular_s, sum.specular_cpu_s += t.specular_cpu_s;
    sum.irradiance_s += t.irradiance_s, sum.irradiance_cpu_s += t.irradiance_cpu_s;
    sum.sh_s += t.sh_s, sum.sh_cpu_s += t.sh_cpu_s;
    sum.lut_s += t.lut_s, sum.lut_cpu_s += t.lut_cpu_s;
    sum.sheen_s += t.sheen_s, sum.sheen_cpu_s += t.sheen_cpu_s;
  }
  const double n = double(state.iterations());
  state.counters["cube_s"] = sum.cube_s / n;
  state.counters["specular_s"] = sum.specular_s / n;
  state.counters["irradiance_s"] = sum.irradiance_s / n;
  state.counters["sh_s"] = sum.sh_s / n;
  state.counters["lut_2models_s"] = (sum.lut_s + other_lut) / n;
  state.counters["cube_cpu_s"] = sum.cube_cpu_s / n;
  state.counters["specular_cpu_s"] = sum.specular_cpu_s / n;
  state.counters["irradiance_cpu_s"] = sum.irradiance_cpu_s / n;
  state.counters["sh_cpu_s"] = sum.sh_cpu_s / n;
  state.counters["lut_2models_cpu_s"] = (sum.lut_cpu_s + other_lut_cpu) / n;
  state.counters["sheen_s"] = sum.sheen_s / n;  // sheen chain + sheen LUT
  state.counters["sheen_cpu_s"] = sum.sheen_cpu_s / n;
  runs()[threads] = {run.wall_s / n, run.cpu_s / n};
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

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  // The figures: whole bake (both LUTs included) per thread count, and the speed-up.
  for (const auto& [threads, r] : runs())
    std::printf("whole bake, %d thread(s): wall %.3f s, process CPU %.3f s\n", threads, r.wall_s,
                r.cpu_s);
  if (runs().count(1) && runs().count(2) && runs()[2].wall_s > 0.0)
    std::printf("speed-up 1 -> 2 threads (wall): %.2fx\n", runs()[1].wall_s / runs()[2].wall_s);
  return 0;
}
