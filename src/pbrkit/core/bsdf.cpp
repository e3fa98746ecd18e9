#include "pbrkit/core/bsdf.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pbrkit {

namespace {

bool is_transmissive(const SurfaceParams& p) {
  return p.base.metallic < 1.0f &&
         (p.transmission.weight > 0.0f || p.diffuse_transmission.weight > 0.0f);
}

// The opaque part of the base: the whole base, or with transmission its dielectric part
// (metallic 0) whose diffuse lobe keeps the 1 - dt not transmitted diffusely (the diffuse
// lobe is linear in baseColor, and the dielectric's specular does not depend on it).
BaseLayer opaque_part(const SurfaceParams& p) {
  BaseLayer d = p.base;
  d.metallic = 0.0f;
  d.base_color *= 1.0f - saturate(p.diffuse_transmission.weight);
  return d;
}

}  // namespace

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
  if (!is_transmissive(params)) return;
  // f_base = (1 - m) [(1 - t) f_dielectric' + t f_glass] + m f_metal (bsdf.h).
  transmissive_ = true;
  // (Built again here rather than in the initialiser: opaque materials, the path tracer's
  // every vertex, then pay nothing for the copy.)
  base_ = Brdf(opaque_part(params), options);
  const float m = saturate(params.base.metallic);
  const float t = saturate(params.transmission.weight);
  const float dt = saturate(params.diffuse_transmission.weight);
  opaque_weight_ = (1.0f - m) * (1.0f - t);
  glass_weight_ = (1.0f - m) * t;
  glass_tint_ = glm::clamp(params.base.base_color, 0.0f, 1.0f);
  Dielectric& glass = glass_.emplace();
  glass.eta = params.transmission.eta;
  // The same roughness as the reflection (transmission README), after the Brdf's clamp.
  glass.alpha_x = base_.alpha_x();
  glass.alpha_y = base_.alpha_y();
  glass.thin_walled = params.transmission.thin_walled;
  // Kulla-Conty compensation of the rough interface, with the base's (the multiscatter
  // option).
  if (options.multiscatter) enable_dielectric_multiscatter(glass);
  metal_weight_ = m;
  if (m > 0.0f) {
    BaseLayer metal = params.base;
    metal.metallic = 1.0f;
    metal_.emplace(metal, options);
  }
  dt_weight_ = (1.0f - m) * (1.0f - t) * dt;
  dt_color_ = glm::clamp(params.diffuse_transmission.color, 0.0f, 1.0f) * kInvPi;
  dt_F0_ = saturate(params.base.specular) *
           max3(dielectric_f0(params.base.ior, params.base.specular_color));
  dt_F90_ =
      params.base.ior > 1.0f || params.base.ior == 0.0f ? saturate(params.base.specular) : 0.0f;
}

void BoundBsdf::bind_transmissive() {
  const Bsdf& b = *bsdf_;
  p_glass_ = p_metal_ = p_dt_ = 0.0f;
  float e_coat = 0.0f, e_sheen = 0.0f;
  if (b.coat_) {
    const glm::vec3 wo_c = b.coat_frame_.to_local(wo_);
    coat_.emplace(*b.coat_, wo_c);
    coat_o_ = 1.0f - b.coat_weight_ * coat_fresnel(std::abs(wo_c.z));
    e_coat = b.coat_weight_ * coat_->albedo_estimate();
  }
  if (b.sheen_max_ > 0.0f) {
    const float Es = b.sheen_max_ * SheenTable::get().E(wo_.z, b.sheen_roughness_);
    sheen_o_ = 1.0f - Es;
    e_sheen = coat_o_ * Es;
  }
  if (b.metal_) metal_.emplace(*b.metal_, wo_);
  // Estimated albedos: the glass reflects F (exact, at the macro normal) and transmits the
  // rest tinted; any positive split keeps the estimator unbiased.
  const float F = fresnel_dielectric(wo_.z, b.glass_->eta);
  const float under = coat_o_ * sheen_o_;
  const float e_glass = under * b.glass_weight_ * (F + (1.0f - F) * luminance(b.glass_tint_));
  const float e_metal = metal_ ? under * b.metal_weight_ * metal_->albedo_estimate() : 0.0f;
  const float e_dt = under * b.dt_weight_ * kPi * luminance(b.dt_color_) * tau(wo_.z);
  const float e_base = under * b.opaque_weight_ * base_.albedo_estimate();
  const float total = e_coat + e_sheen + e_glass + e_metal + e_dt + e_base;
  if (!(total > 0.0f)) return;
  p_coat_ = e_coat / total;
  p_sheen_ = e_sheen / total;
  p_glass_ = e_glass / total;
  p_metal_ = e_metal / total;
  p_dt_ = e_dt / total;
}

