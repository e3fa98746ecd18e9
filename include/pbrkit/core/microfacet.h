#pragma once
// GGX / Trowbridge-Reitz microfacet terms, in the local shading frame (n = +Z) unless a
// function takes cosines. Names mirror the seeds (DistributionGGX, GeometrySchlickGGX,
// fresnelSchlick) so a reader with the papers open can check each line.
//
// alpha = roughness^2 throughout (Burley 2012 / Karis 2013 remap).
#include <string_view>

#include <glm/glm.hpp>

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

/// Schlick-GGX (the seeds' GeometrySchlickGGX): n.x / ((n.x)(1 - k) + k).
float GeometrySchlickGGX(float NdotX, float k);
/// k for punctual lights: (roughness + 1)^2 / 8 (Karis 2013, after Burley's remap).
inline float k_direct(float roughness) {
  return (roughness + 1.0f) * (roughness + 1.0f) / 8.0f;
}
/// k for image-based lighting and the BRDF LUT: alpha / 2 (Karis 2013).
inline float k_ibl(float roughness) {
  return roughness * roughness / 2.0f;
}
/// The seeds' GeometrySmith: G1(n.v) G1(n.l) with the given k.
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

/// GGX NDF sampling as in the seeds' ImportanceSampleGGX (Karis 2013):
/// phi = 2 pi u.x, cos(theta) = sqrt((1 - u.y) / (1 + (alpha^2 - 1) u.y)); pdf = D(h)(n.h).
HalfVectorSample sample_ggx_ndf(glm::vec2 u, float alpha);
float ggx_ndf_pdf(glm::vec3 h, float alpha);

/// Visible-normal sampling (Heitz 2018, "Sampling the GGX Distribution of Visible
/// Normals", JCGT 7(4)); wo in the upper hemisphere.
/// pdf = G1(wo) max(0, wo.h) D(h) / wo.z.
HalfVectorSample sample_ggx_vndf(glm::vec3 wo, glm::vec2 u, float alpha);
float ggx_vndf_pdf(glm::vec3 wo, glm::vec3 h, float alpha);

/// Converts a half-vector pdf to the pdf of the reflected direction: pdf_h / (4 |wo.h|).
inline float reflected_pdf(float pdf_h, float WOdotH) {
  return WOdotH > 0.0f ? pdf_h / (4.0f * WOdotH) : 0.0f;
}

}  // namespace pbrkit
