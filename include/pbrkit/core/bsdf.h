#pragma once
// The layered material of docs/MODEL.md ("Revision 2"): KHR_materials_clearcoat's coat over
// KHR_materials_sheen's sheen over the base layer (core/brdf.h), as the extensions'
// READMEs stack them ("If clearcoat is active at the same time, clearcoat is layered on
// top of sheen"):
//
//   f = f_coat + A_coat (f_sheen + A_sheen f_base)
//
//   f_coat  = clearcoat F_c(v.h) D G / (4 |n_c.v| |n_c.l|)    GGX, ior 1.5, in the coat's
//                                                              own normal's frame
//   A_coat  = min(1 - clearcoat F_c(n_c.v), 1 - clearcoat F_c(n_c.l))
//   f_sheen = sheenColor D_Charlie(h) V_Charlie(v, l)          (V includes 1 / (4 n.v n.l))
//   A_sheen = min(1 - max3(sheenColor) E_sheen(n.v), 1 - max3(sheenColor) E_sheen(n.l))
//
// A_sheen is the sheen README's reciprocal albedo scaling; A_coat is the clearcoat README's
// fresnel_coat weight 1 - clearcoat F_c(n_c.v) in the same reciprocal min form (the README's
// one-sided form is not reciprocal; the two agree whenever the light is closer to the
// normal than the viewer). Neither layer is energy-compensated: MODEL.md states their loss.
//
// Directions in the base layer's local shading frame (n = +Z; +X the anisotropy direction).
#include <optional>

#include <glm/glm.hpp>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sheen.h"

namespace pbrkit {

/// KHR_materials_clearcoat at one shading point.
struct CoatLayer {
  float weight = 0.0f;                 ///< clearcoat (factor x texture)
  float roughness = 0.0f;              ///< clearcoatRoughness
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  ///< the coat's normal in the base's local frame
};

/// KHR_materials_sheen at one shading point.
struct SheenLayer {
  glm::vec3 color{0.0f};  ///< sheenColor (0: no sheen)
  float roughness = 0.0f;
};

/// Everything the layered material needs at one shading point, after textures.
struct SurfaceParams {
  BaseLayer base;
  CoatLayer coat;
  SheenLayer sheen;
};

/// The coat's Fresnel: Schlick with F0 = 0.04 (ior 1.5), F90 = 1 (clearcoat README).
inline float coat_fresnel(float cos_theta) {
  const float m = 1.0f - saturate(cos_theta), m2 = m * m;
  return 0.04f + 0.96f * (m2 * m2 * m);
}

class BoundBsdf;

class Bsdf {
 public:
  explicit Bsdf(const SurfaceParams& params, const BrdfOptions& options = {});

  /// The BSDF seen from `wo` (as Brdf::at); BoundBsdf holds a pointer to this Bsdf, which
  /// must outlive it.
  BoundBsdf at(glm::vec3 wo) const;
  glm::vec3 eval(glm::vec3 wo, glm::vec3 wi) const;
  BrdfSample sample(glm::vec3 wo, float u_lobe, glm::vec2 u) const;
  float pdf(glm::vec3 wo, glm::vec3 wi) const;

  const Brdf& base() const { return base_; }
  bool has_coat() const { return coat_.has_value(); }
  bool has_sheen() const { return sheen_max_ > 0.0f; }

 private:
  friend class BoundBsdf;
  Brdf base_;
  // The coat: a black dielectric Brdf (ior 1.5, no compensation) in the coat's frame.
  std::optional<Brdf> coat_;
  float coat_weight_ = 0.0f;
  Frame coat_frame_;
  glm::vec3 sheen_color_{0.0f};
  float sheen_roughness_ = 0.0f;
  float sheen_max_ = 0.0f;  // max3(sheenColor)
};

/// A Bsdf with wo fixed. Without coat and sheen every call goes straight to the base's
/// BoundBrdf.
class BoundBsdf {
 public:
  BoundBsdf(const Bsdf& bsdf, glm::vec3 wo);

  /// f(wo, wi) without the cosine; with `pdf`, also the pdf of sample() for wi.
  glm::vec3 eval(glm::vec3 wi, float* pdf = nullptr) const;
  float pdf(glm::vec3 wi) const {
    float p = 0.0f;
    eval(wi, &p);
    return p;
  }
  /// A lobe chosen with a probability from its estimated albedo at wo (coat, sheen, base;
  /// the base then chooses between its own lobes), a direction from that lobe's sampler
  /// (the coat's and base's visible-normal GGX, the Charlie half-vector sampler, cosine),
  /// and the weight f cos / pdf with the combined pdf of every lobe.
  BrdfSample sample(float u_lobe, glm::vec2 u) const;

  glm::vec3 wo() const { return wo_; }

