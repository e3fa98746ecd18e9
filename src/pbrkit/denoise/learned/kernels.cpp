#include "pbrkit/denoise/learned/kernels.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "pbrkit/denoise/learned/layers.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit::learned {

namespace {

// The 2x2 box mean of channel i at cell (x, y) of `c`'s half-resolution grid, summed in
// PyTorch's avg_pool2d order (the top row, then the bottom one) and divided by 4.
inline float cell_mean(const RgbBuffer& c, int x, int y, int i) {
  const float* top = c.at(2 * x, 2 * y);
  const float* bottom = c.at(2 * x, 2 * y + 1);
  return (top[i] + top[3 + i] + bottom[i] + bottom[3 + i]) / 4.0f;
}

}  // namespace

RgbBuffer box_down(const RgbBuffer& c) {
  assert(c.width % 2 == 0 && c.height % 2 == 0);
  RgbBuffer out(c.width / 2, c.height / 2);
  pbrkit::parallel_for(0, out.height, [&](int y) {
    for (int x = 0; x < out.width; ++x)
      for (int i = 0; i < 3; ++i) out.at(x, y)[i] = cell_mean(c, x, y, i);
  });
  return out;
}

RgbBuffer apply_kernels(const HeadView& head, const RgbBuffer& c) {
  constexpr int r = kKernelWidth / 2;
  RgbBuffer out(c.width, c.height);
  pbrkit::parallel_for(0, c.height, [&](int y) {
    int rows[kKernelWidth];
    for (int dy = -r; dy <= r; ++dy) rows[dy + r] = std::clamp(y + dy, 0, c.height - 1);
    for (int x = 0; x < c.width; ++x) {
      // Softmax over the 25 logits, the largest subtracted first (as torch.softmax) so
      // that no exp overflows; a weight is never NaN for finite logits.
      const float* logit = head.at(x, y, c.width);
      float largest = logit[0];
      for (int k = 1; k < kKernelTaps; ++k) largest = std::max(largest, logit[k]);
      float w[kKernelTaps];
      float sum = 0.0f;
      for (int k = 0; k < kKernelTaps; ++k) sum += w[k] = std::exp(logit[k] - largest);
      for (int k = 0; k < kKernelTaps; ++k) w[k] /= sum;
      float acc[3] = {0.0f, 0.0f, 0.0f};
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          const float weight = w[(dy + r) * kKernelWidth + (dx + r)];
          const float* p = c.at(std::clamp(x + dx, 0, c.width - 1), rows[dy + r]);
          for (int i = 0; i < 3; ++i) acc[i] += weight * p[i];
        }
      float* o = out.at(x, y);
      for (int i = 0; i < 3; ++i) o[i] = acc[i];
    }
  });
  return out;
}

RgbBuffer blend_scales(const RgbBuffer& d, const HeadView& head, const RgbBuffer& coarse) {
  assert(head.channels >= kKernelTaps + 1);
  assert(coarse.width * 2 == d.width && coarse.height * 2 == d.height);
  RgbBuffer out(d.width, d.height);
  pbrkit::parallel_for(0, d.height, [&](int y) {
    for (int x = 0; x < d.width; ++x) {
      const float a = 1.0f / (1.0f + std::exp(-head.at(x, y, d.width)[kKernelTaps]));
      const float* fine = d.at(x, y);
      const float* low = coarse.at(x / 2, y / 2);
      float* o = out.at(x, y);
      for (int i = 0; i < 3; ++i) o[i] = fine[i] - a * cell_mean(d, x / 2, y / 2, i) + a * low[i];
    }
  });
  return out;
}

RgbBuffer blend_classic(const RgbBuffer& r0, const HeadView& head0, const RgbBuffer& classic) {
  assert(head0.channels == kKernelTaps + 2);
  assert(classic.width == r0.width && classic.height == r0.height);
  RgbBuffer out(r0.width, r0.height);
  pbrkit::parallel_for(0, r0.height, [&](int y) {
    for (int x = 0; x < r0.width; ++x) {
      const float b = 1.0f / (1.0f + std::exp(-head0.at(x, y, r0.width)[kKernelTaps + 1]));
      const float* r = r0.at(x, y);
      const float* k = classic.at(x, y);
      float* o = out.at(x, y);
      for (int i = 0; i < 3; ++i) o[i] = b * k[i] + (1.0f - b) * r[i];
    }
  });
  return out;
}

}  // namespace pbrkit::learned
