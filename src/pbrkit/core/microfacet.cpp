#include "pbrkit/core/microfacet.h"

#include <cmath>
#include <limits>

#include "pbrkit/core/math.h"

namespace pbrkit {

float DistributionGGX(float NdotH, float alpha) {
  // LearnOpenGL's DistributionGGX with a = alpha (already squared roughness).
  const float a2 = alpha * alpha;
  const float NdotH2 = NdotH * NdotH;
  const float denom = NdotH2 * (a2 - 1.0f) + 1.0f;
  return NdotH > 0.0f ? a2 / (kPi * denom * denom) : 0.0f;
}

float DistributionGGX(glm::vec3 h, float alpha) {
  if (h.z <= 0.0f) return 0.0f;
  // (n.h)^2 (a^2 - 1) + 1 = a^2 hz^2 + (hx^2 + hy^2) for unit h: no cancellation.
  const float s2 = h.x * h.x + h.y * h.y;
  const float e = s2 / (alpha * alpha) + h.z * h.z;
  return 1.0f / (kPi * alpha * alpha * e * e);
}

float SmithLambdaGGX(glm::vec3 w, float alpha) {
  const float cos2 = w.z * w.z;
  if (cos2 <= 0.0f) return std::numeric_limits<float>::infinity();
  const float tan2 = (w.x * w.x + w.y * w.y) / cos2;
  return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}

float SmithG1GGX(glm::vec3 w, float alpha) {
  if (w.z <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + SmithLambdaGGX(w, alpha));
}

float SmithG2HeightCorrelated(glm::vec3 wo, glm::vec3 wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + SmithLambdaGGX(wo, alpha) + SmithLambdaGGX(wi, alpha));
}

float GeometrySchlickGGX(float NdotX, float k) {
  const float nom = NdotX;
  const float denom = NdotX * (1.0f - k) + k;
  return nom / denom;
}

float GeometrySmithSchlick(float NdotV, float NdotL, float k) {
  return GeometrySchlickGGX(std::max(NdotV, 0.0f), k) *
         GeometrySchlickGGX(std::max(NdotL, 0.0f), k);
}

float GeometryG(GeometryModel model, glm::vec3 wo, glm::vec3 wi, float roughness) {
  switch (model) {
    case GeometryModel::kReference:
      return SmithG2HeightCorrelated(wo, wi, roughness * roughness);
    case GeometryModel::kClassicDirect:
      return GeometrySmithSchlick(wo.z, wi.z, k_direct(roughness));
    case GeometryModel::kClassicIBL:
      return GeometrySmithSchlick(wo.z, wi.z, k_ibl(roughness));
  }
  return 0.0f;
}

glm::vec3 fresnelSchlick(float cosTheta, glm::vec3 F0) {
  const float m = saturate(1.0f - cosTheta);
  const float m2 = m * m;
  return F0 + (1.0f - F0) * (m2 * m2 * m);
}

glm::vec3 fresnelSchlickSG(float cosTheta, glm::vec3 F0) {
  const float c = saturate(cosTheta);
  return F0 + (1.0f - F0) * std::exp2((-5.55473f * c - 6.98316f) * c);
}

glm::vec3 fresnelSchlickAverage(glm::vec3 F0) {
  return F0 + (1.0f - F0) * (1.0f / 21.0f);
}

HalfVectorSample sample_ggx_ndf(glm::vec2 u, float alpha) {
  // Karis 2013 ImportanceSampleGGX; cos^2 = (1 - u) / ((1 - u) + alpha^2 u) written without
  // the cancellation of 1 + (alpha^2 - 1) u at small alpha.
  const float phi = 2.0f * kPi * u.x;
  const float one_minus_u = 1.0f - u.y;
  const float cos2 = one_minus_u / (one_minus_u + alpha * alpha * u.y);
  const float cos_theta = std::sqrt(cos2);
  // sin^2 = alpha^2 u / ((1 - u) + alpha^2 u) directly: 1 - cos2 rounds to 0 in float for
  // every u below ~1e-2 when alpha = 0.0025 (roughness 0.05), which put ~1% of the samples
  // exactly on the pole (found by the NDF chi-square test).
  const float sin_theta = std::sqrt(alpha * alpha * u.y / (one_minus_u + alpha * alpha * u.y));
  const glm::vec3 h(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
  return {h, ggx_ndf_pdf(h, alpha)};
}

float ggx_ndf_pdf(glm::vec3 h, float alpha) {
  return DistributionGGX(h, alpha) * std::max(h.z, 0.0f);
}

HalfVectorSample sample_ggx_vndf(glm::vec3 wo, glm::vec2 u, float alpha) {
  const glm::vec3 h = sample_ggx_visible_normal(wo, u, alpha);
  return {h, ggx_vndf_pdf(wo, h, alpha)};
}

float ggx_vndf_pdf(glm::vec3 wo, glm::vec3 h, float alpha) {
  if (wo.z <= 0.0f) return 0.0f;
  // D_wo(h) = G1(wo) max(0, wo.h) D(h) / (n.wo)   (Heitz 2018, eq. 3)
  const float WOdotH = glm::dot(wo, h);
  if (WOdotH <= 0.0f) return 0.0f;
  return SmithG1GGX(wo, alpha) * WOdotH * DistributionGGX(h, alpha) / wo.z;
}

}  // namespace pbrkit
