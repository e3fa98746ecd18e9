#include "pbrkit/ibl/anisotropic_taps.h"

#include <algorithm>
#include <cmath>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/microfacet.h"

namespace pbrkit {

glm::vec2 anisotropic_tap_point(int i) {
  // Three equal weights at 0 and +-r hold the uniform disk's second moment along x,
  // integral of x^2 / pi = 1/4, when 2 r^2 / 3 = 1/4.
  const float radius = std::sqrt(3.0f / 8.0f);
  return {i == 0 ? 0.0f : (i == 1 ? radius : -radius), 0.0f};
}

glm::vec3 anisotropic_visible_normal(glm::vec3 wo, glm::vec2 d, float alpha_x, float alpha_y) {
  // Heitz 2018, listing 1 (core/microfacet.h's sample_ggx_visible_normal), with the disk
  // point d measured from the lobe's +X and then expressed in the sampler's (T1, T2).
  const glm::vec3 Vh = glm::normalize(glm::vec3(alpha_x * wo.x, alpha_y * wo.y, wo.z));
  const float lensq = Vh.x * Vh.x + Vh.y * Vh.y;
  const float inv_len = lensq > 0.0f ? 1.0f / std::sqrt(lensq) : 0.0f;
  const glm::vec3 T1 =
      lensq > 0.0f ? glm::vec3(-Vh.y, Vh.x, 0.0f) * inv_len : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 T2 = glm::cross(Vh, T1);
  const glm::vec2 cs = lensq > 0.0f ? glm::vec2(-Vh.y, Vh.x) * inv_len : glm::vec2(1.0f, 0.0f);
  const float t1 = d.x * cs.x + d.y * cs.y;
  float t2 = d.y * cs.x - d.x * cs.y;
  const float s = 0.5f * (1.0f + Vh.z);
  t2 = (1.0f - s) * std::sqrt(std::max(1.0f - t1 * t1, 0.0f)) + s * t2;
  const glm::vec3 Nh = t1 * T1 + t2 * T2 + std::sqrt(std::max(1.0f - t1 * t1 - t2 * t2, 0.0f)) * Vh;
  return glm::normalize(glm::vec3(alpha_x * Nh.x, alpha_y * Nh.y, std::max(Nh.z, 1e-7f)));
}

AnisotropicTap anisotropic_tap(glm::vec3 wo, float alpha_x, float alpha_y, int i) {
  AnisotropicTap tap;
  const glm::vec3 h = anisotropic_visible_normal(wo, anisotropic_tap_point(i), alpha_x, alpha_y);
  const float o_dot_h = glm::dot(wo, h);
  tap.wi = 2.0f * o_dot_h * h - wo;
  const float lambda_o = SmithLambdaGGXAniso(wo, alpha_x, alpha_y);
  // The VNDF estimator of the single-scattering lobe: f cos / pdf = F G2 / G1(wo), and
  // with height-correlated Smith G2 / G1(wo) = (1 + Lambda_o) / (1 + Lambda_o + Lambda_i).
  if (tap.wi.z > 0.0f)
    tap.weight =
        (1.0f + lambda_o) / (1.0f + lambda_o + SmithLambdaGGXAniso(tap.wi, alpha_x, alpha_y));
  // The taps' lookups are the isotropic GGX lobe with the whole lobe's solid angle at
  // normal incidence, 1 / pdf(wi) with pdf = G1(wo) D(h) / (4 n.v) = D(n) / 4 = 1 / (4 pi
  // alpha_x alpha_y) there, equated to the reflected lobe of an isotropic GGX at its peak,
  // 4 pi alpha^2 (the cube's level is prefiltered with D(n) = 1 / (pi alpha^2) and the
  // reflection's Jacobian 1/4): alpha^2 = alpha_x alpha_y, the energy tables' roughness.
  // Each blurs across the short axis more than the lobe does, and the three spread it along
  // the long one; lookups a third as wide left ghosts of an environment's hard edges between
  // the taps, for no smaller error. From the material alone, not the view: one cube level
  // per draw (the view's own solid angle measured about as accurate, and a level per pixel
  // costs llvmpipe 4% of the frame). Clamped to the cube's roughness range.
  const float alpha2 = alpha_x * alpha_y;
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
