#pragma once
// The base layer of docs/MODEL.md: glTF's metallic-roughness BRDF (Lambert diffuse plus
// GGX Cook-Torrance specular) with the surface extensions that change it in place
// (KHR_materials_ior, _specular, _anisotropy, _iridescence), a selectable model
// ("reference": the glTF specification's Appendix B structure; "classic": LearnOpenGL's
// form, de Vries "PBR: Theory") and multiple-scattering energy compensation. The coat and sheen
// layers over it are core/bsdf.h. One implementation for every renderer: the path tracer binds it
// to the view direction at each vertex (Brdf::at, BoundBrdf) and calls eval/sample there, the GL
// shaders mirror eval line by line, and the baker's LUT integrates the same specular lobe.
//
// All directions are in the local shading frame (n = +Z), both pointing away from the
// surface: wo towards the viewer (v), wi towards the light (l).
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/core/anisotropic_energy.h"
#include "pbrkit/core/color.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/core/iridescence.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"

namespace pbrkit {

/// The named model (MODEL.md): `reference` (default; glTF Appendix B's
/// mix(dielectric, metal, metallic) with height-correlated Smith) or `classic` (LearnOpenGL's
/// kd = (1 - F)(1 - metallic) with Schlick-GGX and k_direct; k_IBL is used by the LUT/IBL).
enum class BrdfModel { kReference, kClassic };
BrdfModel parse_brdf_model(std::string_view name);  ///< "reference" | "classic"
std::string_view brdf_model_name(BrdfModel model);
std::vector<std::string> brdf_model_names();  ///< every model's name, in enum order
/// G for evaluating the BRDF with explicit directions (lights, path tracing).
GeometryModel direct_geometry(BrdfModel model);
/// G for image-based lighting and the split-sum LUT.
GeometryModel ibl_geometry(BrdfModel model);
/// Whether multiple-scattering compensation is on when nobody says: on for `reference`
/// (the Khronos Sample Viewer, Filament and Cycles conserve energy by default), off for
/// `classic` (LearnOpenGL has none).
inline bool default_multiscatter(BrdfModel model) {
  return model == BrdfModel::kReference;
}

/// Roughness is clamped to at least this in every renderer (alpha >= 4e-4), so the path
/// tracer and the real-time renderer evaluate the same BRDF; 0.02 is a near-mirror.
inline constexpr float kMinRoughness = 0.02f;

struct BrdfOptions {
  BrdfModel model = BrdfModel::kReference;
  /// Kulla-Conty compensation (default_multiscatter(model)): adds the multiple-scattering
  /// lobe Fms (1 - E(mu_o))(1 - E(mu_i)) / (pi (1 - E_avg)) and weights the diffuse lobe by
  /// the complement of the dielectric's full specular albedo,
  /// (1 - Es(mu_o))(1 - Es(mu_i)) / (1 - Es_avg), so a white dielectric also conserves
  /// energy. Without it the diffuse weight is the spec's (1 - specular max3(F_dielectric(v.h)))
  /// for `reference` and (1 - F(v.h)) for `classic`. The layered Bsdf (core/bsdf.h) takes
  /// the same switch for its rough glass (core/transmission.h's DielectricCompensation) and
  /// its diffuse transmission (weighted as this diffuse lobe).
  bool multiscatter = true;
};

/// The dielectric's normal-incidence reflectance from KHR_materials_ior and
/// KHR_materials_specular: min(((ior - 1) / (ior + 1))^2 specularColor, 1) (0.04 for the
/// default ior 1.5; 0 for ior 1, which has no dielectric specular).
inline glm::vec3 dielectric_f0(float ior, glm::vec3 specular_color) {
  const float r = (ior - 1.0f) / (ior + 1.0f);
  // 0.04 exactly for the default ior (0.2f * 0.2f rounds above it), so materials without
  // the extensions keep LearnOpenGL's F0 to the bit.
  const float r2 = ior == 1.5f ? 0.04f : r * r;
  return glm::min(r2 * specular_color, glm::vec3(1.0f));
}

/// The base layer's inputs at one shading point, after textures (MODEL.md, "The base layer").
struct BaseLayer {
  glm::vec3 base_color{1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;
  float ior = 1.5f;                ///< KHR_materials_ior
  float specular = 1.0f;           ///< KHR_materials_specular: weight of the dielectric's specular
  glm::vec3 specular_color{1.0f};  ///< KHR_materials_specular: F0 tint
  float anisotropy = 0.0f;         ///< KHR_materials_anisotropy strength, along the local +X
  float iridescence = 0.0f;        ///< KHR_materials_iridescence factor
  float iridescence_ior = 1.3f;    ///< the film's ior
  float iridescence_thickness = 0.0f;  ///< nm
};

struct BrdfSample {
  glm::vec3 wi{0.0f};
  glm::vec3 weight{0.0f};  ///< f(wo, wi) cos(theta_i) / pdf
  float pdf = 0.0f;        ///< combined pdf of all lobes (what MIS needs)
  bool valid = false;      ///< false when the sample fell below the horizon
  /// A delta lobe's sample (smooth glass, core/transmission.h): `pdf` is infinite (no light
  /// sample can find this direction, so MIS gives the BSDF sample all the weight) and
  /// eval() does not contain the lobe.
  bool delta = false;
};

class BoundBrdf;

class Brdf {
 public:
  explicit Brdf(const BaseLayer& layer, const BrdfOptions& options = {});
  Brdf(glm::vec3 base_color, float metallic, float roughness, const BrdfOptions& options = {})
      : Brdf(BaseLayer{base_color, metallic, roughness}, options) {}

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
  /// estimated total.
  float specular_probability(glm::vec3 wo) const;

