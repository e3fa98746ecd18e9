#pragma once
// The denoiser's working format: one float plane per channel, padded on every side by
// copies of the edge pixels, so that the filters' inner loops read neighbours without
// bounds checks (and vectorise). Also the box filter and the fast exp(-x) the weights use.
#include <bit>
#include <cstdint>
#include <vector>

#include "pbrkit/image/image.h"

namespace pbrkit::denoising {

struct Plane {
  int width = 0, height = 0, pad = 0, stride = 0;
  std::vector<float> values;

  Plane() = default;
  Plane(int w, int h, int p)
      : width(w),
        height(h),
        pad(p),
        stride(w + 2 * p),
        values(std::size_t(w + 2 * p) * std::size_t(h + 2 * p), 0.0f) {}

  /// Row y (valid for -pad <= y < height + pad); [x] valid for -pad <= x < width + pad.
  float* row(int y) { return values.data() + std::size_t(y + pad) * stride + pad; }
  const float* row(int y) const { return values.data() + std::size_t(y + pad) * stride + pad; }
  float& at(int x, int y) { return row(y)[x]; }
  float at(int x, int y) const { return row(y)[x]; }
};

/// Channel `c` of `image`, padded by `pad` (clamp to edge).
Plane plane_from(const Image& image, int c, int pad);
/// Copies the edge pixels into the padding.
void fill_padding(Plane& plane);
/// Mean over the (2r+1)^2 box around each pixel (edges clamped); same padding as `in`
/// (which must be at least r), padding filled.
Plane box_filter(const Plane& in, int r);

/// exp(-x) for x >= 0 (x is clamped to [0, 80]): 2^(-x log2 e) split into an integer
/// power built in the exponent bits and a degree-6 polynomial for the fraction; relative
/// error below 2e-5, branch-free so that the weight loops vectorise. NaN counts as
/// 80 (a weight of about 2e-35), never as a weight of 1.
inline float exp_neg(float x) {
  x = x < 80.0f ? x : 80.0f;
  x = x > 0.0f ? x : 0.0f;
  const float t = -x * 1.44269504f;  // log2 of the result, in [-115.5, 0]
  const int i = int(t);              // truncation: i >= t, so f in (-1, 0]
  const float f = (t - float(i)) * 0.693147181f;
  // e^f, Taylor to degree 6 (|f| < ln 2).
  const float p =
      1.0f + f * (1.0f + f * (0.5f + f * (1.0f / 6 +
                                          f * (1.0f / 24 + f * (1.0f / 120 + f * (1.0f / 720))))));
  const float scale = std::bit_cast<float>(std::uint32_t(i + 127) << 23);
  return p * scale;
}

/// The NL-means patch distance (Buades et al. 2005 with the variance cancellation of
/// Rousselle et al. 2012, eq. 4) between p = (x, y) and q = p + (dx, dy) for the rows
/// [y0, y1) and every x:
///   d(p, q) = mean over the patch and the channels of
///             ((u_p - u_q)^2 - (v_p + min(v_p, v_q))) / (eps + v_p + v_q),
/// with u the guide and v its variance (per channel, or one plane shared by all channels
/// when `variance` has one entry). Sensitivity k is applied by the caller (d / k^2).
/// Writes (y1 - y0) * width floats to `out`; `scratch` is resized as needed. The planes'
/// padding must be at least max(|dx|, |dy|) + patch_radius.
/// With `symmetric`, the cancellation subtracts v_p + v_q (the unbiased estimate of the
/// squared difference of the means) and d(p, q) = d(q, p) (docs/DENOISER.md, "Energy").
void patch_distance(const std::vector<const Plane*>& guide,
                    const std::vector<const Plane*>& variance, int dx, int dy, int patch_radius,
                    int y0, int y1, float* out, std::vector<float>& scratch,
                    bool symmetric = false);

}  // namespace pbrkit::denoising
