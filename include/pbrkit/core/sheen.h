#pragma once
// STUB (replaced by branch sheen-bake).
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include "pbrkit/core/math.h"
#include "pbrkit/core/microfacet.h"
namespace pbrkit {
inline constexpr float kMinSheenRoughness = 0.07f;
inline float DistributionCharlie(float NdotH, float roughness) {
  const float r = std::max(roughness, kMinSheenRoughness);
  const float inv = 1.0f / r;
  const float sin2 = std::max(1.0f - NdotH * NdotH, 0.0f);
  return (2.0f + inv) * std::pow(sin2, 0.5f * inv) / (2.0f * kPi);
}
inline float VisibilityCharlie(float NdotV, float NdotL, float) {
  if (NdotV <= 0.0f || NdotL <= 0.0f) return 0.0f;
  return 1.0f / (4.0f * (NdotL + NdotV - NdotL * NdotV));
}
inline HalfVectorSample sample_charlie(glm::vec2 u, float roughness) {
  const float r = std::max(roughness, kMinSheenRoughness);
  const float sin_t = std::pow(u.x, r / (2.0f * r + 1.0f));
  const float cos_t = std::sqrt(std::max(1.0f - sin_t * sin_t, 0.0f));
  const float phi = 2.0f * kPi * u.y;
  const glm::vec3 h(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
  return {h, DistributionCharlie(cos_t, roughness) * cos_t};
}
inline float charlie_pdf(glm::vec3 h, float roughness) {
  return h.z > 0.0f ? DistributionCharlie(h.z, roughness) * h.z : 0.0f;
}
class SheenTable {
 public:
  static const SheenTable& get() { static SheenTable t; return t; }
  float E(float, float) const { return 0.1f; }
};
}  // namespace pbrkit
