#pragma once
// Brute-force references for the prefiltered specular chain, and the error of a bake
// against them (what `pbrkit bake --validate` reports and manifest.json records).
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/ibl/cubemap.h"
#include "pbrkit/ibl/roughness_mapping.h"
#include "pbrkit/image/environment.h"

namespace pbrkit {

/// The exact split-sum prefilter integral (Karis 2013 with n = v = R) by quadrature over
/// every texel of the source lat-long map (texel-centre rule, exact texel solid angles):
///   P(R) = int L(l) D(h) max(0, R.l) dl / int D(h) max(0, R.l) dl,  h = normalize(R + l),
/// which is what GGX importance sampling of h with weight n.l estimates (pdf(l) = D / 4).
class PrefilterReference {
 public:
  explicit PrefilterReference(const Environment& env);
  /// P(R) for unit R at `roughness` (alpha = max(roughness, kMinRoughness)^2).
  glm::vec3 eval(glm::vec3 R, float roughness) const;

 private:
  std::vector<glm::vec3> directions_;  // world directions of the map's texel centres
  std::vector<glm::vec3> radiance_;    // L dOmega
  std::vector<float> solid_angle_;
};

/// Error of one specular level against the reference.
struct PrefilterError {
  int level = 0;               ///< specular mip level (>= 1)
  float roughness = 0.0f;      ///< the roughness it was prefiltered for
  int directions = 0;          ///< texels compared
  double mean_relative = 0.0;  ///< mean over directions of sum|P - ref| / sum ref (RGB)
  double max_relative = 0.0;   ///< the largest of those
};

/// Compares `specular` (texel values, no interpolation), baked from `env` with `mapping`,
/// with the reference at `per_face` texel centres on each face of every level >= 1; one
/// entry per level.
std::vector<PrefilterError> validate_prefilter(const Environment& env, const Cubemap& specular,
                                               RoughnessMapping mapping, int per_face = 4);

}  // namespace pbrkit
