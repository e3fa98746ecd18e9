#include "pbrkit/core/brdf.h"

#include <algorithm>
#include <cmath>

#include "pbrkit/core/color.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

BrdfModel parse_brdf_model(std::string_view name) {
  if (name == "reference") return BrdfModel::kReference;
  if (name == "classic") return BrdfModel::kClassic;
  fail("unknown BRDF model '{}' (expected 'reference' or 'classic')", name);
}

std::string_view brdf_model_name(BrdfModel model) {
  return model == BrdfModel::kReference ? "reference" : "classic";
}

GeometryModel direct_geometry(BrdfModel model) {
  return model == BrdfModel::kReference ? GeometryModel::kReference : GeometryModel::kClassicDirect;
}

GeometryModel ibl_geometry(BrdfModel model) {
  return model == BrdfModel::kReference ? GeometryModel::kReference : GeometryModel::kClassicIBL;
}

Brdf::Brdf(glm::vec3 base_color, float metallic, float roughness, const BrdfOptions& options)
    : base_color_(glm::clamp(base_color, 0.0f, 1.0f)),
      metallic_(saturate(metallic)),
      roughness_(std::clamp(roughness, kMinRoughness, 1.0f)),
      alpha_(roughness_ * roughness_),
      // F0 = mix(0.04, baseColor, metallic) (MODEL.md).
      F0_(glm::mix(glm::vec3(0.04f), base_color_, metallic_)),
      options_(options),
      geometry_(direct_geometry(options.model)),
      table_(&EnergyTable::get(geometry_)) {
  if (options_.multiscatter) {
    const glm::vec2 ab_avg = table_->AB_avg(roughness_);
    E_avg_ = ab_avg.x + ab_avg.y;
    Fms_ = multiscatter_fresnel(F0_, E_avg_);
    Es_avg_ = F0_ * ab_avg.x + ab_avg.y + Fms_ * (1.0f - E_avg_);
  }
}

glm::vec3 Brdf::specular_albedo(float mu) const {
  const glm::vec2 ab = table_->AB(mu, roughness_);
  glm::vec3 Es = F0_ * ab.x + ab.y;
  if (options_.multiscatter) Es += Fms_ * (1.0f - (ab.x + ab.y));
  return Es;
}

float Brdf::specular_probability(glm::vec3 wo) const {
  // Weights of the two sampling strategies: the single-scattering specular albedo
  // (sampled by VNDF) against what the cosine strategy covers (diffuse + multiple
  // scattering). Estimates only; any positive split keeps sample() unbiased.
  const float mu = std::max(wo.z, 0.0f);
  const glm::vec2 ab = table_->AB(mu, roughness_);
  const glm::vec3 Ess = F0_ * ab.x + ab.y;
  const float spec = luminance(Ess);
  float rest = (1.0f - metallic_) * luminance(base_color_) * (1.0f - spec);
  if (options_.multiscatter) rest += luminance(Fms_) * (1.0f - (ab.x + ab.y));
  const float total = spec + rest;
  return total > 0.0f ? spec / total : 1.0f;
}

glm::vec3 Brdf::eval(glm::vec3 wo, glm::vec3 wi) const {
  return at(wo).eval(wi);
}

float Brdf::pdf(glm::vec3 wo, glm::vec3 wi) const {
  return at(wo).pdf(wi);
}

BrdfSample Brdf::sample(glm::vec3 wo, float u_lobe, glm::vec2 u) const {
  return at(wo).sample(u_lobe, u);
}

BoundBrdf::BoundBrdf(const Brdf& brdf, glm::vec3 wo)
    : brdf_(brdf),
      wo_(wo),
      p_spec_(brdf.specular_probability(wo)),
      lambert_((1.0f - brdf.metallic_) * brdf.base_color_ * kInvPi) {
  if (wo.z <= 0.0f) return;  // eval, pdf and sample are zero
  const float alpha = brdf_.alpha_;
  if (brdf_.geometry_ == GeometryModel::kReference) {
    lambda_o_ = SmithLambdaGGX(wo, alpha);
    G1_o_ = 1.0f / (1.0f + lambda_o_);  // SmithG1GGX(wo, alpha), Heitz 2014 eq. 43
  } else {
    G1_o_ = SmithG1GGX(wo, alpha);
    schlick_o_ = GeometrySchlickGGX(std::max(wo.z, 0.0f), k_direct(brdf_.roughness_));
  }
  if (brdf_.options_.multiscatter) {
    Es_o_ = brdf_.specular_albedo(wo.z);
    E_o_ = brdf_.table_->E(wo.z, brdf_.roughness_);
  }
}

