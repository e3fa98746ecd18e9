#pragma once
// The layered material of docs/MODEL.md ("The layers"): KHR_materials_clearcoat's coat over
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
// Transmission (MODEL.md, "The dielectric interface and transmission"): KHR_materials_transmission
// and _diffuse_transmission change the dielectric part of the base, as their READMEs write
// dielectric_brdf = fresnel_mix(ior, base = mix(mix(diffuse_brdf, diffuse_btdf, dt),
// specular_btdf baseColor, transmission), layer = specular_brdf):
//
//   f_base = (1 - m) [(1 - t) f_dielectric' + t f_glass] + m f_metal
//
//   f_dielectric' = the opaque dielectric (core/brdf.h, metallic 0) with its diffuse lobe
//                   scaled by 1 - dt, plus dt diffuseTransmissionColor / pi w below the
//                   surface; w the diffuse lobe's compensated reciprocal weight with
//                   multiscatter (BoundBrdf::compensated_diffuse_weight), else
//                   min(tau(|n.v|), tau(|n.l|)), tau = 1 - max3(F_d)
//   f_glass       = the exact dielectric interface (core/transmission.h): its Fresnel
//                   reflection, and its refraction tinted by baseColor (with multiscatter,
//                   its Kulla-Conty compensation lobe too)
//
// The glass part carries its own reflection (exact Fresnel) so that a smooth glass conserves
// energy exactly; the README's single specular_brdf layer is its Schlick approximation.
// KHR_materials_specular acts on the opaque part only. Coat and sheen attenuate transmitted
// light by the same min(o, i) factors as reflected light, with |cos| below the surface.
//
// Directions in the base layer's local shading frame (n = +Z; +X the anisotropy direction).
#include <optional>

#include <glm/glm.hpp>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sheen.h"
#include "pbrkit/core/transmission.h"

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

/// KHR_materials_transmission at one shading point, with the medium on each side
/// (KHR_materials_volume) and the wavelength (KHR_materials_dispersion) already resolved.
struct TransmissionLayer {
  float weight = 0.0f;  ///< transmission (factor x texture); 0: opaque
  /// The ior on the far side of the surface (-Z) over the ior on wo's side (+Z): the
  /// material's ior over the medium's when the ray enters, the reverse when it leaves.
  float eta = 1.5f;
  bool thin_walled = true;  ///< no volume behind the surface (core/transmission.h)
};

/// KHR_materials_diffuse_transmission at one shading point.
struct DiffuseTransmissionLayer {
  float weight = 0.0f;    ///< diffuseTransmission (factor x texture); 0: none
  glm::vec3 color{1.0f};  ///< diffuseTransmissionColor (factor x texture)
};

/// Everything the layered material needs at one shading point, after textures.
struct SurfaceParams {
  BaseLayer base;
  CoatLayer coat;
  SheenLayer sheen;
  TransmissionLayer transmission;
  DiffuseTransmissionLayer diffuse_transmission;
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
  /// Whether any light goes through the surface (transmission or diffuse transmission on a
  /// material that is not fully metallic).
  bool has_transmission() const { return transmissive_; }
  /// Whether the transmission is a delta lobe (smooth glass): its light is found by BSDF
  /// sampling only.
  bool has_delta_lobe() const {
    return transmissive_ && glass_weight_ > 0.0f && dielectric_is_smooth(*glass_);
  }

 private:
  friend class BoundBsdf;
  // Without transmission the whole base; with it, its dielectric part (metallic 0, diffuse
  // scaled by 1 - dt), weighted by opaque_weight_.
  Brdf base_;
  bool transmissive_ = false;
  // The rest is set only when transmissive_ (left uninitialised otherwise: an opaque
  // material, at every path vertex, pays for none of it).
  float opaque_weight_;   // (1 - metallic)(1 - transmission)
  float glass_weight_;    // (1 - metallic) transmission
  glm::vec3 glass_tint_;  // baseColor
  std::optional<Dielectric> glass_;
  float metal_weight_;  // metallic, when the base is split
  std::optional<Brdf> metal_;
  float dt_weight_;       // (1 - metallic)(1 - transmission) diffuseTransmission
  glm::vec3 dt_color_;    // diffuseTransmissionColor / pi
  float dt_F0_, dt_F90_;  // tau's Schlick terms: specular max3(F0_d), specular F90_d (0 for
                          // ior 1: no interface), as core/brdf.h
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
  void bind_transmissive();
  glm::vec3 eval_transmissive(glm::vec3 wi, float* pdf) const;
  BrdfSample sample_transmissive(float u_lobe, glm::vec2 u) const;
  float layer_attenuation(glm::vec3 wi) const;
  float tau(float mu) const;

  const Bsdf* bsdf_;
  glm::vec3 wo_;
  BoundBrdf base_;
  std::optional<BoundBrdf> coat_;
  std::optional<BoundBrdf> metal_;
  bool layered_ = false;
  float p_coat_ = 0.0f, p_sheen_ = 0.0f;
  float p_glass_, p_metal_, p_dt_;  // set by bind_transmissive only (opaque: never read)
  float coat_o_ = 1.0f;             // 1 - clearcoat F_c(n_c.v)
  float sheen_o_ = 1.0f;            // 1 - max3(sheenColor) E_sheen(n.v)
};

// ---- Definitions (inline: the path tracer binds a BSDF at every vertex). ----

inline BoundBsdf Bsdf::at(glm::vec3 wo) const {
  return BoundBsdf(*this, wo);
}

inline BoundBsdf::BoundBsdf(const Bsdf& bsdf, glm::vec3 wo)
    : bsdf_(&bsdf), wo_(wo), base_(bsdf.base_, wo) {
  layered_ = bsdf.coat_.has_value() || bsdf.sheen_max_ > 0.0f || bsdf.transmissive_;
  if (!layered_ || wo.z <= 0.0f) return;
  if (bsdf.transmissive_) {
    bind_transmissive();
    return;
  }
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
  if (bsdf_->transmissive_) return eval_transmissive(wi, pdf);
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
  if (bsdf_->transmissive_) return sample_transmissive(u_lobe, u);
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

// ---- The transmissive material (bsdf.cpp holds the rarely used parts). ----

// tau(mu) = 1 - specular max3(F_d(mu)), Schlick with the dielectric's F0 and F90 (core/brdf.h):
// what the specular layer lets through to the diffuse transmission.
inline float BoundBsdf::tau(float mu) const {
  const float m = 1.0f - saturate(mu), m2 = m * m;
  const Bsdf& b = *bsdf_;
  return 1.0f - (b.dt_F0_ + (b.dt_F90_ - b.dt_F0_) * (m2 * m2 * m));
}

// What the coat and the sheen above the base let through towards wi (either side).
inline float BoundBsdf::layer_attenuation(glm::vec3 wi) const {
  const Bsdf& b = *bsdf_;
  float a = 1.0f;
  if (b.sheen_max_ > 0.0f)
    a *= std::min(sheen_o_,
                  1.0f - b.sheen_max_ * SheenTable::get().E(std::abs(wi.z), b.sheen_roughness_));
  if (coat_) {
    const glm::vec3 wi_c = b.coat_frame_.to_local(wi);
    a *= std::min(coat_o_, 1.0f - b.coat_weight_ * coat_fresnel(std::abs(wi_c.z)));
  }
  return a;
}

}  // namespace pbrkit
