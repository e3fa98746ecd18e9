#pragma once
// GGX / Trowbridge-Reitz microfacet terms, in the local shading frame (n = +Z) unless a
// function takes cosines. Names mirror LearnOpenGL's "PBR: Theory" (de Vries; DistributionGGX,
// GeometrySchlickGGX, fresnelSchlick) so a reader with the papers open can check each line.
//
// alpha = roughness^2 throughout (Burley 2012 / Karis 2013 remap).
#include <algorithm>
#include <cmath>
#include <string_view>

#include <glm/glm.hpp>

#include "pbrkit/core/math.h"

namespace pbrkit {

/// Which masking-shadowing term G the specular lobe uses (MODEL.md, "G, two forms").
enum class GeometryModel {
  kReference,      ///< height-correlated Smith for GGX (Heitz 2014, eq. 99)
  kClassicDirect,  ///< Smith product of Schlick-GGX with k = (roughness + 1)^2 / 8
  kClassicIBL,     ///< Smith product of Schlick-GGX with k = alpha / 2 (IBL, BRDF LUT)
};

/// GGX normal distribution D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2).
/// D is a density over solid angle (it exceeds 1 for small alpha); what integrates to 1
/// over the hemisphere is D(h) (n.h).
float DistributionGGX(float NdotH, float alpha);
/// The same for a local-frame half vector, written as
/// 1 / (pi alpha^2 ((hx^2 + hy^2) / alpha^2 + hz^2)^2), which stays accurate at tiny alpha.
float DistributionGGX(glm::vec3 h, float alpha);

/// Smith's Lambda for GGX (Heitz 2014, eq. 72): (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2.
float SmithLambdaGGX(glm::vec3 w, float alpha);
/// Smith's exact (uncorrelated) masking for GGX: G1 = 1 / (1 + Lambda).
float SmithG1GGX(glm::vec3 w, float alpha);
/// Height-correlated masking-shadowing (Heitz 2014, eq. 99): 1 / (1 + Lambda(v) + Lambda(l)).
float SmithG2HeightCorrelated(glm::vec3 wo, glm::vec3 wi, float alpha);

/// Schlick-GGX (LearnOpenGL's GeometrySchlickGGX): n.x / ((n.x)(1 - k) + k).
float GeometrySchlickGGX(float NdotX, float k);
/// k for punctual lights: (roughness + 1)^2 / 8 (Karis 2013, after Burley's remap).
inline float k_direct(float roughness) {
  return (roughness + 1.0f) * (roughness + 1.0f) / 8.0f;
}
/// k for image-based lighting and the BRDF LUT: alpha / 2 (Karis 2013).
inline float k_ibl(float roughness) {
  return roughness * roughness / 2.0f;
}
/// LearnOpenGL's GeometrySmith: G1(n.v) G1(n.l) with the given k.
float GeometrySmithSchlick(float NdotV, float NdotL, float k);

/// G(l, v) for the chosen model; directions in the local frame.
float GeometryG(GeometryModel model, glm::vec3 wo, glm::vec3 wi, float roughness);

/// Fresnel-Schlick: F0 + (1 - F0)(1 - cos)^5.
glm::vec3 fresnelSchlick(float cosTheta, glm::vec3 F0);
/// UE4's spherical-Gaussian approximation (Karis 2013): F0 + (1 - F0) 2^((-5.55473 c - 6.98316) c).
/// Allowed in the real-time path only.
glm::vec3 fresnelSchlickSG(float cosTheta, glm::vec3 F0);
/// Hemispherical cosine-weighted average of Schlick's Fresnel: F0 + (1 - F0) / 21.
glm::vec3 fresnelSchlickAverage(glm::vec3 F0);

/// A sampled half vector and its pdf with respect to the solid angle of h.
struct HalfVectorSample {
  glm::vec3 h;
  float pdf;
};

/// GGX NDF sampling as in LearnOpenGL's ImportanceSampleGGX (Karis 2013):
/// phi = 2 pi u.x, cos(theta) = sqrt((1 - u.y) / (1 + (alpha^2 - 1) u.y)); pdf = D(h)(n.h).
HalfVectorSample sample_ggx_ndf(glm::vec2 u, float alpha);
float ggx_ndf_pdf(glm::vec3 h, float alpha);

/// Visible-normal sampling (Heitz 2018, "Sampling the GGX Distribution of Visible
/// Normals", JCGT 7(4)); wo in the upper hemisphere.
/// pdf = G1(wo) max(0, wo.h) D(h) / wo.z.
HalfVectorSample sample_ggx_vndf(glm::vec3 wo, glm::vec2 u, float alpha);
float ggx_vndf_pdf(glm::vec3 wo, glm::vec3 h, float alpha);

/// The half vector of sample_ggx_vndf without its pdf (Heitz 2018, listing 1), inline for
/// the path tracer's per-vertex BRDF (core/brdf.h BoundBrdf), whose pdf shares D with eval.
inline glm::vec3 sample_ggx_visible_normal(glm::vec3 wo, glm::vec2 u, float ax, float ay);
inline glm::vec3 sample_ggx_visible_normal(glm::vec3 wo, glm::vec2 u, float alpha) {
  return sample_ggx_visible_normal(wo, u, alpha, alpha);
}

// ---- Anisotropic GGX (KHR_materials_anisotropy; Heitz 2014 section 5.4, Heitz 2018) with
// alpha_x along the local +X (the anisotropy direction) and alpha_y along +Y. With
// alpha_x = alpha_y each reduces to its isotropic form above, term for term. Inline: the
// path tracer's BRDF evaluates them at every vertex.

/// D(h) = 1 / (pi ax ay (hx^2/ax^2 + hy^2/ay^2 + hz^2)^2).
inline float DistributionGGXAniso(glm::vec3 h, float ax, float ay) {
  if (h.z <= 0.0f) return 0.0f;
  const float x = h.x / ax, y = h.y / ay;
  const float e = x * x + y * y + h.z * h.z;
  return 1.0f / (kPi * ax * ay * e * e);
}

/// Smith's Lambda (Heitz 2014, eq. 86): (-1 + sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2)) / 2.
/// Only for w.z > 0.
inline float SmithLambdaGGXAniso(glm::vec3 w, float ax, float ay) {
  const float x = ax * w.x, y = ay * w.y;
  return 0.5f * (-1.0f + std::sqrt(1.0f + (x * x + y * y) / (w.z * w.z)));
}

/// Visible-normal sampling of the anisotropic distribution (Heitz 2018, listing 1, which is
/// written for ax != ay): stretch wo, sample the hemisphere's projected disk, unstretch.
inline glm::vec3 sample_ggx_visible_normal(glm::vec3 wo, glm::vec2 u, float ax, float ay) {
  const glm::vec3 Vh = glm::normalize(glm::vec3(ax * wo.x, ay * wo.y, wo.z));
  const float lensq = Vh.x * Vh.x + Vh.y * Vh.y;
  const glm::vec3 T1 =
      lensq > 0.0f ? glm::vec3(-Vh.y, Vh.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 T2 = glm::cross(Vh, T1);
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * kPi * u.y;
  const float t1 = r * std::cos(phi);
  float t2 = r * std::sin(phi);
  const float s = 0.5f * (1.0f + Vh.z);
  t2 = (1.0f - s) * safe_sqrt(1.0f - t1 * t1) + s * t2;
  const glm::vec3 Nh = t1 * T1 + t2 * T2 + safe_sqrt(1.0f - t1 * t1 - t2 * t2) * Vh;
  return glm::normalize(glm::vec3(ax * Nh.x, ay * Nh.y, std::max(Nh.z, 1e-7f)));
}

/// Converts a half-vector pdf to the pdf of the reflected direction: pdf_h / (4 |wo.h|).
inline float reflected_pdf(float pdf_h, float WOdotH) {
  return WOdotH > 0.0f ? pdf_h / (4.0f * WOdotH) : 0.0f;
}

}  // namespace pbrkit