glm::vec3 BoundBrdf::eval_specular(glm::vec3 wi, float D, glm::vec3 F) const {
  // Cook-Torrance: D G F / (4 (n.l)(n.v)).
  float G;
  if (brdf_.geometry_ == GeometryModel::kReference) {
    // Height-correlated Smith (Heitz 2014, eq. 99): 1 / (1 + Lambda(v) + Lambda(l)).
    G = 1.0f / (1.0f + lambda_o_ + SmithLambdaGGX(wi, brdf_.alpha_));
  } else {
    // The seeds' GeometrySmith: G1(n.v) G1(n.l) with Schlick-GGX and k_direct.
    G = schlick_o_ * GeometrySchlickGGX(std::max(wi.z, 0.0f), k_direct(brdf_.roughness_));
  }
  return D * G * F / (4.0f * wo_.z * wi.z);
}

glm::vec3 BoundBrdf::eval_diffuse_and_ms(glm::vec3 wi, glm::vec3 F) const {
  // kd = (1 - F(v.h)) (1 - metallic) (MODEL.md / LearnOpenGL).
  if (!brdf_.options_.multiscatter) return (1.0f - F) * lambert_;
  // Diffuse under a specular layer, weighted reciprocally by what the specular lobe
  // (single + multiple scattering) does not reflect: the white-dielectric furnace is 1.
  const glm::vec3 Es_i = brdf_.specular_albedo(wi.z);
  const glm::vec3 diffuse =
      lambert_ * (1.0f - Es_o_) * (1.0f - Es_i) / glm::max(1.0f - brdf_.Es_avg_, glm::vec3(1e-6f));
  // Kulla & Conty 2017: f_ms = Fms (1 - E(mu_o))(1 - E(mu_i)) / (pi (1 - E_avg)).
  const float E_i = brdf_.table_->E(wi.z, brdf_.roughness_);
  const glm::vec3 ms =
      brdf_.Fms_ * ((1.0f - E_o_) * (1.0f - E_i) / (kPi * std::max(1.0f - brdf_.E_avg_, 1e-6f)));
  return diffuse + ms;
}

float BoundBrdf::pdf(glm::vec3 wi, float WOdotH, float D) const {
  // The visible-normal pdf of h, G1(wo) max(0, wo.h) D(h) / wo.z (Heitz 2018, eq. 3),
  // taken to the reflected direction, mixed with the cosine lobe by the lobe choice.
  const float pdf_h = WOdotH <= 0.0f ? 0.0f : G1_o_ * WOdotH * D / wo_.z;
  const float pdf_spec = reflected_pdf(pdf_h, WOdotH);
  return p_spec_ * pdf_spec + (1.0f - p_spec_) * cosine_hemisphere_pdf(wi.z);
}

glm::vec3 BoundBrdf::eval(glm::vec3 wi, float* pdf) const {
  if (wo_.z <= 0.0f || wi.z <= 0.0f) {
    if (pdf) *pdf = 0.0f;
    return glm::vec3(0.0f);
  }
  const glm::vec3 h = glm::normalize(wo_ + wi);
  const float WOdotH = glm::dot(wo_, h);
  const float D = DistributionGGX(h, brdf_.alpha_);
  const glm::vec3 F = fresnelSchlick(std::max(WOdotH, 0.0f), brdf_.F0_);
  if (pdf) *pdf = this->pdf(wi, WOdotH, D);
  return eval_specular(wi, D, F) + eval_diffuse_and_ms(wi, F);
}

float BoundBrdf::pdf(glm::vec3 wi) const {
  if (wo_.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const glm::vec3 h = glm::normalize(wo_ + wi);
  return pdf(wi, glm::dot(wo_, h), DistributionGGX(h, brdf_.alpha_));
}

glm::vec3 BoundBrdf::sample_visible_normal(glm::vec2 u) const {
  // sample_ggx_vndf(wo, u, alpha).h (core/microfacet.cpp; Heitz 2018, listing 1), without
  // the pdf it also computes: the pdf of the sample comes from eval, which shares D.
  const glm::vec3 wo = wo_;
  const float alpha = brdf_.alpha_;
  const glm::vec3 Vh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
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
  return glm::normalize(glm::vec3(alpha * Nh.x, alpha * Nh.y, std::max(Nh.z, 1e-7f)));
}

BrdfSample BoundBrdf::sample(float u_lobe, glm::vec2 u) const {
  BrdfSample s;
  if (wo_.z <= 0.0f) return s;
  if (u_lobe < p_spec_) {
    s.wi = reflect_about(wo_, sample_visible_normal(u));
  } else {
    s.wi = sample_cosine_hemisphere(u).direction;
  }
  if (s.wi.z <= 0.0f) return s;
  const glm::vec3 f = eval(s.wi, &s.pdf);
  if (!(s.pdf > 0.0f)) return s;
  s.weight = f * s.wi.z / s.pdf;
  s.valid = true;
  return s;
}

}  // namespace pbrkit
