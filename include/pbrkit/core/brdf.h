#pragma once
// The metallic-roughness BRDF of docs/MODEL.md: Lambert diffuse plus GGX
// Cook-Torrance specular, with a selectable G ("reference" or "classic") and optional
// multiple-scattering energy compensation. One implementation for every renderer:
// the path tracer binds it to the view direction at each vertex (Brdf::at, BoundBrdf) and
// calls eval/sample there, the GL shaders mirror eval line by line, and the baker's LUT
// integrates the same specular lobe.
//
// All directions are in the local shading frame (n = +Z), both pointing away from the
// surface: wo towards the viewer (v), wi towards the light (l).
#include <algorithm>
#include <cmath>
#include <string_view>

#include <glm/glm.hpp>

#include "pbrkit/core/color.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"

namespace pbrkit {

/// The named model (MODEL.md): `reference` (default; height-correlated Smith) or
/// `classic` (the seeds' Schlick-GGX with k_direct; k_IBL is used by the LUT/IBL).
enum class BrdfModel { kReference, kClassic };
BrdfModel parse_brdf_model(std::string_view name);  ///< "reference" | "classic"
std::string_view brdf_model_name(BrdfModel model);
/// G for evaluating the BRDF with explicit directions (lights, path tracing).
GeometryModel direct_geometry(BrdfModel model);
/// G for image-based lighting and the split-sum LUT.
GeometryModel ibl_geometry(BrdfModel model);

/// Roughness is clamped to at least this in every renderer (alpha >= 4e-4), so the path
/// tracer and the real-time renderer evaluate the same BRDF; 0.02 is a near-mirror.
inline constexpr float kMinRoughness = 0.02f;

struct BrdfOptions {
  BrdfModel model = BrdfModel::kReference;
  /// Kulla-Conty compensation: adds the multiple-scattering lobe
  /// Fms (1 - E(mu_o))(1 - E(mu_i)) / (pi (1 - E_avg)) and weights the diffuse lobe by
  /// the complement of the full specular albedo,
  /// (1 - Es(mu_o))(1 - Es(mu_i)) / (1 - Es_avg), so a white dielectric also conserves
  /// energy. Without it, kd = (1 - F(v.h))(1 - metallic) exactly as in MODEL.md.
  bool multiscatter = false;
};

struct BrdfSample {
  glm::vec3 wi{0.0f};
  glm::vec3 weight{0.0f};  ///< f(wo, wi) cos(theta_i) / pdf
  float pdf = 0.0f;        ///< combined pdf of all lobes (what MIS needs)
  bool valid = false;      ///< false when the sample fell below the horizon
};

class BoundBrdf;

class Brdf {
 public:
  Brdf(glm::vec3 base_color, float metallic, float roughness, const BrdfOptions& options = {});

  /// The BRDF seen from `wo`: what depends on wo alone is computed here, once, for the
  /// calls that follow (a path vertex evaluates a light sample and draws a BSDF sample).
  /// eval, sample and pdf below are this with a single call each. @see BoundBrdf
  BoundBrdf at(glm::vec3 wo) const;

  /// f(wo, wi), without the cosine. Zero unless both directions are above the surface.
  glm::vec3 eval(glm::vec3 wo, glm::vec3 wi) const;
  /// Chooses the specular lobe (visible-normal GGX sampling) with probability
  /// specular_probability(wo), else the diffuse lobe (cosine sampling, which also covers
  /// the multiple-scattering lobe). u_lobe picks the lobe, u the direction.
  BrdfSample sample(glm::vec3 wo, float u_lobe, glm::vec2 u) const;
  /// The combined pdf of sample() for wi (solid angle).
  float pdf(glm::vec3 wo, glm::vec3 wi) const;
  /// Probability of choosing the specular lobe: estimated specular albedo over the
  /// estimated total (Fresnel at n.v, diffuse weight (1 - metallic) lum(baseColor)).
  float specular_probability(glm::vec3 wo) const;

  /// The full specular albedo at mu: F0 A + B (+ Fms (1 - E) with compensation);
  /// per channel. Exposed for the diffuse weighting and for tests.
  glm::vec3 specular_albedo(float mu) const;

  glm::vec3 base_color() const { return base_color_; }
  float metallic() const { return metallic_; }
  float roughness() const { return roughness_; }
  float alpha() const { return alpha_; }
  glm::vec3 F0() const { return F0_; }
  const BrdfOptions& options() const { return options_; }

 private:
  friend class BoundBrdf;

