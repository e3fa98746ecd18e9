#pragma once
// Image-based lighting precomputation (Karis 2013, "Real Shading in Unreal Engine 4",
// the split-sum approximation), the library behind `pbrkit bake` (as Filament's
// libs/ibl sits behind cmgen):
//   integral f L cos ~= prefiltered(R, roughness) (F0 A + B) + kd baseColor irradiance(n)
#include <optional>
#include <string>
#include <string_view>

#include "pbrkit/core/brdf.h"
#include "pbrkit/ibl/cubemap.h"
#include "pbrkit/ibl/roughness_mapping.h"
#include "pbrkit/ibl/spherical_harmonics.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image.h"
#include "pbrkit/util/progress.h"

namespace pbrkit {

/// Largest BakeOptions::face_size accepted (8192 px faces are 1.6 GB of RGBA floats per
/// chain).
inline constexpr int kMaxFaceSize = 4096;

/// What to bake and how; the defaults are the offline bake of `pbrkit bake`.
struct BakeOptions {
  int face_size = 256;       ///< specular cube, mip 0
  int min_face_size = 8;     ///< the chain stops at this size (inclusive)
  int samples = 1024;        ///< GGX samples per texel (Hammersley)
  int irradiance_size = 32;  ///< diffuse irradiance cube
  int lut_size = 128;        ///< BRDF LUT, lut_size x lut_size over (n.v, roughness)
  RoughnessMapping mapping = RoughnessMapping::kLinear;  ///< roughness of each specular level
  BrdfModel model = BrdfModel::kReference;               ///< the G of BakeResult::lut
  bool filtered_importance_sampling = true;              ///< Colbert & Krivanek 2007
  /// Small levels with roughness >= 0.25 are prefiltered by direct quadrature over a
  /// source level (exact up to the texel-centre rule) where that is cheap; the others by
  /// importance sampling. False: importance sampling everywhere.
  bool quadrature_for_rough_levels = true;
  /// The cost a level may have to be prefiltered by quadrature: output texels x source
  /// texels (x 6 faces each) at most this. 2^32 (~0.7 s on one core): in the default bake
  /// every level of roughness >= 0.25 (0.4 and up), within 0.1% of a brute-force
  /// reference on the peaky studio.exr, where importance sampling missed by up to 3%.
  double quadrature_budget = 0x1p32;
  /// Sheen chain (ibl/sheen_prefilter.h; the GGX chain's sizes and levels): the largest
  /// face its quadrature computes (larger levels are upsampled from it), and the largest
  /// source level it reads. The Charlie lobe of l is a ring tens of degrees wide around R at
  /// every roughness, so small grids suffice (see docs/MODEL.md, "Sheen maps").
  int sheen_grid_size = 32;
  int sheen_source_size = 32;
};

/// A field of BakeOptions whose value the bake cannot use.
struct BakeOptionsProblem {
  int BakeOptions::*field = nullptr;  ///< the field, e.g. &BakeOptions::face_size
  std::string_view name;              ///< the field's name, e.g. "face_size"
  std::string message;  ///< what is required and what it holds, e.g. "must be in 1..1024, got 0"
};

/// The first field of `options` out of its range (face_size, min_face_size, samples,
/// irradiance_size, lut_size, sheen_grid_size, sheen_source_size, in that order), or none. A caller
/// that filled the fields from elsewhere (command-line flags, a file) can report the problem under
/// its own names.
std::optional<BakeOptionsProblem> find_bake_options_problem(const BakeOptions& options);

/// Throws pbrkit::Error "BakeOptions::<field> <message>" for the first problem that
/// find_bake_options_problem() finds; bake_environment() calls it first.
void check_bake_options(const BakeOptions& options);

/// Wall-clock seconds of each stage, and the process CPU seconds (all threads, std::clock)
/// spent during it: on a shared machine the CPU time is the figure that shows what the work
/// costs.
struct BakeTimings {
  double cube_s = 0, specular_s = 0, irradiance_s = 0, sh_s = 0, lut_s = 0, total_s = 0;
  double cube_cpu_s = 0, specular_cpu_s = 0, irradiance_cpu_s = 0, sh_cpu_s = 0, lut_cpu_s = 0,
         total_cpu_s = 0;
  double sheen_s = 0, sheen_cpu_s = 0;  ///< the sheen chain and the sheen LUT
};

/// Everything the bake computes (see bake_environment()).
struct BakeResult {
  Cubemap environment;  ///< the source resampled to a cube with its full box-filtered mip chain
  Cubemap specular;     ///< prefiltered GGX, level i at roughness mip_roughness(i, levels)
  Cubemap irradiance;   ///< diffuse irradiance E(n) (not divided by pi), RGB
  SH9 sh;               ///< irradiance SH (see SH9)
  Image lut;            ///< RGBA over (x: n.v, y: roughness): A, B, E = A+B, E_avg(roughness)
  /// Charlie-prefiltered sheen chain, level i at sheen roughness mip_roughness(i, levels)
  /// (ibl/sheen_prefilter.h); the same sizes and levels as `specular`.
  Cubemap sheen;
  /// RGBA over (x: n.v, y: sheen roughness): DG = E_sheen, E_sheen_avg(r), 0, 1
  /// (ibl/sheen_lut.h), lut_size x lut_size.
  Image sheen_lut;
  BakeTimings timings;
  /// The progress callback stopped the bake (util/progress.h): the stages finished before
  /// the stop are filled (of the specular and sheen chains, the levels finished), the
  /// others are empty.
  bool interrupted = false;
};

/// Runs every stage on `env` (its rotation and intensity applied) with `options` (checked
/// first: check_bake_options()) and times each. `progress` receives the fraction done and
/// the stage's name; it may be empty; when it returns false the bake stops early and
/// returns what it has (BakeResult::interrupted). Throws pbrkit::Error for bad options or
/// an empty map.
BakeResult bake_environment(const Environment& env, const BakeOptions& options,
                            const ProgressCallback& progress = {});

}  // namespace pbrkit
