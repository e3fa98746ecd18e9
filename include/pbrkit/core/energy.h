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

/// Directional albedo of the rough dielectric interface of core/transmission.h (GGX,
/// height-correlated Smith, exact Fresnel), reflection plus transmission in importance
/// transport, for multiple-scattering compensation of rough glass (Kulla & Conty 2017, the
/// dielectric part; Cycles' multiscatter GGX glass tabulates the same): tables over
/// (mu, roughness, eta) for both sides of an interface, eta the ior of the far side over the
/// near side's, so one entry holds E seen from the rarer side (eta) and from the denser side
/// (1 / eta). The values are baked (dielectric_energy_data.inc, 4096 Hammersley VNDF points an
/// entry: the denser side's TIR ridge needs that many for 1e-3, which would take seconds at
/// start-up); DielectricEnergyTable.BakedEntriesMatchTheirQuadrature checks them and
/// tools/tables/write_baked_table regenerates them.
class DielectricEnergyTable {
 public:
  static constexpr int kMuSize = 32;         ///< mu nodes, i / (kMuSize - 1)
  static constexpr int kRoughnessSize = 32;  ///< roughness (sqrt alpha) nodes, j / (size - 1)
  static constexpr int kEtaSize = 16;        ///< nodes in x = (eta - 1) / (eta + 1), 0 .. 0.5
  static constexpr int kSamples = 4096;      ///< Hammersley VNDF samples per baked entry
  static constexpr std::size_t kEntries = std::size_t(2) * kEtaSize * kRoughnessSize * kMuSize;

  static const DielectricEnergyTable& get() {
    const DielectricEnergyTable* t = built_.load(std::memory_order_acquire);
    return t ? *t : build();
  }

  /// E(mu): the single-scattering albedo (reflection + transmission) seen from a side whose
  /// far side has `eta` times its ior (eta < 1: the denser side); interpolated.
  float E(float mu, float roughness, float eta) const;
  /// The cosine-weighted averages 2 int E mu dmu and 2 int R mu dmu (R: reflection alone)
  /// of the interpolant, seen from the side with ratio `eta`.
  glm::vec2 averages(float roughness, float eta) const;
  /// One entry by direct quadrature with `samples` points: (E, R) at mu, roughness, eta.
  static glm::vec2 integrate(float mu, float roughness, float eta, int samples);
  /// The ratio of eta node k (>= 1).
  static float eta_of_node(int k);
  /// Computes what is baked: E at every node, [side][k][j][i] (side 0 seen with eta_k,
  /// side 1 with 1 / eta_k; k eta, j roughness, i mu), and R_avg [side][k][j].
  static void compute(int samples, std::vector<float>& E, std::vector<float>& R_avg);

 private:
  static const DielectricEnergyTable& build();
  static inline std::atomic<const DielectricEnergyTable*> built_{nullptr};
  DielectricEnergyTable();
  // [side][(k * kRoughnessSize + j) * kMuSize + i]: side 0 seen with eta >= 1, side 1 with
  // 1 / eta; k the eta node, j roughness, i mu.
  std::vector<float> E_[2];
  std::vector<glm::vec2> avg_[2];  // [side][k * kRoughnessSize + j]: (E_avg, R_avg)
};

/// Kulla-Conty multiple-scattering quantities for a given F0, roughness and mu's.
/// Fms = Favg^2 E_avg / (1 - Favg (1 - E_avg)) (Kulla & Conty 2017, slide 18), so that
/// for F0 = 1 the single- plus multiple-scattering albedo is exactly 1.
glm::vec3 multiscatter_fresnel(glm::vec3 F0, float E_avg);

}  // namespace pbrkit
