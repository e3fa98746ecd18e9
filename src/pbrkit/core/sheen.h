#pragma once
// The sheen lobe of KHR_materials_sheen: the "Charlie" microfiber distribution and
// visibility of Estevez & Kulla 2017 ("Production Friendly Microfacet Sheen BRDF", SIGGRAPH
// 2017 course), in the form of the extension's README (implementation notes):
//   f_sheen = sheenColor D_Charlie(h) V_Charlie(v, l),   V including 1 / (4 n.v n.l).
// The README's alphaG is the sheen roughness itself (not squared). It is clamped to at least
// kMinSheenRoughness, as Filament and three.js do: below it (2 + 1/r) and sin^(1/r) leave
// float range and the l(x, alphaG) fit of the visibility was never fitted there.
// Local frame n = +Z where a function takes vectors. Used by the layered BSDF, the baker's
// sheen maps (ibl/sheen_prefilter.h, ibl/sheen_lut.h) and, through them, the GL renderer.
#include <atomic>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/core/microfacet.h"

namespace pbrkit {

/// Smallest sheen roughness the lobe uses (Filament, three.js).
inline constexpr float kMinSheenRoughness = 0.07f;

/// Charlie D (Estevez & Kulla 2017; KHR_materials_sheen README):
/// (2 + 1/r) sin(theta_h)^(1/r) / (2 pi), r = max(roughness, kMinSheenRoughness).
/// Like GGX's D it is a density over solid angle; D(h) (n.h) integrates to 1.
float DistributionCharlie(float NdotH, float roughness);

/// lambdaSheen of the README: exp(l(cos)) for cos < 0.5, else exp(2 l(0.5) - l(1 - cos)),
/// with l(x, r) the README's rational fit (Estevez & Kulla 2017, table 1).
float SheenLambda(float cos_theta, float roughness);

/// The README's sheenVisibility, INCLUDING the 1/(4 NdotV NdotL):
/// 1 / ((1 + Lambda(v) + Lambda(l)) 4 NdotV NdotL). 0 if either cosine <= 0.
float VisibilityCharlie(float NdotV, float NdotL, float roughness);

/// Half vector drawn with pdf D_Charlie(h) (n.h) (solid angle of h); local frame n = +Z.
/// The CDF of theta_h is sin(theta_h)^(2 + 1/r), so sin(theta) = u.x^(r/(2r+1)) inverts it
/// exactly; phi = 2 pi u.y.
/// @see charlie_pdf
HalfVectorSample sample_charlie(glm::vec2 u, float roughness);
/// The pdf of sample_charlie: D(h) h.z (0 for h.z <= 0).
float charlie_pdf(glm::vec3 h, float roughness);

/// Directional albedo of the sheen lobe with sheenColor = 1:
///   E(mu, r) = int D_Charlie(h) V_Charlie(v, l) (n.l) dl over the upper hemisphere,
/// n.v = mu, and the direction of the same cosine-weighted lobe's mean,
///   m(mu, r) = int l D_Charlie(h) V_Charlie(v, l) (n.l) dl / E(mu, r),
/// by its components along n and along t, v's direction in the tangent plane (m has no
/// component across the plane of n and v). The components, not the angle, are tabulated:
/// near normal incidence the angle jumps (at n.v = 1 it is 0 by symmetry, but already
/// 26 degrees at n.v = 0.98 for roughness 0.3, where the lobe is a ring about n and m short),
/// while the components go to (0, |m|) continuously. Tabulated once at first use (thread-safe;
/// about 20 ms on 2 cores, 30 on one) and looked up bilinearly. E is both the albedo scaling of the
/// base (1 - max3(sheenColor) E(n.v)) and the split-sum scale of the sheen IBL (ibl/sheen_lut.h);
/// the moments (the mean and the second moments) are what the real-time sheen IBL averages
/// the environment's SH with (ibl/sheen_sh.h, MODEL.md "Sheen maps").
class SheenTable {
 public:
  static constexpr int kMuSize = 64;         ///< mu nodes: mu_i = (i / (kMuSize - 1))^2
  static constexpr int kRoughnessSize = 48;  ///< r_j = 0.07 + 0.93 (j / 47)^2
  static constexpr int kSamples = 32;        ///< quadrature nodes per axis of integrate_E

  static const SheenTable& get() {
    const SheenTable* t = built_.load(std::memory_order_acquire);
    return t ? *t : build();
  }

  /// E(mu, roughness), bilinear in (sqrt(mu), sqrt(roughness - 0.07)); mu in [0, 1], roughness
  /// clamped to [kMinSheenRoughness, 1].
  float E(float mu, float roughness) const;

  /// The cosine-weighted average over l of max(E(mu), E(n.l)):
  ///   E_max_avg(mu, r) = 2 int_0^1 max(E(mu, r), E(mu_l, r)) mu_l dmu_l,
  /// bilinear on E's nodes. The base under the sheen is scaled by min(1 - c E(n.v),
  /// 1 - c E(n.l)) = 1 - c max(E(n.v), E(n.l)) (c = max3(sheenColor); the layered Bsdf, after
  /// the README's albedo scaling made reciprocal), so under a uniform environment its
  /// image-based light is scaled by exactly 1 - c E_max_avg(n.v): the real-time renderer's
  /// scaling of the base's IBL.
  float E_max_avg(float mu, float roughness) const;
  /// The lobe's mean m(mu, roughness) as (along t, along n), bilinear on E's nodes.
  glm::vec2 lobe_mean(float mu, float roughness) const;
  /// The lobe's second moments int l_a l_b D V (n.l) dl / E as (tt, nn, tn), bilinear on
  /// E's nodes (bb = 1 - tt - nn; tb = nb = 0 by the lobe's symmetry across the plane of n
  /// and v). With lobe_mean they give the lobe's integral against any polynomial of degree
  /// 2 in l, so against an environment's order-2 spherical harmonics exactly
  /// (ibl/sheen_sh.h).
  glm::vec3 lobe_second_moments(float mu, float roughness) const;
  /// The angle (radians) of lobe_mean from n towards v. Positive: the Charlie lobe gathers
  /// light from the viewer's side of n (back-scatter), not around the mirror direction (at
  /// negative angles).
  float lobe_angle(float mu, float roughness) const;

  /// One entry computed directly with a `samples` x `samples` midpoint product quadrature in
  /// (sqrt(n.l), phi) (the half vector follows from l): used to build the table and by tests.
  static float integrate_E(float mu, float roughness, int samples);

 private:
  struct Moments {
    double e, mean_t, mean_n;  // E and the unnormalised mean along t (towards v) and n
    double tt, nn, tn;         // the unnormalised second moments
  };
  static Moments integrate_moments(float mu, float roughness, int samples);
  SheenTable();
  static const SheenTable& build();
  static inline std::atomic<const SheenTable*> built_{};
  float lerp_nodes(const std::vector<float>& nodes, float mu, float roughness) const;
  std::vector<float> e_;             // [j * kMuSize + i]
  std::vector<float> mean_t_;        // [j * kMuSize + i]
  std::vector<float> mean_n_;        // [j * kMuSize + i]
  std::vector<float> e_max_avg_;     // [j * kMuSize + i]
  std::vector<float> tt_, nn_, tn_;  // [j * kMuSize + i]: the second moments
};

}  // namespace pbrkit
