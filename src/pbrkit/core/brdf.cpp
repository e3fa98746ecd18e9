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
