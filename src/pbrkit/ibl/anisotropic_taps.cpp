#include "pbrkit/ibl/anisotropic_taps.h"

#include <algorithm>
#include <cmath>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/microfacet.h"

namespace pbrkit {

glm::vec2 anisotropic_tap_point(int i) {
  // 1 / golden ratio; the offset 0.5 keeps tap 0 off the disk's seam.
  constexpr float kInvPhi = 0.618033988749895f;
  const float u2 = float(i) * kInvPhi + 0.5f;
  return {(float(i) + 0.5f) / float(kAnisotropicTaps), u2 - std::floor(u2)};
}

AnisotropicTap anisotropic_tap(glm::vec3 wo, float alpha_x, float alpha_y, int i) {
  AnisotropicTap tap;
  const glm::vec3 h = sample_ggx_visible_normal(wo, anisotropic_tap_point(i), alpha_x, alpha_y);
  const float o_dot_h = glm::dot(wo, h);
  tap.wi = 2.0f * o_dot_h * h - wo;
  const float lambda_o = SmithLambdaGGXAniso(wo, alpha_x, alpha_y);
  // The VNDF estimator of the single-scattering lobe: f cos / pdf = F G2 / G1(wo), and
  // with height-correlated Smith G2 / G1(wo) = (1 + Lambda_o) / (1 + Lambda_o + Lambda_i).
  if (tap.wi.z > 0.0f)
    tap.weight =
        (1.0f + lambda_o) / (1.0f + lambda_o + SmithLambdaGGXAniso(tap.wi, alpha_x, alpha_y));
  // The tap's share of the solid angle, 1 / (K pdf(wi)) with pdf = G1(wo) D(h) / (4 n.v),
  // equated to the reflected lobe of an isotropic GGX at its peak, 4 pi alpha^2 (the cube's
  // level is prefiltered with D(n) = 1 / (pi alpha^2) and the reflection's Jacobian 1/4):
  // alpha^2 = n.v (1 + Lambda_o) / (pi K D(h)). Clamped to the cube's roughness range.
  const float d = DistributionGGXAniso(h, alpha_x, alpha_y);
  const float alpha2 =
      wo.z * (1.0f + lambda_o) / (kPi * float(kAnisotropicTaps) * std::max(d, 1e-6f));
  tap.roughness = std::clamp(std::sqrt(std::sqrt(alpha2)), kMinRoughness, 1.0f);
  return tap;
}

std::array<AnisotropicTap, kAnisotropicTaps> anisotropic_taps(glm::vec3 wo, float alpha_x,
                                                              float alpha_y) {
  std::array<AnisotropicTap, kAnisotropicTaps> taps;
  for (int i = 0; i < kAnisotropicTaps; ++i)
    taps[std::size_t(i)] = anisotropic_tap(wo, alpha_x, alpha_y, i);
  return taps;
}

}  // namespace pbrkit
