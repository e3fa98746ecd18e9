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

glm::vec3 Brdf::eval_specular(glm::vec3 wo, glm::vec3 wi) const {
  // Cook-Torrance: D G F / (4 (n.l)(n.v)).
  const glm::vec3 h = glm::normalize(wo + wi);
  const float VdotH = std::max(glm::dot(wo, h), 0.0f);
  const glm::vec3 F = fresnelSchlick(VdotH, F0_);
  const float D = DistributionGGX(h, alpha_);
  const float G = GeometryG(geometry_, wo, wi, roughness_);
  return D * G * F / (4.0f * wo.z * wi.z);
}

glm::vec3 Brdf::eval_diffuse_and_ms(glm::vec3 wo, glm::vec3 wi) const {
  const glm::vec3 lambert = (1.0f - metallic_) * base_color_ * kInvPi;
  if (!options_.multiscatter) {
    // kd = (1 - F(v.h)) (1 - metallic) (MODEL.md / LearnOpenGL).
    const glm::vec3 h = glm::normalize(wo + wi);
    const glm::vec3 F = fresnelSchlick(std::max(glm::dot(wo, h), 0.0f), F0_);
    return (1.0f - F) * lambert;
  }
  // Diffuse under a specular layer, weighted reciprocally by what the specular lobe
  // (single + multiple scattering) does not reflect: the white-dielectric furnace is 1.
  const glm::vec3 Es_o = specular_albedo(wo.z), Es_i = specular_albedo(wi.z);
  const glm::vec3 diffuse =
      lambert * (1.0f - Es_o) * (1.0f - Es_i) / glm::max(1.0f - Es_avg_, glm::vec3(1e-6f));
  // Kulla & Conty 2017: f_ms = Fms (1 - E(mu_o))(1 - E(mu_i)) / (pi (1 - E_avg)).
  const float E_o = table_->E(wo.z, roughness_), E_i = table_->E(wi.z, roughness_);
  const glm::vec3 ms =
      Fms_ * ((1.0f - E_o) * (1.0f - E_i) / (kPi * std::max(1.0f - E_avg_, 1e-6f)));
  return diffuse + ms;
}

glm::vec3 Brdf::eval(glm::vec3 wo, glm::vec3 wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return glm::vec3(0.0f);
  return eval_specular(wo, wi) + eval_diffuse_and_ms(wo, wi);
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

float Brdf::pdf(glm::vec3 wo, glm::vec3 wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const float p_spec = specular_probability(wo);
  const glm::vec3 h = glm::normalize(wo + wi);
  const float pdf_spec = reflected_pdf(ggx_vndf_pdf(wo, h, alpha_), glm::dot(wo, h));
  return p_spec * pdf_spec + (1.0f - p_spec) * cosine_hemisphere_pdf(wi.z);
}

BrdfSample Brdf::sample(glm::vec3 wo, float u_lobe, glm::vec2 u) const {
  BrdfSample s;
  if (wo.z <= 0.0f) return s;
  const float p_spec = specular_probability(wo);
  if (u_lobe < p_spec) {
    s.wi = reflect_about(wo, sample_ggx_vndf(wo, u, alpha_).h);
  } else {
    s.wi = sample_cosine_hemisphere(u).direction;
  }
  if (s.wi.z <= 0.0f) return s;
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return s;
  s.weight = eval(wo, s.wi) * s.wi.z / s.pdf;
  s.valid = true;
  return s;
}

}  // namespace pbrkit
