// The half-buffer variance estimate: two interleaved halves of a pixel's samples are
// independent estimates of its mean, so their squared difference is an unbiased (if
// noisy: one degree of freedom) estimate of the sum of their variances. A box filter
// trades resolution for a usable estimate (Rousselle et al. 2012, section 4).
#include "pbrkit/util/parallel.h"
#include "stages.h"

namespace pbrkit::denoising {

Channels channels_from(const Image& image, int pad) {
  Channels out;
  out.reserve(std::size_t(image.channels));
  for (int c = 0; c < image.channels; ++c) out.push_back(plane_from(image, c, pad));
  return out;
}

Channels half_variance(const Channels& a, const Channels& b, int r) {
  Channels out;
  for (std::size_t c = 0; c < a.size(); ++c) {
    Plane d(a[c].width, a[c].height, a[c].pad);
    for (int y = 0; y < d.height; ++y) {
      const float* pa = a[c].row(y);
      const float* pb = b[c].row(y);
      float* pd = d.row(y);
      for (int x = 0; x < d.width; ++x) {
        const float diff = pa[x] - pb[x];
        pd[x] = 0.5f * diff * diff;
      }
    }
    fill_padding(d);
    out.push_back(r > 0 ? box_filter(d, r) : std::move(d));
  }
  return out;
}

Channels half_variance_relative(const Channels& a, const Channels& b, int r) {
  Channels out;
  constexpr float kFloor = 1e-2f;  // (a level of 0.1): dark pixels keep a variance
  for (std::size_t c = 0; c < a.size(); ++c) {
    Plane d(a[c].width, a[c].height, a[c].pad);
    for (int y = 0; y < d.height; ++y) {
      const float* pa = a[c].row(y);
      const float* pb = b[c].row(y);
      float* pd = d.row(y);
      for (int x = 0; x < d.width; ++x) {
        const float diff = pa[x] - pb[x];
        const float m = 0.5f * (pa[x] + pb[x]);
        pd[x] = 0.5f * diff * diff / (m * m + kFloor);
      }
    }
    fill_padding(d);
    Plane s = r > 0 ? box_filter(d, r) : std::move(d);
    for (int y = 0; y < s.height; ++y) {
      const float* pa = a[c].row(y);
      const float* pb = b[c].row(y);
      float* ps = s.row(y);
      for (int x = 0; x < s.width; ++x) {
        const float m = 0.5f * (pa[x] + pb[x]);
        ps[x] *= m * m + kFloor;
      }
    }
    fill_padding(s);
    out.push_back(std::move(s));
  }
  return out;
}

Plane channel_mean(const Channels& per_channel) {
  const Plane& first = per_channel.front();
  Plane out(first.width, first.height, first.pad);
  const float inv = 1.0f / float(per_channel.size());
  for (const Plane& p : per_channel)
    for (std::size_t i = 0; i < out.values.size(); ++i) out.values[i] += p.values[i] * inv;
  return out;
}

}  // namespace pbrkit::denoising
