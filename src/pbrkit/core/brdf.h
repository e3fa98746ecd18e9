#pragma once
// The metallic-roughness BRDF of docs/MODEL.md: Lambert diffuse plus GGX
// Cook-Torrance specular, with a selectable G ("reference" or "classic") and optional
// multiple-scattering energy compensation. One implementation for every renderer:
// the path tracer calls eval/sample/pdf, the GL shaders mirror eval line by line, and the
// baker's LUT integrates the same specular lobe.
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

class Brdf {
 public:
  Brdf(glm::vec3 base_color, float metallic, float roughness, const BrdfOptions& options = {});

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
  glm::vec3 eval_specular(glm::vec3 wo, glm::vec3 wi) const;
  glm::vec3 eval_diffuse_and_ms(glm::vec3 wo, glm::vec3 wi) const;

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

}  // namespace pbrkit
