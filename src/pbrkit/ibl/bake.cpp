// The IBL bake (Karis 2013 split sum): runs the stages in order (environment_cube.h,
// prefilter.h, spherical_harmonics.h, irradiance_cube.h, brdf_lut.h) and times them. See
// bake.h.
#include "pbrkit/ibl/bake.h"

#include <fmt/format.h>

#include <chrono>
#include <ctime>
#include <optional>
#include <string>

#include "pbrkit/ibl/brdf_lut.h"
#include "pbrkit/ibl/environment_cube.h"
#include "pbrkit/ibl/irradiance_cube.h"
#include "pbrkit/ibl/prefilter.h"
#include "pbrkit/ibl/sheen_lut.h"
#include "pbrkit/ibl/sheen_prefilter.h"
#include "pbrkit/ibl/spherical_harmonics.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Process CPU time (all threads): std::clock on POSIX systems.
double cpu_seconds() {
  return double(std::clock()) / CLOCKS_PER_SEC;
}

// Wall and CPU time of one stage.
struct StageTimer {
  Clock::time_point wall = Clock::now();
  double cpu = cpu_seconds();
  void stop(double& wall_s, double& cpu_s) const {
    wall_s = seconds_since(wall);
    cpu_s = cpu_seconds() - cpu;
  }
};

bool is_power_of_two(int n) {
  return n > 0 && (n & (n - 1)) == 0;
}

}  // namespace

std::optional<BakeOptionsProblem> find_bake_options_problem(const BakeOptions& o) {
  // The messages name neither the field nor a command-line flag: the caller prefixes the
  // name it knows the field by.
  if (!is_power_of_two(o.face_size) || o.face_size > kMaxFaceSize)
    return BakeOptionsProblem{
        &BakeOptions::face_size, "face_size",
        fmt::format("must be a power of two in 1..{}, got {}", kMaxFaceSize, o.face_size)};
  if (!is_power_of_two(o.min_face_size) || o.min_face_size > o.face_size)
    return BakeOptionsProblem{&BakeOptions::min_face_size, "min_face_size",
                              fmt::format("must be a power of two in 1..{} (the face size), got {}",
                                          o.face_size, o.min_face_size)};
  if (o.samples < 1 || o.samples > (1 << 20))
    return BakeOptionsProblem{&BakeOptions::samples, "samples",
                              fmt::format("must be in 1..{}, got {}", 1 << 20, o.samples)};
  if (o.irradiance_size < 1 || o.irradiance_size > 1024)
    return BakeOptionsProblem{&BakeOptions::irradiance_size, "irradiance_size",
                              fmt::format("must be in 1..1024, got {}", o.irradiance_size)};
  if (o.lut_size < 1 || o.lut_size > 4096)
    return BakeOptionsProblem{&BakeOptions::lut_size, "lut_size",
                              fmt::format("must be in 1..4096, got {}", o.lut_size)};
  if (!is_power_of_two(o.sheen_grid_size) || o.sheen_grid_size > kMaxFaceSize)
    return BakeOptionsProblem{
        &BakeOptions::sheen_grid_size, "sheen_grid_size",
        fmt::format("must be a power of two in 1..{}, got {}", kMaxFaceSize, o.sheen_grid_size)};
  if (!is_power_of_two(o.sheen_source_size) || o.sheen_source_size > kMaxFaceSize)
    return BakeOptionsProblem{
        &BakeOptions::sheen_source_size, "sheen_source_size",
        fmt::format("must be a power of two in 1..{}, got {}", kMaxFaceSize, o.sheen_source_size)};
  return std::nullopt;
}

void check_bake_options(const BakeOptions& options) {
  if (const auto problem = find_bake_options_problem(options))
    fail("BakeOptions::{} {}", problem->name, problem->message);
}

BakeResult bake_environment(const Environment& env, const BakeOptions& options,
                            const ProgressCallback& progress) {
  check_bake_options(options);
  if (env.map.empty()) fail("{}: the environment map is empty", env.source);
  BakeResult result;
  // Stopped by `progress` (util/progress.h): the stages done are returned, the rest left
  // empty, and `interrupted` set.
  bool stopped = false;
  auto report = [&](double f, const std::string& detail) {
    if (progress && !stopped && !progress(f, detail)) stopped = true;
    return !stopped;
  };
  // Progress weights: the stages' typical share of the run time.
  auto stage = [&](double begin, double end) -> ProgressCallback {
    if (!progress) return {};
    return [&report, begin, end](double f, const std::string& detail) {
      return report(begin + (end - begin) * f, detail);
    };
  };
  const StageTimer all;
  auto stop_here = [&] {
    all.stop(result.timings.total_s, result.timings.total_cpu_s);
    result.interrupted = true;
    return result;
  };

  StageTimer t;
  result.environment = resample_to_cube(env, options.face_size);
  build_mip_chain(result.environment, 1);
  t.stop(result.timings.cube_s, result.timings.cube_cpu_s);
  if (!report(0.1, "cube")) return stop_here();

  t = StageTimer();
  result.specular = prefilter_specular(result.environment, options, stage(0.1, 0.85));
  t.stop(result.timings.specular_s, result.timings.specular_cpu_s);
  if (stopped) return stop_here();

  t = StageTimer();
  result.sh = project_sh_irradiance(result.environment, 0);
  t.stop(result.timings.sh_s, result.timings.sh_cpu_s);

  t = StageTimer();
  result.irradiance = irradiance_cube(result.environment, options.irradiance_size);
  t.stop(result.timings.irradiance_s, result.timings.irradiance_cpu_s);
  if (!report(0.9, "irradiance")) return stop_here();

  t = StageTimer();
  result.lut = compute_brdf_lut(options.model, options.lut_size);
  t.stop(result.timings.lut_s, result.timings.lut_cpu_s);

  t = StageTimer();
  result.sheen = prefilter_sheen(result.environment, options, stage(0.9, 1.0));
  if (stopped) return stop_here();
  result.sheen_lut = compute_sheen_lut(options.lut_size);
  t.stop(result.timings.sheen_s, result.timings.sheen_cpu_s);
  report(1.0, "done");

  all.stop(result.timings.total_s, result.timings.total_cpu_s);
  return result;
}

}  // namespace pbrkit