  glm::vec3 base_color_;
  float metallic_, roughness_, alpha_;
  glm::vec3 F0_;
  BrdfOptions options_;
  GeometryModel geometry_;
  // Compensation state (valid when options_.multiscatter).
  const EnergyTable* table_ = nullptr;
  float E_avg_ = 1.0f;
  glm::vec3 Fms_{0.0f};
  glm::vec3 Es_avg_{0.0f};
};

/// A Brdf with wo fixed (Brdf::at): the lobe-selection probability (with its albedo table
/// lookup), Smith's Lambda(wo) or Schlick-GGX's G1(wo), the Lambertian term and the
/// compensation's albedos at wo are computed once, and eval shares the half vector, D and
/// F between f and the pdf of one direction. This is the BRDF's implementation; Brdf's
/// eval, sample and pdf call it. Holds a copy of the Brdf, so it may outlive it.
class BoundBrdf {
 public:
  /// `wo` in the local shading frame.
  BoundBrdf(const Brdf& brdf, glm::vec3 wo);

  /// f(wo, wi) without the cosine (Brdf::eval); with `pdf`, also the pdf of sample() for
  /// wi (Brdf::pdf), which shares the half vector and D with f.
  glm::vec3 eval(glm::vec3 wi, float* pdf = nullptr) const;
  /// The combined pdf of sample() for wi (Brdf::pdf).
  float pdf(glm::vec3 wi) const;
  /// A direction drawn as Brdf::sample does, with its pdf and weight f cos / pdf.
  BrdfSample sample(float u_lobe, glm::vec2 u) const;

  glm::vec3 wo() const { return wo_; }
  /// Brdf::specular_probability(wo).
  float specular_probability() const { return p_spec_; }
  const Brdf& brdf() const { return brdf_; }

 private:
  glm::vec3 eval_specular(glm::vec3 wi, float D, glm::vec3 F) const;
  glm::vec3 eval_diffuse_and_ms(glm::vec3 wi, glm::vec3 F) const;
  float pdf(glm::vec3 wi, float WOdotH, float D) const;
  glm::vec3 sample_visible_normal(glm::vec2 u) const;

  Brdf brdf_;
  glm::vec3 wo_;
  float p_spec_ = 1.0f;      // specular_probability(wo)
  glm::vec3 lambert_{0.0f};  // (1 - metallic) baseColor / pi
  float lambda_o_ = 0.0f;    // Smith's Lambda(wo) (reference G)
  float G1_o_ = 0.0f;        // Smith's G1(wo) (the visible-normal pdf)
  float schlick_o_ = 0.0f;   // Schlick-GGX G1(n.v) (classic G)
  glm::vec3 Es_o_{0.0f};     // specular_albedo(wo.z) (compensation)
  float E_o_ = 0.0f;         // E(wo.z) (compensation)
};

// ---- Definitions. Inline because BoundBrdf runs at every path vertex: the path tracer's
// integrator inlines the binding and the sampling into its loop (out of line, its
// sampling loop executed 1.3% more instructions; callgrind, spheres at 96x96, 16 spp). ----

inline BoundBrdf Brdf::at(glm::vec3 wo) const {
  return BoundBrdf(*this, wo);
}

inline glm::vec3 Brdf::specular_albedo(float mu) const {
  const glm::vec2 ab = table_->AB(mu, roughness_);
  glm::vec3 Es = F0_ * ab.x + ab.y;
  if (options_.multiscatter) Es += Fms_ * (1.0f - (ab.x + ab.y));
  return Es;
}

inline float Brdf::specular_probability(glm::vec3 wo) const {
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

inline BoundBrdf::BoundBrdf(const Brdf& brdf, glm::vec3 wo)
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

inline glm::vec3 BoundBrdf::eval_specular(glm::vec3 wi, float D, glm::vec3 F) const {
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

inline glm::vec3 BoundBrdf::eval_diffuse_and_ms(glm::vec3 wi, glm::vec3 F) const {
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

inline float BoundBrdf::pdf(glm::vec3 wi, float WOdotH, float D) const {
  // The visible-normal pdf of h, G1(wo) max(0, wo.h) D(h) / wo.z (Heitz 2018, eq. 3),
  // taken to the reflected direction, mixed with the cosine lobe by the lobe choice.
  const float pdf_h = WOdotH <= 0.0f ? 0.0f : G1_o_ * WOdotH * D / wo_.z;
  const float pdf_spec = reflected_pdf(pdf_h, WOdotH);
  return p_spec_ * pdf_spec + (1.0f - p_spec_) * cosine_hemisphere_pdf(wi.z);
}

inline glm::vec3 BoundBrdf::eval(glm::vec3 wi, float* pdf) const {
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

inline float BoundBrdf::pdf(glm::vec3 wi) const {
  if (wo_.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const glm::vec3 h = glm::normalize(wo_ + wi);
  return pdf(wi, glm::dot(wo_, h), DistributionGGX(h, brdf_.alpha_));
}

inline glm::vec3 BoundBrdf::sample_visible_normal(glm::vec2 u) const {
  return sample_ggx_visible_normal(wo_, u, brdf_.alpha_);
}

inline BrdfSample BoundBrdf::sample(float u_lobe, glm::vec2 u) const {
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
