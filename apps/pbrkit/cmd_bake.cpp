// pbrkit bake: image-based-lighting precomputation (Karis 2013 split sum). A thin shell over
// libpbrkit's ibl module (bake.h, bake_output.h), as Filament's cmgen sits over libs/ibl.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "commands.h"
#include "pbrkit/core/color.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/ibl/bake_output.h"
#include "pbrkit/ibl/brdf_lut.h"
#include "pbrkit/ibl/prefilter_validation.h"
#include "pbrkit/ibl/roughness_mapping.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/progress.h"

namespace pbrkit::cli {

namespace {

// The flags that set the BakeOptions fields the library range-checks, in --help order.
struct BakeFlag {
  int BakeOptions::*field;
  const char* name;
  const char* help;
};
constexpr BakeFlag kBakeFlags[] = {
    {&BakeOptions::face_size, "--size", "specular cube face size (power of two)"},
    {&BakeOptions::min_face_size, "--min-size", "smallest specular mip face size (power of two)"},
    {&BakeOptions::samples, "--samples", "GGX samples per texel (Hammersley)"},
    {&BakeOptions::irradiance_size, "--irradiance-size", "irradiance cube face size"},
    {&BakeOptions::lut_size, "--lut-size", "BRDF LUT size (square)"},
};

// Fails naming the flag whose value the bake cannot use ("--size: must be a power of two
// ..."); the library's own check (check_bake_options) names the BakeOptions field instead.
void check_bake_flags(const BakeOptions& options) {
  const auto problem = find_bake_options_problem(options);
  if (!problem) return;
  for (const BakeFlag& flag : kBakeFlags)
    if (flag.field == problem->field) fail("{}: {}", flag.name, problem->message);
  check_bake_options(options);  // a field no flag sets
}

struct BakeCommandOptions {
  std::string input;
  std::string output;
  BakeOptions bake;
  std::string mapping = "linear";
  std::string model = "reference";
  float rotation = 0.0f;
  float intensity = 1.0f;
  bool float32 = false;
  bool no_exr = false;
  bool no_previews = false;
  bool no_fis = false;
  bool no_quadrature = false;
  float exposure = 0.0f;
  std::string tonemap = "pbr-neutral";
  bool validate = false;
  int validate_per_face = 4;
};

void run_bake(const BakeCommandOptions& o) {
  using Clock = std::chrono::steady_clock;
  const auto t_start = Clock::now();
  BakeOptions options = o.bake;
  options.mapping = parse_roughness_mapping(o.mapping);
  options.model = parse_brdf_model(o.model);
  options.filtered_importance_sampling = !o.no_fis;
  options.quadrature_for_rough_levels = !o.no_quadrature;
  check_bake_flags(options);
  BakeOutputOptions out;
  out.float32 = o.float32;
  out.exr = !o.no_exr;
  out.previews = !o.no_previews;
  out.preview = {o.exposure, parse_tone_mapper(o.tonemap)};
  // Fail on an unusable output directory before spending the bake's time.
  check_output_directory(o.output);

  const Environment env = Environment::load(o.input, o.rotation, o.intensity);
  const double load_s = std::chrono::duration<double>(Clock::now() - t_start).count();

  BakeRecord record;
  record.environment = &env;
  record.options = options;
  BakeResult result;
  {
    ProgressBar bar("bake");
    result = bake_environment(env, options, bar.callback());
    bar.finish();
  }
  // Both LUTs are written; bake_environment made the one of options.model.
  const auto t_lut = Clock::now();
  const BrdfModel other =
      options.model == BrdfModel::kReference ? BrdfModel::kClassic : BrdfModel::kReference;
  Image other_lut = compute_brdf_lut(other, options.lut_size);
  record.lut_both_s =
      result.timings.lut_s + std::chrono::duration<double>(Clock::now() - t_lut).count();
  record.lut_reference = options.model == BrdfModel::kReference ? result.lut : other_lut;
  record.lut_classic = options.model == BrdfModel::kClassic ? result.lut : other_lut;

  if (o.validate) {
    record.validation =
        validate_prefilter(env, result.specular, options.mapping, o.validate_per_face);
    std::printf("validation: prefiltered texels vs brute-force quadrature over %s (%dx%d)\n",
                env.source.c_str(), env.map.width, env.map.height);
    std::printf("%6s %6s %10s %10s %12s %12s\n", "level", "size", "roughness", "directions",
                "mean rel.", "max rel.");
    for (const PrefilterError& e : record.validation)
      std::printf("%6d %6d %10.3f %10d %11.3f%% %11.3f%%\n", e.level, result.specular.size(e.level),
                  e.roughness, e.directions, 100.0 * e.mean_relative, 100.0 * e.max_relative);
    std::fflush(stdout);
  }

  const auto t_write = Clock::now();
  const auto files = write_bake_outputs(o.output, result, record, out);
  const double write_s = std::chrono::duration<double>(Clock::now() - t_write).count();
  const double total_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  const BakeTimings& t = result.timings;
  std::fprintf(stderr,
               "bake: load %.2f s, cube %.2f s, specular %.2f s (%d levels, %d px), irradiance "
               "%.2f s, SH %.3f s, LUTs %.2f s, sheen %.2f s (%d levels, %d px), write %.2f s; "
               "total %.2f s\n"
               "bake: wrote %zu files to %s\n",
               load_s, t.cube_s, t.specular_s, result.specular.levels(), options.face_size,
               t.irradiance_s, t.sh_s, record.lut_both_s, t.sheen_s, result.sheen.levels(),
               result.sheen.size(0), write_s, total_s, files.size(), o.output.c_str());
}

}  // namespace

void register_bake_command(CLI::App& app) {
  auto o = std::make_shared<BakeCommandOptions>();
  auto* cmd = app.add_subcommand(
      "bake",
      "Precompute image-based lighting from an equirectangular environment (Karis 2013 split "
      "sum): GGX-prefiltered specular cubemap mips, diffuse irradiance (cube + SH9), BRDF "
      "LUTs for both models; KTX2 + EXR + PNG previews + manifest.json. Input limit: 16384 x "
      "8192 pixels, 2:1 aspect; negative/NaN/Inf pixels are set to 0 and counted.");
  cmd->add_option("env", o->input, "environment map (.exr or .hdr, equirectangular 2:1)")
      ->required();
  cmd->add_option("-o,--output", o->output, "output directory (created if needed)")->required();
  for (const BakeFlag& flag : kBakeFlags)
    cmd->add_option(flag.name, o->bake.*flag.field, flag.help)->capture_default_str();
  cmd->add_option("--roughness-mapping", o->mapping,
                  "mip level -> roughness: linear (roughness = level / (levels - 1), the "
                  "Khronos sample viewer's and UE4's)")
      ->check(CLI::IsMember({"linear"}))
      ->capture_default_str();
  cmd->add_option("--model", o->model,
                  "G used by the BRDF LUT in BakeResult (both LUTs are written)")
      ->check(CLI::IsMember(brdf_model_names()))
      ->capture_default_str();
  cmd->add_option("--rotation", o->rotation,
                  "environment rotation about +Y in degrees (counter-clockwise from above)")
      ->capture_default_str();
  cmd->add_option("--intensity", o->intensity, "environment radiance scale")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag("--float32", o->float32, "write cubemaps as RGBA32F KTX2 (default RGBA16F)");
  cmd->add_flag("--no-exr", o->no_exr, "skip the EXR crosses");
  cmd->add_flag("--no-previews", o->no_previews, "skip the PNG previews");
  cmd->add_flag("--no-fis", o->no_fis, "point-sample the source (no filtered importance sampling)");
  cmd->add_flag("--no-quadrature", o->no_quadrature,
                "importance-sample every level (no direct quadrature for small rough levels)");
  cmd->add_option("--exposure", o->exposure, "preview exposure in EV")->capture_default_str();
  cmd->add_option("--tonemap", o->tonemap, "preview tone mapper")
      ->check(CLI::IsMember(tone_mapper_names()))
      ->capture_default_str();
  cmd->add_flag("--validate", o->validate,
                "compare prefiltered texels with a brute-force quadrature and print the error "
                "table by roughness (also stored in manifest.json)");
  cmd->add_option("--validate-directions", o->validate_per_face,
                  "texels per face and level checked by --validate")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->callback([o] { run_bake(*o); });
}

}  // namespace pbrkit::cli
