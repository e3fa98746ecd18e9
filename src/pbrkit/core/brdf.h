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
#include <string_view>

#include <glm/glm.hpp>

#include "pbrkit/core/energy.h"
#include "pbrkit/core/microfacet.h"

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

inline BoundBrdf Brdf::at(glm::vec3 wo) const {
  return BoundBrdf(*this, wo);
}

}  // namespace pbrkit