  /// The full specular albedo at mu (the dielectric's and the metal's specular mixed by
  /// metallic, + the multiple-scattering lobe with compensation); per channel. Exposed for
  /// tests. Exact for isotropic GGX without iridescence (tabulated A, B).
  glm::vec3 specular_albedo(float mu) const;

  glm::vec3 base_color() const { return base_color_; }
  float metallic() const { return metallic_; }
  float roughness() const { return roughness_; }
  float alpha() const { return alpha_; }
  float alpha_x() const { return alpha_x_; }
  float alpha_y() const { return alpha_y_; }
  /// classic: mix(F0_dielectric, baseColor, metallic); reference: the same, what a
  /// split-sum specular term multiplies A by.
  glm::vec3 F0() const { return F0_; }
  const BrdfOptions& options() const { return options_; }

 private:
  friend class BoundBrdf;
  bool reference() const { return options_.model == BrdfModel::kReference; }
  // Single-scattering specular albedo and the diffuse lobe's share at mu (estimates for
  // the lobe choice; exact for isotropic GGX without iridescence).
  glm::vec3 dielectric_albedo(glm::vec2 ab) const;

  glm::vec3 base_color_;
  float metallic_, roughness_, alpha_;
  float alpha_x_, alpha_y_;  // anisotropic GGX (alpha_x = alpha_y = alpha when isotropic)
  float table_roughness_;    // the albedo tables' roughness: sqrt(sqrt(alpha_x alpha_y))
  glm::vec3 F0_;             // classic's F0; reference: mix(s F0_d, baseColor, metallic)
  glm::vec3 F0_d_;           // the dielectric's F0 (ior, specular colour)
  float F90_d_;              // the dielectric's F90: 1, or 0 for ior 1 (no interface)
  float spec_weight_;        // KHR_materials_specular's specular
  float iridescence_, film_ior_, film_thickness_;
  BrdfOptions options_;
  GeometryModel geometry_;
  // Compensation state (valid when options_.multiscatter).
  const EnergyTable* table_ = nullptr;
  float E_avg_ = 1.0f;
  glm::vec3 Fms_{0.0f};     // Fms of the whole specular (the dielectric's weighted + the metal's)
  glm::vec3 Fms_d_{0.0f};   // reference: the dielectric's Fms (times its weight)
  glm::vec3 Es_avg_{0.0f};  // classic: Es_avg per channel; reference: the dielectric's
  // Anisotropic compensation (reference, alpha_x != alpha_y; core/anisotropic_energy.h): the
  // table, the broadened lobe's alphas and 1 / (pi (1 - E_tot_avg)).
  const AnisotropicEnergyTable* aniso_table_ = nullptr;
  float bx_ = 1.0f, by_ = 1.0f;
  float aniso_rest_norm_ = 0.0f;
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
  /// The direction alone (no evaluation): what a layered BSDF draws before it evaluates
  /// every layer. wi.z <= 0 means no sample.
  glm::vec3 sample_direction(float u_lobe, glm::vec2 u) const;

