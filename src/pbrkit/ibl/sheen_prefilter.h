#pragma once
// The Charlie-prefiltered sheen chain (BakeResult::sheen), as the Khronos Sample Viewer's
// "charlie" environment map and Filament's cloth IBL: the split sum (Karis 2013) applied to
// the sheen lobe of KHR_materials_sheen (core/sheen.h), with n = v = R. Level m holds
//   int L(l) D_Charlie(h) (n.l) dl / int D_Charlie(h) (n.l) dl,   h = (R + l) / |R + l|,
// for the sheen roughness mip_roughness(m, levels): a constant environment stays that
// constant. The lobe of l is a ring tens of degrees wide around R at every roughness
// (D_Charlie peaks at grazing half vectors), so every level, 0 included, is filtered, on a
// small grid (BakeOptions::sheen_grid_size) upsampled to the level's size (the GGX chain's;
// a halving chain of small faces, 32 px down to 1 px, left the rough levels at 1-2 px and
// 54-84% off in a lookup), by direct quadrature over a small source level
// (BakeOptions::sheen_source_size): importance sampling with sample_charlie and filtered importance
// sampling (as the GGX chain) was measured 33% off a brute-force reference at 256 samples per texel
// on the studio map at roughness 0.07 (the ring of l crosses the softboxes with a few samples
// each), and needed 4096 to come within 1%; the quadrature is exact up to the
// texel-centre rule. The scale of the split sum is the sheen LUT (ibl/sheen_lut.h).
#include <vector>

#include "pbrkit/ibl/bake.h"
#include "pbrkit/ibl/cubemap.h"
#include "pbrkit/ibl/prefilter.h"
#include "pbrkit/ibl/prefilter_kernels.h"
#include "pbrkit/util/progress.h"

namespace pbrkit {

/// Face size of the grid level `level` of the sheen chain is computed on:
/// min(options.face_size >> level, options.sheen_grid_size).
int sheen_grid_size(const BakeOptions& options, int level);

/// The level of `source` the quadrature for `roughness` reads: the finest with faces of at
/// most options.sheen_source_size px, half that (at least 8) for roughness >= 0.4.
int sheen_source_level(const Cubemap& source, const BakeOptions& options, float roughness);

/// The prefilter kernel D_Charlie(h) max(0, R.l) as a function of c = R.l alone (n = v = R:
/// sin^2(theta_h) = (1 - c) / 2), without its constant factor, tabulated over c in [0, 1].
struct SheenKernel {
  static constexpr int kSize = 1024;  ///< intervals; linear interpolation
  explicit SheenKernel(float roughness);
  std::vector<float> k;  ///< k[i] = ((1 - c) / 2)^(1 / (2r)) c at c = i / kSize
};

/// sum L(l) K(R.l) dOmega / sum K(R.l) dOmega over the texels of `q` (R unit): the
/// texel-centre quadrature of one prefiltered texel.
glm::vec3 sheen_quadrature(const detail::QuadratureSource& q, const SheenKernel& kernel,
                           glm::vec3 R);

/// The sheen chain of `source` (which needs its full mip chain): the GGX chain's levels and
/// sizes (specular_levels(face_size, min_face_size), face_size >> m px), level m for the
/// sheen roughness mip_roughness(m, levels, options.mapping), by direct quadrature over
/// sheen_source_level() on a sheen_grid_size() px grid, bilinearly upsampled to the level.
/// Stopped by `progress` (util/progress.h), it returns the levels finished before the stop
/// (a prefix of the chain, possibly empty).
Cubemap prefilter_sheen(const Cubemap& source, const BakeOptions& options,
                        const ProgressCallback& progress = {});

}  // namespace pbrkit
