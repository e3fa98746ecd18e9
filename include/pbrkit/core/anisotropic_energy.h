#pragma once
// Multiple-scattering compensation of the anisotropic GGX lobe (height-correlated Smith, a
// white conductor), reciprocal and energy conserving, that keeps the elongation of the
// highlight that the microsurface random walk gives (Heitz, Hanika, d'Eon & Dachsbacher 2016,
// "Multiple-Scattering Microfacet BSDFs with the Smith Model"; tests/support/microsurface_walk.h).
// With f_ss the single-scattering lobe at (alpha_x, alpha_y), E_ss its albedo and f_b the same
// lobe at the broadened alphas (beta alpha_x, beta alpha_y), each capped at 1:
//
//   f_ms(wo, wi) = h(wo) h(wi) f_b(wo, wi)
//                + (1 - E_tot(wo)) (1 - E_tot(wi)) / (pi (1 - E_tot_avg))
//
// The first term is f_b scaled symmetrically (reciprocal), h chosen so that its albedo is
// c = 0.9 of what the single scattering misses, h(wo) int f_b h(wi) cos dwi = c (1 - E_ss(wo)):
// a symmetric matrix scaling, solved at the table's nodes by the damped Sinkhorn iteration
// h <- sqrt(h c (1 - E_ss) / H). The second is Kulla & Conty 2017's lobe on what is left, with
// E_tot = E_ss + h H the first two terms' albedo, so a white metal reflects exactly 1 up to
// the tables' interpolation. beta depends on the lobe's aspect ratio rho = alpha_x / alpha_y
// (fitted to the walk's elongation, docs/MODEL.md "Anisotropic compensation against the
// walk"): 1.5 up to rho = 4.4, then 1.5 - 0.87 ln(rho / 4.4), at least 0.5 (once alpha_x is
// capped at 1 only alpha_y broadens, which rounds the lobe, so beta falls as rho grows).
//
// Tabulated over AnisotropicAlbedoTable's coordinates (ibl/anisotropic_albedo.h: sqrt(n.v),
// the folded azimuth p, sqrt(alpha_y), the strength sqrt((alpha_x - alpha_y) / (1 - alpha_y)))
// and nodes, three numbers a node (E_ss, h, E_tot), plus E_ss_avg and E_tot_avg per (r, s)
// node; baked into anisotropic_energy_data.inc by tools/tables/write_baked_table.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit {

class AnisotropicEnergyTable {
 public:
  static constexpr int kMu = 16, kPhi = 8, kR = 16, kS = 8;  ///< nodes per coordinate
  static constexpr int kLattice = 32;     ///< VNDF lattice points per side for each integral
  static constexpr int kIterations = 16;  ///< Sinkhorn iterations
  static constexpr float kShare = 0.9f;   ///< c: the broadened lobe's share of 1 - E_ss
  static constexpr std::size_t kNodes = std::size_t(kMu) * kPhi * kR * kS;

  /// The process's table (baked).
  static const AnisotropicEnergyTable& get();

  /// beta for the lobe (alpha_x, alpha_y); the broadened alphas are min(beta alpha, 1).
  static float broadening(float alpha_x, float alpha_y);
  static glm::vec2 broadened_alphas(float alpha_x, float alpha_y);

  struct Entry {
    float E_ss = 1.0f;   ///< single-scattering albedo at wo
    float h = 0.0f;      ///< the symmetric scaling of the broadened lobe
    float E_tot = 1.0f;  ///< E_ss + h(wo) int f_b(wo, wi) h(wi) cos dwi
  };
  /// The interpolated entry for wo (local frame, +X the anisotropy direction).
  Entry lookup(glm::vec3 wo, float alpha_x, float alpha_y) const;
  /// (E_ss_avg, E_tot_avg): 1 / pi int E cos dw over the hemisphere, interpolated.
  glm::vec2 averages(float alpha_x, float alpha_y) const;

  /// Computes what is baked: 3 numbers a node, node index ((l kR + k) kPhi + j) kMu + i,
  /// followed by the two averages of each (k, l) slice at (l kR + k).
  static std::vector<float> compute();
  /// The lobe of node (i, j, k, l), as AnisotropicAlbedoTable::node_lobe.
  static void node_lobe(int i, int j, int k, int l, glm::vec3& wo, float& alpha_x, float& alpha_y);
  /// The table's coordinates in [0, 1], as AnisotropicAlbedoTable::coordinates.
  static glm::vec4 coordinates(glm::vec3 wo, float alpha_x, float alpha_y);
  static std::size_t index(int i, int j, int k, int l) {
    return ((std::size_t(l) * kR + std::size_t(k)) * kPhi + std::size_t(j)) * kMu + std::size_t(i);
  }
  const std::vector<float>& values() const { return values_; }

 private:
  AnisotropicEnergyTable();
  std::vector<float> values_;  // compute()'s layout
};

}  // namespace pbrkit