  glm::vec3 wo() const { return wo_; }
  /// Brdf::specular_probability(wo).
  float specular_probability() const { return p_spec_; }
  /// An estimate of the directional albedo at wo (luminance), for a layered BSDF's lobe
  /// choice.
  float albedo_estimate() const { return albedo_est_; }
  const Brdf& brdf() const { return brdf_; }
  /// Whether the diffuse lobe is weighted by the compensated, reciprocal complement of the
  /// dielectric's specular albedo (reference with multiscatter on).
  bool compensates_diffuse() const { return brdf_.options_.multiscatter && brdf_.reference(); }
  /// That weight for a direction at |cos| mu_i (either side of the surface):
  /// (1 - max3(Es(mu_o))) (1 - max3(Es(mu_i))) / (1 - max3(Es_avg)), Es the dielectric's
  /// single- plus multiple-scattering specular albedo; its cosine-weighted integral over
  /// mu_i is 1 - max3(Es(mu_o)), what the specular layer leaves. Only when
  /// compensates_diffuse().
  float compensated_diffuse_weight(float mu_i) const {
    const Brdf& b = brdf_;
    const glm::vec2 ab_i = b.table_->AB(mu_i, b.table_roughness_);
    const glm::vec3 Es_i = b.dielectric_albedo(ab_i) + b.Fms_d_ * (1.0f - (ab_i.x + ab_i.y));
    return diffuse_o_ * (1.0f - max3(Es_i));
  }

 private:
  glm::vec3 specular_fresnel(float WOdotH, glm::vec3* diffuse_weight) const;
  glm::vec3 eval_diffuse_and_ms(glm::vec3 wi, glm::vec3 diffuse_weight) const;
  float pdf(glm::vec3 wi, float WOdotH, float D) const;

