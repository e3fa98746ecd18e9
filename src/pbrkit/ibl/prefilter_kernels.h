#pragma once
// Private to the ibl module: the two inner loops of the specular prefilter, in
// structure-of-arrays form and vectorised with simd.h.
//  - SampleSet / sample_sum: the filtered-importance-sampled core of a lobe (Colbert &
//    Krivanek 2007): every sample's direction, face and texel coordinates computed for
//    simd::kLanes samples at once, then a trilinear RGBA fetch per sample.
//  - QuadratureSource / quadrature_sums: a direct quadrature over the texels of one level;
//    cosine_sum, the same loop for the irradiance cube (irradiance_cube.cpp).
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/ibl/cubemap.h"
#include "pbrkit/ibl/prefilter.h"

namespace pbrkit::detail {

/// The most levels a sampled source may have (a 32768 px face; kMaxFaceSize is 4096).
inline constexpr int kMaxSampledLevels = 16;

/// The samples of one level, in the local frame of R, padded with zero-weight samples to a
/// whole number of SIMD vectors. Each sample's trilinear lookup is split into its two
/// levels: weight n.l (1 - f) on level `level`, n.l f on level + 1.
struct SampleSet {
  std::vector<float> x, y, z;      // direction
  std::vector<float> w0, w1;       // weights of the two levels
  std::vector<float> half0, max0;  // level `level`: size / 2 and size - 1
  std::vector<float> half1, max1;  // level + 1 (unused when w1 = 0)
  std::vector<int> level;          // the finer level
  float weight_sum = 0.0f;         // sum of n.l over the samples
};

/// `samples` (from prefilter_samples) for lookups in `source`.
SampleSet make_sample_set(const std::vector<PrefilterSample>& samples, const Cubemap& source);

/// sum_i L(l_i) n.l_i over the set rotated to the frame of R (unit), L the trilinear lookup
/// of cube_lookup.h (face-clamped bilinear, linear between levels). `source` must have 4
/// channels.
glm::vec3 sample_sum(const Cubemap& source, const SampleSet& set, glm::vec3 R);

/// A source level flattened for the direct quadrature, face by face and row by row.
struct QuadratureSource {
  int size = 0;                       // face size
  std::vector<float> x, y, z;         // texel-centre directions
  std::vector<float> r, g, b, omega;  // L dOmega per channel, and dOmega
  // Row k (face k / size, y = k % size) lies on the points row_a[k] + s row_b[k], s in
  // [0, 1] (cube_face_point): lets the sums skip the texels behind R.
  std::vector<glm::vec3> row_a, row_b;
};

/// Level `level` of `cube` flattened for quadrature_sums() and cosine_sum().
QuadratureSource flatten_level(const Cubemap& cube, int level);

/// Sums over the source texels with R.l < cos_max of L w and w, w = max(0, R.l) / d^2 dOmega
/// where, with n = v = R, (n.h)^2 = (1 + R.l) / 2 and D(h) = alpha^2 / (pi d^2),
/// d = (n.h)^2 (alpha^2 - 1) + 1: so D(h) max(0, R.l) dOmega = alpha^2 / pi * w.
glm::vec4 quadrature_sums(const QuadratureSource& q, float alpha, glm::vec3 R, float cos_max);

/// The irradiance sum over the texels of L max(0, n.l) dOmega (RGB).
glm::vec3 cosine_sum(const QuadratureSource& q, glm::vec3 n);

}  // namespace pbrkit::detail
