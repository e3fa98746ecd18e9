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
/// n.v = mu. Tabulated once at first use (thread-safe; about 20 ms on 2 cores, 30 on one) and
/// looked up bilinearly. It is both the albedo scaling of the base (1 - max3(sheenColor) E(n.v))
/// and the split-sum scale of the sheen IBL (ibl/sheen_lut.h).
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

  /// One entry computed directly with a `samples` x `samples` midpoint product quadrature in
  /// (sqrt(n.l), phi) (the half vector follows from l): used to build the table and by tests.
  static float integrate_E(float mu, float roughness, int samples);

 private:
  SheenTable();
  static const SheenTable& build();
  static inline std::atomic<const SheenTable*> built_{};
  std::vector<float> e_;  // [j * kMuSize + i]
};

}  // namespace pbrkit
