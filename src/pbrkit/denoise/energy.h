#pragma once
// How far a denoised image moves the energy of a region, in units of the raw image's own
// standard error. The raw image is the mean of the two half buffers; each pixel's half
// difference d = (a - b) / 2 has the same variance as its mean (a + b) / 2 (a and b are
// independent with equal variance), so for a region R of N pixels the standard error of
// the raw region mean is estimated by sqrt(sum_R d^2) / N (docs/DENOISER.md, "Energy").
// A denoiser that keeps energy moves a region's mean by what crosses its border only, so
// |denoised mean - raw mean| / that error should stay below about 2 for every region
// larger than the filter window.
#include <vector>

#include "pbrkit/denoise/denoiser.h"

namespace pbrkit {

/// One region's deviation: the raw and denoised means (channel mean), the raw mean's
/// standard error and z = (denoised - raw) / error.
struct RegionEnergy {
  int id = -1;  ///< the block index (row-major) or the object id
  std::size_t pixels = 0;
  double raw = 0.0, denoised = 0.0, error = 0.0, z = 0.0;
};

struct EnergyReport {
  RegionEnergy frame;
  std::vector<RegionEnergy> blocks;   ///< blocks of block x block pixels (edges: smaller)
  std::vector<RegionEnergy> objects;  ///< per id of `ids` (>= 0), when given
  /// The region of largest |z| among blocks and objects (id -1 when there are none).
  RegionEnergy worst_block, worst_object;
};

/// Measures `denoised` against the mean of `input`'s colour halves: the whole frame,
/// blocks of `block` x `block` pixels and, when `ids` holds one id per pixel (negative:
/// none), every object of at least `min_pixels` pixels. Regions whose raw error is 0 get
/// z = 0 when the means agree exactly and +-infinity otherwise.
EnergyReport measure_energy(const DenoiseInput& input, const Image& denoised, int block,
                            const std::vector<int>* ids = nullptr, std::size_t min_pixels = 16);

}  // namespace pbrkit
