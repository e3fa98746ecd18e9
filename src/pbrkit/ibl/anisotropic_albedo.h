#pragma once
// The single-scattering albedo of an anisotropic GGX lobe without Fresnel (height-correlated
// Smith), integral of D G2 / (4 n.v) over the hemisphere, = E[G2 / G1(wo)] over the visible
// normals: what the lobe reflects of a uniform white environment. The OpenGL renderer's
// anisotropic image-based light scales its few taps' normalized mean by it
// (ibl/anisotropic_taps.h): a handful of taps estimates where the lobe gathers light well
// but its albedo badly (the horizon cuts the stretched lobe), so the albedo comes from
// this table, tabulated once from many points and read with one interpolation per pixel.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit {

/// The albedo for `wo` (local frame: n = +Z, +X the anisotropy direction; wo.z > 0) and
/// the lobe's alpha_x, alpha_y, integrated with a fixed polar lattice of `radii` x
/// `angles` points on Heitz 2018's disk (the visible normals' sampler, so each point has
/// the same weight).
float anisotropic_albedo(glm::vec3 wo, float alpha_x, float alpha_y, int radii = 32,
                         int angles = 64);

/// anisotropic_albedo tabulated over (sqrt(n.v), dense towards grazing where the albedo
/// changes fastest, p = |wo.y| / (|wo.x| + |wo.y|), the azimuth
/// folded into [0, pi/2] and measured without an arc tangent, r = sqrt(alpha_y), s =
/// sqrt((alpha_x - alpha_y) / (1 - alpha_y))): alpha_y is the smaller alpha
/// (KHR_materials_anisotropy's alpha_b; the lobe is symmetric under swapping the axes with
/// the azimuth) and s how far alpha_x has been stretched towards 1 (KHR_materials_anisotropy's
/// strength: alpha_t = mix(alpha_b, 1, strength^2)). Each
/// coordinate's n nodes sit at i / (n - 1), both ends included (normal incidence and full
/// strength are common): a coordinate c maps to c (n - 1) and is interpolated linearly
/// between the nodes around it; so the OpenGL renderer reads it as a 3D texture with linear
/// filtering at (c (n - 1) + 0.5) / n ((mu, p, r) by the hardware; each texel holds two
/// neighbours along s) and gets the same numbers.
class AnisotropicAlbedoTable {
 public:
  static constexpr int kMu = 16, kPhi = 8, kR = 16, kS = 8;  ///< nodes per coordinate

  /// The process's table: compute()'s nodes, baked into the library
  /// (anisotropic_albedo_data.inc, written by tools/tables/write_baked_table; about 1 s of
  /// CPU time to make).
  static const AnisotropicAlbedoTable& get();

  /// Every node's anisotropic_albedo, in values()'s order.
  static std::vector<float> compute();

  /// The table's coordinates in [0, 1] for wo and the two alphas.
  static glm::vec4 coordinates(glm::vec3 wo, float alpha_x, float alpha_y);

  /// The albedo interpolated from the table.
  float lookup(glm::vec3 wo, float alpha_x, float alpha_y) const;

  /// The node (i, j, k, l): sqrt(n.v), p, r and s's indices.
  float node(int i, int j, int k, int l) const { return values_[index(i, j, k, l)]; }
  /// Where node (i, j, k, l) lies in values().
  static std::size_t index(int i, int j, int k, int l) {
    return ((std::size_t(l) * kR + std::size_t(k)) * kPhi + std::size_t(j)) * kMu + std::size_t(i);
  }
  /// All nodes, mu fastest, then p, r and s.
  const std::vector<float>& values() const { return values_; }

  /// What node (i, j, k, l) holds the albedo of: (wo, alpha_x, alpha_y).
  static void node_lobe(int i, int j, int k, int l, glm::vec3& wo, float& alpha_x, float& alpha_y);

 private:
  AnisotropicAlbedoTable();
  std::vector<float> values_;
};

}  // namespace pbrkit
