#pragma once
// Image-based lighting precomputation (Karis 2013, "Real Shading in Unreal Engine 4",
// the split-sum approximation), the library behind `pbrkit bake` (as Filament's
// libs/ibl sits behind cmgen):
//   integral f L cos ~= prefiltered(R, roughness) (F0 A + B) + kd baseColor irradiance(n)
#include <array>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "pbrkit/core/brdf.h"
#include "pbrkit/ibl/cubemap.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image.h"
#include "pbrkit/util/progress.h"

namespace pbrkit {

/// How a specular mip level maps to roughness.
enum class RoughnessMapping {
  /// roughness = level / (levels - 1): the Khronos glTF sample viewer's and UE4's mapping.
  kLinear,
};
RoughnessMapping parse_roughness_mapping(std::string_view name);  ///< "linear"
std::string_view roughness_mapping_name(RoughnessMapping mapping);
/// Roughness of mip `level` of a `levels`-level chain.
float mip_roughness(int level, int levels, RoughnessMapping mapping = RoughnessMapping::kLinear);
/// Fractional mip level for `roughness` (the inverse; what shaders compute).
float roughness_lod(float roughness, int levels,
                    RoughnessMapping mapping = RoughnessMapping::kLinear);

struct BakeOptions {
  int face_size = 256;       ///< specular cube, mip 0
  int min_face_size = 8;     ///< the chain stops at this size (inclusive)
  int samples = 1024;        ///< GGX samples per texel (Hammersley)
  int irradiance_size = 32;  ///< diffuse irradiance cube
  int lut_size = 128;        ///< BRDF LUT, lut_size x lut_size over (n.v, roughness)
  RoughnessMapping mapping = RoughnessMapping::kLinear;
  BrdfModel model = BrdfModel::kReference;   ///< the G of the prefilter weights
  bool filtered_importance_sampling = true;  ///< Colbert & Krivanek 2007
  /// Small levels with roughness >= 0.25 are prefiltered by direct quadrature over a
  /// source level (exact up to the texel-centre rule) where that is cheap; the others by
  /// importance sampling. False: importance sampling everywhere.
  bool quadrature_for_rough_levels = true;
  /// The cost a level may have to be prefiltered by quadrature: output texels x source
  /// texels (x 6 faces each) at most this. 2^32 (~0.7 s on one core): in the default bake
  /// every level of roughness >= 0.25 (0.4 and up), within 0.1% of a brute-force
  /// reference on the peaky studio.exr, where importance sampling missed by up to 3%.
  double quadrature_budget = 0x1p32;
};

/// 9 SH coefficients (bands l <= 2) per colour channel. Convention: the coefficients of
/// the IRRADIANCE E(n) = int L(w) max(0, n.w) dw (Ramamoorthi & Hanrahan 2001, eq. 8:
/// the cosine-lobe convolution A_l is folded in, 1/pi is NOT), in the real SH basis order
/// (l,m) = (0,0), (1,-1), (1,0), (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2), with
/// Y_1-1 ~ y, Y_10 ~ z, Y_11 ~ x. Lambertian outgoing radiance is baseColor / pi * E(n).
using SH9 = std::array<glm::vec3, 9>;

/// Evaluates the irradiance E(n) from SH9 coefficients (world directions).
glm::vec3 eval_sh_irradiance(const SH9& sh, glm::vec3 n);

/// Wall-clock seconds of each stage, and the process CPU seconds (all threads, std::clock)
/// spent during it: on a shared machine the CPU time is the figure that shows what the work
/// costs.
struct BakeTimings {
  double cube_s = 0, specular_s = 0, irradiance_s = 0, sh_s = 0, lut_s = 0, total_s = 0;
  double cube_cpu_s = 0, specular_cpu_s = 0, irradiance_cpu_s = 0, sh_cpu_s = 0, lut_cpu_s = 0,
         total_cpu_s = 0;
};

struct BakeResult {
  Cubemap environment;  ///< the source resampled to a cube with its full box-filtered mip chain
  Cubemap specular;     ///< prefiltered GGX, level i at roughness mip_roughness(i, levels)
  Cubemap irradiance;   ///< diffuse irradiance E(n) (not divided by pi), RGB
  SH9 sh;               ///< irradiance SH (see SH9)
  Image lut;            ///< RGBA over (x: n.v, y: roughness): A, B, E = A+B, E_avg(roughness)
  BakeTimings timings;
};

/// Runs every stage. The environment's rotation and intensity are applied. `progress`
/// may be empty.
BakeResult bake_environment(const Environment& env, const BakeOptions& options,
                            const ProgressCallback& progress = {});

/// The split-sum BRDF LUT for `model` (RGBA, see BakeResult::lut): texel (x, y) at
/// n.v = (x + 0.5) / size, roughness = (y + 0.5) / size (at least kMinRoughness),
/// integrated with the IBL G of the model (k = alpha / 2 for classic).
Image compute_brdf_lut(BrdfModel model, int size);

}  // namespace pbrkit
