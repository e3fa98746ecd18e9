#include "pbrkit/core/bsdf.h"

#include <algorithm>

namespace pbrkit {

Bsdf::Bsdf(const SurfaceParams& params, const BrdfOptions& options) : base_(params.base, options) {
  if (params.coat.weight > 0.0f) {
    // The coat is a GGX dielectric of ior 1.5 with nothing under it (its Brdf has a black
    // base) and no compensation; the layering weights it and attenuates what is below.
    BaseLayer coat;
    coat.base_color = glm::vec3(0.0f);
    coat.metallic = 0.0f;
    coat.roughness = params.coat.roughness;
    coat_.emplace(coat, BrdfOptions{BrdfModel::kReference, false});
    coat_weight_ = saturate(params.coat.weight);
    const glm::vec3 n = params.coat.normal;
    coat_frame_ = Frame(glm::dot(n, n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f, 0.0f, 1.0f));
  }
  sheen_color_ = glm::clamp(params.sheen.color, 0.0f, 1.0f);
  sheen_max_ = max3(sheen_color_);
  sheen_roughness_ = std::clamp(params.sheen.roughness, kMinSheenRoughness, 1.0f);
}

glm::vec3 Bsdf::eval(glm::vec3 wo, glm::vec3 wi) const {
  return at(wo).eval(wi);
}

float Bsdf::pdf(glm::vec3 wo, glm::vec3 wi) const {
  return at(wo).pdf(wi);
}

BrdfSample Bsdf::sample(glm::vec3 wo, float u_lobe, glm::vec2 u) const {
  return at(wo).sample(u_lobe, u);
}

}  // namespace pbrkit