  Brdf brdf_;
  glm::vec3 wo_;
  float p_spec_ = 1.0f;      // specular_probability(wo)
  float albedo_est_ = 0.0f;  // albedo_estimate()
  glm::vec3 lambert_{0.0f};  // (1 - metallic) baseColor / pi
  float lambda_o_ = 0.0f;    // Smith's Lambda(wo) (reference G)
  float G1_o_ = 0.0f;        // Smith's G1(wo) (the visible-normal pdf)
  float schlick_o_ = 0.0f;   // Schlick-GGX G1(n.v) (classic G)
  float diffuse_o_ = 1.0f;   // compensation: the diffuse lobe's factor at wo
  float E_o_ = 0.0f;         // E(wo.z) (compensation)
  // Anisotropic compensation: the broadened lobe's choice probability, h(wo), 1 - E_tot(wo),
  // and Smith's Lambda(wo) and G1(wo) at the broadened alphas.
  float p_b_ = 0.0f, h_o_ = 0.0f, rest_o_ = 0.0f, lambda_b_o_ = 0.0f, G1_b_o_ = 0.0f;
};

// ---- Definitions. Inline because BoundBrdf runs at every path vertex: the path tracer's
// integrator inlines the binding and the sampling into its loop (out of line, its
// sampling loop executed 1.3% more instructions; callgrind, spheres at 96x96, 16 spp). ----

inline BoundBrdf Brdf::at(glm::vec3 wo) const {
  return BoundBrdf(*this, wo);
}

inline glm::vec3 Brdf::dielectric_albedo(glm::vec2 ab) const {
  // The dielectric's specular with F90 = 1 (KHR_materials_specular), weighted.
  return spec_weight_ * (F0_d_ * ab.x + F90_d_ * ab.y);
}

inline glm::vec3 Brdf::specular_albedo(float mu) const {
  const glm::vec2 ab = table_->AB(mu, table_roughness_);
  // reference: (1 - metallic) s (F0_d A + B) + metallic (baseColor A + B), F0_ holding both
  // F0 parts; classic: F0 A + B.
  const float b_weight =
      reference() ? (1.0f - metallic_) * spec_weight_ * F90_d_ + metallic_ : 1.0f;
  glm::vec3 Es = F0_ * ab.x + ab.y * b_weight;
  if (options_.multiscatter) Es += Fms_ * (1.0f - (ab.x + ab.y));
  return Es;
}

inline float Brdf::specular_probability(glm::vec3 wo) const {
  return at(wo).specular_probability();
}

inline BoundBrdf::BoundBrdf(const Brdf& brdf, glm::vec3 wo)
    : brdf_(brdf), wo_(wo), lambert_((1.0f - brdf.metallic_) * brdf.base_color_ * kInvPi) {
  // Weights of the two sampling strategies: the single-scattering specular albedo
  // (sampled by VNDF) against what the cosine strategy covers (diffuse + multiple
  // scattering). Estimates only; any positive split keeps sample() unbiased.
  const float mu = std::max(wo.z, 0.0f);
  const glm::vec2 ab = brdf.table_->AB(mu, brdf.table_roughness_);
  const float E = ab.x + ab.y;
  float spec, rest;
  if (brdf.reference()) {
    const glm::vec3 Ed = brdf.dielectric_albedo(ab);
    spec =
        luminance((1.0f - brdf.metallic_) * Ed + brdf.metallic_ * (brdf.base_color_ * ab.x + ab.y));
    rest = (1.0f - brdf.metallic_) * luminance(brdf.base_color_) * (1.0f - max3(Ed));
  } else {
    spec = luminance(brdf.F0_ * ab.x + ab.y);
    rest = (1.0f - brdf.metallic_) * luminance(brdf.base_color_) * (1.0f - spec);
  }
  float broadened = 0.0f;
  if (brdf.aniso_table_ && wo.z > 0.0f) {
    // The anisotropic compensation's two lobes: the broadened GGX lobe (its own VNDF
    // strategy) carries E_tot - E_ss, the Kulla-Conty rest (cosine) 1 - E_tot.
    const AnisotropicEnergyTable::Entry e =
        brdf.aniso_table_->lookup(wo, brdf.alpha_x_, brdf.alpha_y_);
    h_o_ = e.h;
    rest_o_ = 1.0f - e.E_tot;
    broadened = luminance(brdf.Fms_) * std::max(e.E_tot - e.E_ss, 0.0f);
    rest += luminance(brdf.Fms_) * rest_o_;
    lambda_b_o_ = SmithLambdaGGXAniso(wo, brdf.bx_, brdf.by_);
    G1_b_o_ = 1.0f / (1.0f + lambda_b_o_);
  } else if (brdf.options_.multiscatter) {
    rest += luminance(brdf.Fms_) * (1.0f - E);
  }
  albedo_est_ = spec + rest + broadened;
  p_spec_ = albedo_est_ > 0.0f ? spec / albedo_est_ : 1.0f;
  p_b_ = albedo_est_ > 0.0f ? broadened / albedo_est_ : 0.0f;
  if (wo.z <= 0.0f) return;  // eval, pdf and sample are zero
  const float ax = brdf_.alpha_x_, ay = brdf_.alpha_y_;
  if (brdf_.geometry_ == GeometryModel::kReference) {
    lambda_o_ = SmithLambdaGGXAniso(wo, ax, ay);
    G1_o_ = 1.0f / (1.0f + lambda_o_);  // Smith's G1, Heitz 2014 eq. 43
  } else {
    G1_o_ = 1.0f / (1.0f + SmithLambdaGGXAniso(wo, ax, ay));
    schlick_o_ = GeometrySchlickGGX(mu, k_direct(brdf_.roughness_));
  }
  if (brdf_.options_.multiscatter) {
    E_o_ = E;
    if (brdf.reference()) {
      // The diffuse lobe under the dielectric's specular (single + multiple scattering).
      const glm::vec3 Es_o = brdf.dielectric_albedo(ab) + brdf.Fms_d_ * (1.0f - E);
      diffuse_o_ = (1.0f - max3(Es_o)) / std::max(1.0f - max3(brdf.Es_avg_), 1e-6f);
    }
  }
}

// The specular lobe's Fresnel at v.h (what multiplies D G / (4 n.v n.l)) and, through
// `diffuse_weight`, the Fresnel part of the diffuse lobe's weight without compensation.
inline glm::vec3 BoundBrdf::specular_fresnel(float WOdotH, glm::vec3* diffuse_weight) const {
  const Brdf& b = brdf_;
  const float c = std::max(WOdotH, 0.0f);
  const float m = 1.0f - c, m2 = m * m, w5 = m2 * m2 * m;  // Schlick's (1 - v.h)^5
  if (!b.reference()) {
    // LearnOpenGL: F = F0 + (1 - F0)(1 - v.h)^5 with the mixed F0; kd = 1 - F.
    glm::vec3 F = b.F0_ + (1.0f - b.F0_) * w5;
    if (b.iridescence_ > 0.0f)
      F = glm::mix(F, iridescence_fresnel(c, b.film_ior_, b.film_thickness_, b.F0_),
                   b.iridescence_);
    *diffuse_weight = 1.0f - F;
    return F;
  }
  // glTF Appendix B: the dielectric's Fresnel (F0 from ior and specular, F90 = 1, weighted
  // by specular; KHR_materials_specular's fresnel_mix) and the metal's (F0 = baseColor),
  // mixed by metallic; the diffuse sits under the dielectric's specular only, weighted by
  // 1 - specular max3(F_dielectric).
  glm::vec3 Fd = b.F0_d_ + (b.F90_d_ - b.F0_d_) * w5;
  glm::vec3 Fm = b.base_color_ + (1.0f - b.base_color_) * w5;
  if (b.iridescence_ > 0.0f) {
    // KHR_materials_iridescence: the thin film replaces both Fresnel terms, by its factor.
    // (Each thin film only where its term has weight: the evaluation is ~200 ns.)
    if (b.metallic_ < 1.0f)
      Fd = glm::mix(Fd, iridescence_fresnel(c, b.film_ior_, b.film_thickness_, b.F0_d_),
                    b.iridescence_);
    if (b.metallic_ > 0.0f)
      Fm = glm::mix(Fm, iridescence_fresnel(c, b.film_ior_, b.film_thickness_, b.base_color_),
                    b.iridescence_);
  }
  Fd *= b.spec_weight_;
  *diffuse_weight = glm::vec3(1.0f - max3(Fd));
  return (1.0f - b.metallic_) * Fd + b.metallic_ * Fm;
}

inline glm::vec3 BoundBrdf::eval_diffuse_and_ms(glm::vec3 wi, glm::vec3 diffuse_weight) const {
  if (!brdf_.options_.multiscatter) return diffuse_weight * lambert_;
  const Brdf& b = brdf_;
  const glm::vec2 ab_i = b.table_->AB(wi.z, b.table_roughness_);
  const float E_i = ab_i.x + ab_i.y;
  // Diffuse under a specular layer, weighted reciprocally by what the specular lobe
  // (single + multiple scattering) does not reflect: the white-dielectric furnace is 1.
  glm::vec3 diffuse;
  if (b.reference()) {
    const glm::vec3 Es_i = b.dielectric_albedo(ab_i) + b.Fms_d_ * (1.0f - E_i);
    diffuse = lambert_ * (diffuse_o_ * (1.0f - max3(Es_i)));
  } else {
    const glm::vec3 Es_o = b.specular_albedo(wo_.z), Es_i = b.specular_albedo(wi.z);
    diffuse =
        lambert_ * (1.0f - Es_o) * (1.0f - Es_i) / glm::max(1.0f - b.Es_avg_, glm::vec3(1e-6f));
  }
  if (b.aniso_table_) {
    // Anisotropic: h(wo) h(wi) f_b(wo, wi), the single-scattering lobe at the broadened
    // alphas scaled symmetrically, plus Kulla & Conty 2017's lobe on what is left,
    // (1 - E_tot(wo))(1 - E_tot(wi)) / (pi (1 - E_tot_avg)) (core/anisotropic_energy.h).
    const AnisotropicEnergyTable::Entry e = b.aniso_table_->lookup(wi, b.alpha_x_, b.alpha_y_);
    const glm::vec3 h = glm::normalize(wo_ + wi);
    const float G2 = 1.0f / (1.0f + lambda_b_o_ + SmithLambdaGGXAniso(wi, b.bx_, b.by_));
    const float f_b = DistributionGGXAniso(h, b.bx_, b.by_) * G2 / (4.0f * wo_.z * wi.z);
    return diffuse + b.Fms_ * (h_o_ * e.h * f_b + rest_o_ * (1.0f - e.E_tot) * b.aniso_rest_norm_);
  }
  // Kulla & Conty 2017: f_ms = Fms (1 - E(mu_o))(1 - E(mu_i)) / (pi (1 - E_avg)).
  const glm::vec3 ms =
      b.Fms_ * ((1.0f - E_o_) * (1.0f - E_i) / (kPi * std::max(1.0f - b.E_avg_, 1e-6f)));
  return diffuse + ms;
}

inline float BoundBrdf::pdf(glm::vec3 wi, float WOdotH, float D) const {
  // The visible-normal pdf of h, G1(wo) max(0, wo.h) D(h) / wo.z (Heitz 2018, eq. 3),
  // taken to the reflected direction, mixed with the cosine lobe by the lobe choice.
  const float pdf_h = WOdotH <= 0.0f ? 0.0f : G1_o_ * WOdotH * D / wo_.z;
  const float pdf_spec = reflected_pdf(pdf_h, WOdotH);
  float pdf_b = 0.0f;
  if (p_b_ > 0.0f && WOdotH > 0.0f) {
    // The broadened lobe's visible normals, the same pdf at its alphas.
    const glm::vec3 h = glm::normalize(wo_ + wi);
    pdf_b = reflected_pdf(G1_b_o_ * WOdotH * DistributionGGXAniso(h, brdf_.bx_, brdf_.by_) / wo_.z,
                          WOdotH);
  }
  return p_spec_ * pdf_spec + p_b_ * pdf_b +
         std::max(1.0f - p_spec_ - p_b_, 0.0f) * cosine_hemisphere_pdf(wi.z);
}

inline glm::vec3 BoundBrdf::eval(glm::vec3 wi, float* pdf) const {
  if (wo_.z <= 0.0f || wi.z <= 0.0f) {
    if (pdf) *pdf = 0.0f;
    return glm::vec3(0.0f);
  }
  const Brdf& b = brdf_;
  const glm::vec3 h = glm::normalize(wo_ + wi);
  const float WOdotH = glm::dot(wo_, h);
  const float D = DistributionGGXAniso(h, b.alpha_x_, b.alpha_y_);
  glm::vec3 diffuse_weight;
  const glm::vec3 F = specular_fresnel(WOdotH, &diffuse_weight);
  if (pdf) *pdf = this->pdf(wi, WOdotH, D);
  // Cook-Torrance: D G F / (4 (n.l)(n.v)).
  float G;
  if (b.geometry_ == GeometryModel::kReference) {
    // Height-correlated Smith (Heitz 2014, eq. 99): 1 / (1 + Lambda(v) + Lambda(l)).
    G = 1.0f / (1.0f + lambda_o_ + SmithLambdaGGXAniso(wi, b.alpha_x_, b.alpha_y_));
  } else {
    // LearnOpenGL's GeometrySmith: G1(n.v) G1(n.l) with Schlick-GGX and k_direct.
    G = schlick_o_ * GeometrySchlickGGX(wi.z, k_direct(b.roughness_));
  }
  return D * G * F / (4.0f * wo_.z * wi.z) + eval_diffuse_and_ms(wi, diffuse_weight);
}

inline float BoundBrdf::pdf(glm::vec3 wi) const {
  if (wo_.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const glm::vec3 h = glm::normalize(wo_ + wi);
  return pdf(wi, glm::dot(wo_, h), DistributionGGXAniso(h, brdf_.alpha_x_, brdf_.alpha_y_));
}

inline glm::vec3 BoundBrdf::sample_direction(float u_lobe, glm::vec2 u) const {
  if (wo_.z <= 0.0f) return glm::vec3(0.0f);
  if (u_lobe < p_spec_)
    return reflect_about(wo_, sample_ggx_visible_normal(wo_, u, brdf_.alpha_x_, brdf_.alpha_y_));
  if (u_lobe < p_spec_ + p_b_)
    return reflect_about(wo_, sample_ggx_visible_normal(wo_, u, brdf_.bx_, brdf_.by_));
  return sample_cosine_hemisphere(u).direction;
}

inline BrdfSample BoundBrdf::sample(float u_lobe, glm::vec2 u) const {
  BrdfSample s;
  s.wi = sample_direction(u_lobe, u);
  if (s.wi.z <= 0.0f) return s;
  const glm::vec3 f = eval(s.wi, &s.pdf);
  if (!(s.pdf > 0.0f)) return s;
  s.weight = f * s.wi.z / s.pdf;
  s.valid = true;
  return s;
}

}  // namespace pbrkit