glm::vec3 BoundBsdf::eval_transmissive(glm::vec3 wi, float* pdf) const {
  const Bsdf& b = *bsdf_;
  if (wo_.z <= 0.0f || wi.z == 0.0f) {
    if (pdf) *pdf = 0.0f;
    return glm::vec3(0.0f);
  }
  glm::vec3 f(0.0f);
  float p = 0.0f;
  const float p_base = std::max(1.0f - p_coat_ - p_sheen_ - p_glass_ - p_metal_ - p_dt_, 0.0f);
  if (wi.z > 0.0f) {
    float pb = 0.0f;
    f = b.opaque_weight_ * base_.eval(wi, pdf ? &pb : nullptr);
    p += p_base * pb;
    if (metal_) {
      float pm = 0.0f;
      f += b.metal_weight_ * metal_->eval(wi, pdf ? &pm : nullptr);
      p += p_metal_ * pm;
    }
  } else if (b.dt_weight_ > 0.0f) {
    // The diffuse BTDF under the specular layer: with compensation, the same reciprocal
    // weight as the diffuse reflection (what the specular layer's single and multiple
    // scattering leave), so that a white material's reflected and transmitted diffuse light
    // add up to what the specular leaves; without, the layers' reciprocal min form of
    // Schlick's transmittance (which loses what the min and the missing multiple scattering
    // drop).
    const float w = base_.compensates_diffuse() ? base_.compensated_diffuse_weight(-wi.z)
                                                : std::min(tau(wo_.z), tau(-wi.z));
    f += b.dt_weight_ * b.dt_color_ * w;
    p += p_dt_ * cosine_hemisphere_pdf(-wi.z);
  }
  if (b.glass_weight_ > 0.0f && !dielectric_is_smooth(*b.glass_)) {
    const float fg = dielectric_eval(*b.glass_, wo_, wi);
    f += b.glass_weight_ * fg * (wi.z < 0.0f ? b.glass_tint_ : glm::vec3(1.0f));
    if (pdf) p += p_glass_ * dielectric_pdf(*b.glass_, wo_, wi);
  }
  // The layers above: f = f_coat + A_coat (f_sheen + A_sheen f_base), |cos| below.
  if (b.sheen_max_ > 0.0f) {
    const float sheen_i =
        1.0f - b.sheen_max_ * SheenTable::get().E(std::abs(wi.z), b.sheen_roughness_);
    f *= std::min(sheen_o_, sheen_i);
    if (wi.z > 0.0f) {
      const glm::vec3 h = glm::normalize(wo_ + wi);
      const float D = DistributionCharlie(h.z, b.sheen_roughness_);
      f += b.sheen_color_ * (D * VisibilityCharlie(wo_.z, wi.z, b.sheen_roughness_));
      p += p_sheen_ * reflected_pdf(D * h.z, glm::dot(wo_, h));
    }
  }
  if (coat_) {
    const glm::vec3 wi_c = b.coat_frame_.to_local(wi);
    float pdf_coat = 0.0f;
    const glm::vec3 f_coat = b.coat_weight_ * coat_->eval(wi_c, pdf ? &pdf_coat : nullptr);
    f = f_coat + std::min(coat_o_, 1.0f - b.coat_weight_ * coat_fresnel(std::abs(wi_c.z))) * f;
    p += p_coat_ * pdf_coat;
  }
  if (pdf) *pdf = p;
  return f;
}

BrdfSample BoundBsdf::sample_transmissive(float u_lobe, glm::vec2 u) const {
  const Bsdf& b = *bsdf_;
  BrdfSample s;
  // Lobes in the order coat, sheen, glass, diffuse transmission, metal, base.
  const float c_sheen = p_coat_, c_glass = c_sheen + p_sheen_, c_dt = c_glass + p_glass_,
              c_metal = c_dt + p_dt_, c_base = c_metal + p_metal_;
  auto rescale = [&](float lo, float p) {
    return std::min((u_lobe - lo) / std::max(p, 1e-30f), 0x1.fffffep-1f);
  };
  bool reflection = true;
  if (u_lobe < c_sheen) {
    const glm::vec3 wi_c = coat_->sample_direction(0.0f, u);
    if (!(wi_c.z > 0.0f)) return s;
    s.wi = b.coat_frame_.to_world(wi_c);
  } else if (u_lobe < c_glass) {
    s.wi = reflect_about(wo_, sample_charlie(u, b.sheen_roughness_).h);
  } else if (u_lobe < c_dt) {
    const DielectricSample ds = dielectric_sample(*b.glass_, wo_, rescale(c_glass, p_glass_), u);
    if (!ds.valid) return s;
    if (ds.delta) {
      // A delta lobe: its weight directly (mass / probability), and no other lobe shares
      // the direction.
      const glm::vec3 tint = ds.transmitted ? b.glass_tint_ : glm::vec3(1.0f);
      s.wi = ds.wi;
      s.weight = (b.glass_weight_ * ds.weight * layer_attenuation(ds.wi) / p_glass_) * tint;
      s.pdf = std::numeric_limits<float>::infinity();
      s.delta = true;
      s.valid = std::isfinite(s.weight.x + s.weight.y + s.weight.z);
      return s;
    }
    s.wi = ds.wi;
    reflection = false;
  } else if (u_lobe < c_metal) {
    s.wi = sample_cosine_hemisphere(u).direction;
    s.wi.z = -s.wi.z;
    reflection = false;
  } else if (u_lobe < c_base) {
    s.wi = metal_->sample_direction(rescale(c_metal, p_metal_), u);
  } else {
    s.wi = base_.sample_direction(rescale(c_base, 1.0f - c_base), u);
  }
  if (reflection && !(s.wi.z > 0.0f)) return s;
  if (s.wi.z == 0.0f) return s;
  const glm::vec3 f = eval_transmissive(s.wi, &s.pdf);
  if (!(s.pdf > 0.0f)) return s;
  s.weight = f * std::abs(s.wi.z) / s.pdf;
  s.valid = true;
  return s;
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
