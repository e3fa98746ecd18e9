#pragma once
// The pixel filter (PixelFilter, path_tracer.h), importance-sampled: a camera sample
// lands at an offset from the pixel centre drawn from the filter and has weight 1, so
// pixels are independent (no splatting) and films of sample ranges merge by addition.
#include <cmath>

#include <glm/glm.hpp>

#include "pbrkit/pt/path_tracer.h"

namespace pbrkit {

/// Inverse CDF of the tent filter of radius 1 (pbrt-v3 TriangleFilter sampling):
/// density 1 - |x| on [-1, 1].
inline float sample_tent(float u) {
  // -1 + sqrt(2 u) below 1/2, 1 - sqrt(2 - 2 u) above, with one square root and selects
  // (u is random: a branch here mispredicts half the time).
  const bool low = u < 0.5f;
  const float r = std::sqrt(low ? 2.0f * u : 2.0f - 2.0f * u);
  return low ? r - 1.0f : 1.0f - r;
}

/// The offset from the pixel centre, in pixels, of the sample drawn from `filter` with
/// `u` in [0, 1)^2.
inline glm::vec2 sample_pixel_filter(PixelFilter filter, glm::vec2 u) {
  return filter == PixelFilter::kTent ? glm::vec2(sample_tent(u.x), sample_tent(u.y)) : u - 0.5f;
}

}  // namespace pbrkit
