// The feature prefilter (Rousselle et al. 2013, section 4.1): features are noisy too
// (anti-aliased edges, depth of field, and albedo and normals seen through rough
// reflections), so each is NL-means filtered with its own variance before it guides the
// colour filter. Both halves are filtered with the same weights, so the difference of the
// filtered halves still estimates the variance left in the prefiltered feature.
#include <algorithm>

#include "pbrkit/util/parallel.h"
#include "stages.h"

namespace pbrkit::denoising {

namespace {
constexpr int kStrip = 16;       // rows per parallel work item
constexpr int kPatchRadius = 1;  // 3x3 patches for the features
}  // namespace

Feature prefilter_feature(const Channels& a, const Channels& b, const DenoiseOptions& options,
                          float tau) {
  const int w = a.front().width, h = a.front().height, pad = a.front().pad;
  const int channels = int(a.size());
  const int r = options.prefilter_radius;
  // The mean of the halves and the variance of that mean (half a half's).
  Channels mean;
  for (int c = 0; c < channels; ++c) {
    Plane m(w, h, pad);
    for (std::size_t i = 0; i < m.values.size(); ++i)
      m.values[i] = 0.5f * (a[std::size_t(c)].values[i] + b[std::size_t(c)].values[i]);
    mean.push_back(std::move(m));
  }
  Plane mean_variance = channel_mean(half_variance(a, b, options.variance_radius));
  for (float& v : mean_variance.values) v *= 0.5f;

  Feature out;
  if (r <= 0) {
    out.mean = std::move(mean);
    out.variance = std::move(mean_variance);
  } else {
    Channels fa, fb;
    for (int c = 0; c < channels; ++c) {
      fa.emplace_back(w, h, pad);
      fb.emplace_back(w, h, pad);
    }
    std::vector<const Plane*> guide, variance{&mean_variance};
    for (const Plane& p : mean) guide.push_back(&p);
    const int strips = (h + kStrip - 1) / kStrip;
    pbrkit::parallel_for(0, strips, [&](int s) {
      const int y0 = s * kStrip, y1 = std::min(h, y0 + kStrip);
      const std::size_t n = std::size_t(y1 - y0) * w;
      std::vector<float> dist(n), weight_sum(n, 0.0f), scratch;
      std::vector<float> sum_a(n * channels, 0.0f), sum_b(n * channels, 0.0f);
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          patch_distance(guide, variance, dx, dy, kPatchRadius, y0, y1, dist.data(), scratch);
          const int x0 = std::max(0, -dx), x1 = std::min(w, w - dx);
          for (int y = y0; y < y1; ++y) {
            if (y + dy < 0 || y + dy >= h) continue;
            const std::size_t o = std::size_t(y - y0) * w;
            for (int x = x0; x < x1; ++x) dist[o + x] = exp_neg(dist[o + x]);
            for (int x = x0; x < x1; ++x) weight_sum[o + x] += dist[o + x];
            for (int c = 0; c < channels; ++c) {
              const float* qa = a[std::size_t(c)].row(y + dy) + dx;
              const float* qb = b[std::size_t(c)].row(y + dy) + dx;
              float* sa = sum_a.data() + n * c + o;
              float* sb = sum_b.data() + n * c + o;
              for (int x = x0; x < x1; ++x) {
                sa[x] += dist[o + x] * qa[x];
                sb[x] += dist[o + x] * qb[x];
              }
            }
          }
        }
      for (int c = 0; c < channels; ++c)
        for (int y = y0; y < y1; ++y) {
          const std::size_t o = std::size_t(y - y0) * w;
          float* da = fa[std::size_t(c)].row(y);
          float* db = fb[std::size_t(c)].row(y);
          for (int x = 0; x < w; ++x) {
            const float inv = 1.0f / weight_sum[o + x];  // >= 1: the pixel itself weighs 1
            da[x] = sum_a[n * c + o + x] * inv;
            db[x] = sum_b[n * c + o + x] * inv;
          }
        }
    });
    for (int c = 0; c < channels; ++c) {
      fill_padding(fa[std::size_t(c)]);
      fill_padding(fb[std::size_t(c)]);
      Plane m(w, h, pad);
      for (std::size_t i = 0; i < m.values.size(); ++i)
        m.values[i] = 0.5f * (fa[std::size_t(c)].values[i] + fb[std::size_t(c)].values[i]);
      out.mean.push_back(std::move(m));
    }
    // The variance of the prefiltered mean: a quarter of the squared difference of the
    // filtered halves, smoothed.
    out.variance = channel_mean(half_variance(fa, fb, options.variance_radius));
    for (float& v : out.variance.values) v *= 0.5f;
  }
  // Rousselle et al. 2013, eq. 9: the feature distance is normalised by
  // k_f^2 max(tau, Var, |grad|^2), which relaxes it across slopes (depth on a tilted
  // plane) and where the feature is still noisy.
  out.inv_norm = Plane(w, h, pad);
  const float k2 = options.feature_k * options.feature_k;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float g2 = 0.0f;
      for (const Plane& p : out.mean) {
        const float gx = 0.5f * (p.at(x + 1, y) - p.at(x - 1, y));
        const float gy = 0.5f * (p.at(x, y + 1) - p.at(x, y - 1));
        g2 += gx * gx + gy * gy;
      }
      g2 *= options.feature_gradient / float(channels);
      const float norm = std::max({tau, out.variance.at(x, y), g2});
      out.inv_norm.at(x, y) = 1.0f / (k2 * norm);
    }
  return out;
}

}  // namespace pbrkit::denoising
