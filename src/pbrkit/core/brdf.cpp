#include "pbrkit/core/brdf.h"

#include <algorithm>

#include "pbrkit/core/math.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

BrdfModel parse_brdf_model(std::string_view name) {
  if (name == "reference") return BrdfModel::kReference;
  if (name == "classic") return BrdfModel::kClassic;
  fail("unknown BRDF model '{}' (expected 'reference' or 'classic')", name);
}

std::vector<std::string> brdf_model_names() {
  return {std::string(brdf_model_name(BrdfModel::kReference)),
          std::string(brdf_model_name(BrdfModel::kClassic))};
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

Brdf::Brdf(const BaseLayer& layer, const BrdfOptions& options)
    : base_color_(glm::clamp(layer.base_color, 0.0f, 1.0f)),
      metallic_(saturate(layer.metallic)),
      roughness_(std::clamp(layer.roughness, kMinRoughness, 1.0f)),
      alpha_(roughness_ * roughness_),
      // ior 0 is KHR_materials_ior's special value (F0 = 1, the specular-glossiness mode);
      // anything else below 1 is treated as 1.
      F0_d_(dielectric_f0(layer.ior == 0.0f ? 0.0f : std::max(layer.ior, 1.0f),
                          glm::max(layer.specular_color, 0.0f))),
      // ior 1 is no interface at all: no dielectric specular, not even Schlick's grazing
      // term (KHR_materials_ior: "ior 1.0 means no dielectric specular"; the exact Fresnel
      // of an index-matched interface is 0 at every angle).
      F90_d_(layer.ior > 1.0f || layer.ior == 0.0f ? 1.0f : 0.0f),
      spec_weight_(saturate(layer.specular)),
      iridescence_(saturate(layer.iridescence)),
      film_ior_(std::max(layer.iridescence_ior, 1.0f)),
      film_thickness_(std::max(layer.iridescence_thickness, 0.0f)),
      options_(options),
      geometry_(direct_geometry(options.model)),
      table_(&EnergyTable::get(geometry_)) {
  // KHR_materials_anisotropy: alpha_t = mix(alpha, 1, anisotropy^2) along the direction,
  // alpha_b = alpha across it.
  const float aniso = saturate(layer.anisotropy);
  alpha_x_ = glm::mix(alpha_, 1.0f, aniso * aniso);
  alpha_y_ = alpha_;
  // The albedo tables are isotropic: an anisotropic lobe looks its albedo up at the
  // roughness of the geometric-mean alpha (exact when isotropic; the white furnace of
  // tests/core/bsdf_test.cpp measures what it misses).
  table_roughness_ = aniso > 0.0f ? std::sqrt(std::sqrt(alpha_x_ * alpha_y_)) : roughness_;
  // F0 = mix(0.04, baseColor, metallic) (MODEL.md), with the dielectric's 0.04 from its ior,
  // specular colour and weight (reference: what the dielectric and metal Fresnel mix to at
  // normal incidence; classic: LearnOpenGL's F0).
  F0_ = glm::mix(spec_weight_ * F0_d_, base_color_, metallic_);
  if (options_.multiscatter) {
    const glm::vec2 ab_avg = table_->AB_avg(table_roughness_);
    E_avg_ = ab_avg.x + ab_avg.y;
    if (options.model == BrdfModel::kReference) {
      // Each specular (the dielectric's, weighted by specular; the metal's) gets its own
      // Kulla-Conty Fms; the diffuse sits under the dielectric's only.
      Fms_d_ = spec_weight_ * F90_d_ * multiscatter_fresnel(F0_d_, E_avg_);
      Fms_ = (1.0f - metallic_) * Fms_d_ + metallic_ * multiscatter_fresnel(base_color_, E_avg_);
      Es_avg_ = spec_weight_ * (F0_d_ * ab_avg.x + F90_d_ * ab_avg.y) + Fms_d_ * (1.0f - E_avg_);
    } else {
      Fms_ = multiscatter_fresnel(F0_, E_avg_);
      Es_avg_ = F0_ * ab_avg.x + ab_avg.y + Fms_ * (1.0f - E_avg_);
    }
    if (aniso > 0.0f && geometry_ == GeometryModel::kReference) {
      // The anisotropic lobe's own compensation (core/anisotropic_energy.h), which keeps the
      // walk's elongation; Fms (1 for white) and the diffuse weight stay the isotropic tables'.
      aniso_table_ = &AnisotropicEnergyTable::get();
      const glm::vec2 b = AnisotropicEnergyTable::broadened_alphas(alpha_x_, alpha_y_);
      bx_ = b.x;
      by_ = b.y;
      const float E_tot_avg = aniso_table_->averages(alpha_x_, alpha_y_).y;
      aniso_rest_norm_ = 1.0f / (kPi * std::max(1.0f - E_tot_avg, 1e-6f));
    }
  }
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

}  // namespace pbrkit
