#pragma once
// The input transform `log1p-autoexposure-v1` (docs/LEARNED_DENOISER.md, "Input"; the
// PyTorch twin is tools/denoiser/model.py's sanitize, autoexposure and network_input).
#include <algorithm>
#include <cmath>

#include "pbrkit/image/image.h"

namespace pbrkit::learned {

/// A colour value as the network takes it: non-finite or negative values are 0.
inline float sanitize_color(float v) {
  return std::isfinite(v) && v > 0.0f ? v : 0.0f;
}
/// An albedo value: NaN is 0, the rest clamped to [0, 1] (infinities to the ends).
inline float sanitize_albedo(float v) {
  return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
}
/// A normal component: NaN is 0, the rest clamped to [-1, 1].
inline float sanitize_normal(float v) {
  return std::isnan(v) ? 0.0f : std::clamp(v, -1.0f, 1.0f);
}

/// The autoexposure s of the whole image: 0.18 over the geometric mean of the 16x16
/// blocks' mean luminance (blocks from the top-left corner, those on the right and bottom
/// edges smaller; only blocks whose mean exceeds 1e-8 count), in double precision; 1 when
/// no block counts. `color`'s values are sanitised (sanitize_color) first.
double autoexposure(const Image& color);

/// The 9 input channels of pixel (x, y) of the images, for exposure `s`: log1p(s * RGB),
/// albedo RGB, normal XYZ; and its linear colour, sanitised. The log is taken in double
/// precision, as model.py's network_input does.
void network_input_pixel(const Image& color, const Image& albedo, const Image& normal, double s,
                         int x, int y, float* input9, float* rgb);

/// kpcn-blend-v2's 3 more input channels of pixel (x, y): log1p(s * classic RGB), `s` the
/// noisy colour's autoexposure; and the classic output's linear colour, sanitised.
void classic_input_pixel(const Image& classic, double s, int x, int y, float* input3, float* rgb);

}  // namespace pbrkit::learned
