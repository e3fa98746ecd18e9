// The half-buffer variance estimate: two interleaved halves of a pixel's samples are
// independent estimates of its mean, so their squared difference is an unbiased (if
// noisy: one degree of freedom) estimate of the sum of their variances. A box filter
// trades resolution for a usable estimate (Rousselle et al. 2012, section 4).
#include <algorithm>
#include <cmath>

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

namespace {
constexpr float kFloor = 1e-2f;  // (a level of 0.1): dark pixels keep a variance

// The mean of `d` over the (2r+1)^2 box around each pixel, over the pixels whose level
// (the mean of the halves a and b, plus the floor's 0.1) is within a factor `ratio` of the
// pixel's own. A quiet pixel beside a much brighter or darker noisy one (a light's edge, a
// silhouette) keeps its own relative variance instead of taking in the other's.
Plane level_guided_box(const Plane& d, const Plane& a, const Plane& b, int r, float ratio) {
  // Each pixel's level once (the padding too: a and b are padded at least r), not once per
  // tap of every box that reads it.
  Plane level(d.width, d.height, d.pad);
  for (int y = -d.pad; y < d.height + d.pad; ++y)
    for (int x = -d.pad; x < d.width + d.pad; ++x)
      level.at(x, y) = std::abs(0.5f * (a.at(x, y) + b.at(x, y))) + 0.1f;
  Plane out(d.width, d.height, d.pad);
  pbrkit::parallel_for(0, d.height, [&](int y) {
    for (int x = 0; x < d.width; ++x) {
      const float lp = level.at(x, y);
      float sum = 0.0f;
      int n = 0;
      for (int qy = y - r; qy <= y + r; ++qy)
        for (int qx = x - r; qx <= x + r; ++qx) {
          const float lq = level.at(qx, qy);
          if (std::max(lp, lq) > ratio * std::min(lp, lq)) continue;
          sum += d.at(qx, qy);
          ++n;
        }
      out.at(x, y) = sum / float(std::max(n, 1));
    }
  });
  fill_padding(out);
  return out;
}
}  // namespace

Channels half_variance_relative(const Channels& a, const Channels& b, int r, float level_ratio) {
  Channels out;
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
    Plane s = r <= 0               ? std::move(d)
              : level_ratio > 0.0f ? level_guided_box(d, a[c], b[c], r, level_ratio)
                                   : box_filter(d, r);
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