 private:
  const Bsdf* bsdf_;
  glm::vec3 wo_;
  BoundBrdf base_;
  std::optional<BoundBrdf> coat_;
  bool layered_ = false;
  float p_coat_ = 0.0f, p_sheen_ = 0.0f;
  float coat_o_ = 1.0f;   // 1 - clearcoat F_c(n_c.v)
  float sheen_o_ = 1.0f;  // 1 - max3(sheenColor) E_sheen(n.v)
};

// ---- Definitions (inline: the path tracer binds a BSDF at every vertex). ----

inline BoundBsdf Bsdf::at(glm::vec3 wo) const {
  return BoundBsdf(*this, wo);
}

inline BoundBsdf::BoundBsdf(const Bsdf& bsdf, glm::vec3 wo)
    : bsdf_(&bsdf), wo_(wo), base_(bsdf.base_, wo) {
  layered_ = bsdf.coat_.has_value() || bsdf.sheen_max_ > 0.0f;
  if (!layered_ || wo.z <= 0.0f) return;
  float e_coat = 0.0f, e_sheen = 0.0f;
  if (bsdf.coat_) {
    const glm::vec3 wo_c = bsdf.coat_frame_.to_local(wo);
    coat_.emplace(*bsdf.coat_, wo_c);
    coat_o_ = 1.0f - bsdf.coat_weight_ * coat_fresnel(std::abs(wo_c.z));
    e_coat = bsdf.coat_weight_ * coat_->albedo_estimate();
  }
  if (bsdf.sheen_max_ > 0.0f) {
    const float Es = bsdf.sheen_max_ * SheenTable::get().E(wo.z, bsdf.sheen_roughness_);
    sheen_o_ = 1.0f - Es;
    e_sheen = coat_o_ * Es;
  }
  const float e_base = coat_o_ * sheen_o_ * base_.albedo_estimate();
  const float total = e_coat + e_sheen + e_base;
  if (total > 0.0f) {
    p_coat_ = e_coat / total;
    p_sheen_ = e_sheen / total;
  }
}

inline glm::vec3 BoundBsdf::eval(glm::vec3 wi, float* pdf) const {
  float pdf_base = 0.0f;
  glm::vec3 f = base_.eval(wi, pdf ? &pdf_base : nullptr);
  if (!layered_) {
    if (pdf) *pdf = pdf_base;
    return f;
  }
  if (wo_.z <= 0.0f || wi.z <= 0.0f) {
    if (pdf) *pdf = 0.0f;
    return glm::vec3(0.0f);
  }
  const Bsdf& b = *bsdf_;
  float p = (1.0f - p_coat_ - p_sheen_) * pdf_base;
  if (b.sheen_max_ > 0.0f) {
    const glm::vec3 h = glm::normalize(wo_ + wi);
    const float D = DistributionCharlie(h.z, b.sheen_roughness_);
    const glm::vec3 f_sheen =
        b.sheen_color_ * (D * VisibilityCharlie(wo_.z, wi.z, b.sheen_roughness_));
    const float sheen_i = 1.0f - b.sheen_max_ * SheenTable::get().E(wi.z, b.sheen_roughness_);
    f = f_sheen + std::min(sheen_o_, sheen_i) * f;
    // The Charlie half-vector pdf D (n.h) taken to the reflected direction.
    if (pdf) p += p_sheen_ * reflected_pdf(D * h.z, glm::dot(wo_, h));
  }
  if (coat_) {
    const glm::vec3 wi_c = b.coat_frame_.to_local(wi);
    float pdf_coat = 0.0f;
    const glm::vec3 f_coat = b.coat_weight_ * coat_->eval(wi_c, pdf ? &pdf_coat : nullptr);
    const float coat_i = 1.0f - b.coat_weight_ * coat_fresnel(std::abs(wi_c.z));
    f = f_coat + std::min(coat_o_, coat_i) * f;
    p += p_coat_ * pdf_coat;
  }
  if (pdf) *pdf = p;
  return f;
}

inline BrdfSample BoundBsdf::sample(float u_lobe, glm::vec2 u) const {
  if (!layered_) return base_.sample(u_lobe, u);
  BrdfSample s;
  if (wo_.z <= 0.0f) return s;
  const Bsdf& b = *bsdf_;
  if (u_lobe < p_coat_) {
    // A reflection below the coat's own surface has no coat pdf: no sample.
    const glm::vec3 wi_c = coat_->sample_direction(0.0f, u);
    if (!(wi_c.z > 0.0f)) return s;
    s.wi = b.coat_frame_.to_world(wi_c);
  } else if (u_lobe < p_coat_ + p_sheen_) {
    s.wi = reflect_about(wo_, sample_charlie(u, b.sheen_roughness_).h);
  } else {
    // The base's own lobe choice reuses u_lobe, rescaled to [0, 1).
    const float p_base = 1.0f - p_coat_ - p_sheen_;
    const float u_base = std::min((u_lobe - p_coat_ - p_sheen_) / p_base, 0x1.fffffep-1f);
    s.wi = base_.sample_direction(u_base, u);
  }
  if (!(s.wi.z > 0.0f)) return s;
  const glm::vec3 f = eval(s.wi, &s.pdf);
  if (!(s.pdf > 0.0f)) return s;
  s.weight = f * s.wi.z / s.pdf;
  s.valid = true;
  return s;
}

}  // namespace pbrkit
