#pragma once
// Tabulated directional albedo of the GGX specular lobe, for multiple-scattering energy
// compensation (Kulla & Conty 2017, "Revisiting Physically Based Shading at Imageworks";
// Fdez-Aguera 2019, "A Multiple-Scattering Microfacet Model for Real-Time Image-Based
// Lighting"). Shared by the path tracer's BRDF, the baker's LUT and the GL renderer.
//
// With Schlick's Fresnel the single-scattering albedo is linear in F0:
//   E_ss(mu, F0) = F0 A(mu, r) + B(mu, r)      (Karis 2013's split-sum scale and bias)
// and E(mu, r) = A + B is the albedo of a white (F0 = 1) metal. E_avg(r) = 2 int E mu dmu.
// The tables are computed once per geometry model at first use (about 50 ms on 2 cores, within the
// 100 ms budget) by visible-normal sampling over Hammersley points, and are then
// immutable and thread-safe.
#include <array>
#include <atomic>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/core/microfacet.h"

namespace pbrkit {

class EnergyTable {
 public:
  static constexpr int kMuSize = 32;         ///< mu = n.v nodes, i / (kMuSize - 1)
  static constexpr int kRoughnessSize = 32;  ///< roughness nodes, j / (kRoughnessSize - 1)
  static constexpr int kSamples = 1024;      ///< Hammersley VNDF samples per entry

  /// The table for `model` (computed on first call; thread-safe). Inline and one atomic
  /// load once built: every BRDF construction asks for its table (twice per path vertex
  /// in the path tracer), and std::call_once costs about 45 instructions a call.
  static const EnergyTable& get(GeometryModel model) {
    const EnergyTable* t = built_[std::size_t(model)].load(std::memory_order_acquire);
    return t ? *t : build(model);
  }

  /// Split-sum scale and bias, bilinearly interpolated; mu in [0,1], roughness in [0,1].
  glm::vec2 AB(float mu, float roughness) const;
  /// E(mu) = A + B: the albedo of the single-scattering lobe for F0 = 1.
  float E(float mu, float roughness) const;
  /// Cosine-weighted averages 2 int A mu dmu and 2 int B mu dmu (interpolated in roughness).
  glm::vec2 AB_avg(float roughness) const;
  float E_avg(float roughness) const {
    const glm::vec2 ab = AB_avg(roughness);
    return ab.x + ab.y;
  }

  /// Computes one entry directly (not interpolated) with `samples` VNDF samples:
  /// used to build the table and by tests.
  static glm::vec2 integrate_AB(GeometryModel model, float mu, float roughness, int samples);

  GeometryModel model() const { return model_; }

 private:
  static const EnergyTable& build(GeometryModel model);
  static inline std::array<std::atomic<const EnergyTable*>, 3> built_{};
  explicit EnergyTable(GeometryModel model);
  GeometryModel model_;
  std::vector<glm::vec2> ab_;      // [j * kMuSize + i]
  std::vector<glm::vec2> ab_avg_;  // [j]
};

/// Kulla-Conty multiple-scattering quantities for a given F0, roughness and mu's.
/// Fms = Favg^2 E_avg / (1 - Favg (1 - E_avg)) (Kulla & Conty 2017, slide 18), so that
/// for F0 = 1 the single- plus multiple-scattering albedo is exactly 1.
glm::vec3 multiscatter_fresnel(glm::vec3 F0, float E_avg);

}  // namespace pbrkit
