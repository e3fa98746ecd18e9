// Energy-conserving outlier (firefly) treatment. A path that finds a small, very bright
// light through a rough reflection gives one sample worth hundreds of ordinary ones: the
// pixel's half mean is far above anything around it, the half-buffer variance there is
// dominated by that one sample, and the cross filter's SURE estimate (which assumes noise
// that a few samples describe) is wrong, so the filter turns the firefly into a blotch.
//
// Detection, per half and pixel, on the channel mean: the pixel is an outlier when it is
// above T = max(the other half at the same pixel, the 90th percentile of both halves'
// values in the (2r+1)^2 window around it) + k * 1.4826 MAD of those values, a robust
// version of the usual "k-th largest of the neighbourhood plus several standard
// deviations" rule
// (DeCoro et al. 2010, "Density-based Outlier Rejection in Monte Carlo Rendering", reject
// samples by their neighbourhood; the other half is the same pixel's independent
// estimate, so a value both halves share is signal, not a firefly).
//
// Treatment: the pixel is scaled down to T and its excess is not dropped but spread over
// the pixels around it (the filter's window), weighted by how alike their features are
// (the cross filter's feature weight), with normalised weights, half of it into each
// half buffer. So the mean of the two halves summed over any region that contains the
// spread window keeps its energy exactly, as in Zirr, Hanika and Dachsbacher 2018,
// "Re-Weighting Firefly Samples for Improved Finite-Sample Monte Carlo Estimates" (who
// redistribute a firefly's weight rather than clamping it; we do it in image space, once,
// over a window instead of over sample cascades). Everything after this stage (the
// variance, the colour weights, SURE and the averages) sees the treated halves.
#include <algorithm>
#include <cmath>

#include "pbrkit/util/parallel.h"
#include "stages.h"

namespace pbrkit::denoising {

namespace {
struct Outlier {
  int x, y, half;
  float excess[3];
};
}  // namespace

int spread_outliers(Channels color[2], const std::vector<const Feature*>& features,
                    const DenoiseOptions& options,
                    const std::vector<unsigned char>* direct_environment) {
  if (options.outlier_k <= 0.0f || options.outlier_radius <= 0) return 0;
  const int w = color[0].front().width, h = color[0].front().height;
  const int r = options.outlier_radius;
  // A pixel that saw only the environment is a lookup, not a Monte Carlo estimate of the
  // scene: it has no firefly of its own, and an excess spread into it from a silhouette
  // beside it would leave the scene's region (the feature weight is weak across a
  // silhouette, where the features' gradient is steep).
  auto environment = [&](int x, int y) {
    return direct_environment &&
           (*direct_environment)[std::size_t(y) * std::size_t(w) + std::size_t(x)];
  };
  // The channel mean of each half (scaled before summing: no overflow near FLT_MAX).
  std::vector<float> level[2];
  for (int half = 0; half < 2; ++half) {
    level[half].resize(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        float m = 0.0f;
        for (int c = 0; c < 3; ++c) m += color[half][std::size_t(c)].at(x, y) / 3.0f;
        level[half][std::size_t(y) * w + x] = m;
      }
  }
  std::vector<std::vector<Outlier>> rows(static_cast<std::size_t>(h));
  const float k = options.outlier_k;
  const float quantile = std::clamp(options.outlier_quantile, 0.5f, 1.0f);
  pbrkit::parallel_for(0, h, [&](int y) {
    std::vector<float> values, deviation;
    for (int x = 0; x < w; ++x)
      for (int half = 0; half < 2; ++half) {
        const float v = level[half][std::size_t(y) * w + x];
        const float other = level[1 - half][std::size_t(y) * w + x];
        if (!(v > other) || environment(x, y)) continue;
        // The window's values (both halves, without the pixel itself).
        values.clear();
        for (int qy = std::max(0, y - r); qy <= std::min(h - 1, y + r); ++qy)
          for (int qx = std::max(0, x - r); qx <= std::min(w - 1, x + r); ++qx)
            for (int g = 0; g < 2; ++g) {
              if (qx == x && qy == y && g == half) continue;
              values.push_back(level[g][std::size_t(qy) * w + qx]);
            }
        if (values.size() < 3) continue;
        // The base: the window's 90th percentile (and the other half). The second largest
        // value, the usual "k-th largest" rule, lets rare bright samples that fall close
        // together (two in one window, likely under a small bright light) hide each
        // other; the 90th percentile ignores up to a tenth of the window being outliers
        // and still covers an edge of real signal (a light seen directly, a highlight)
        // that fills more than a tenth of it. The spread: 1.4826 times the median
        // absolute deviation (a Gaussian's sigma).
        const auto upper = values.begin() + std::ptrdiff_t(quantile * float(values.size() - 1));
        std::nth_element(values.begin(), upper, values.end());
        const float base = std::max(other, *upper);
        const auto mid = values.begin() + std::ptrdiff_t(values.size() / 2);
        std::nth_element(values.begin(), mid, values.end());
        const float median = *mid;
        deviation.clear();
        for (float q : values) deviation.push_back(std::abs(q - median));
        const auto dmid = deviation.begin() + std::ptrdiff_t(deviation.size() / 2);
        std::nth_element(deviation.begin(), dmid, deviation.end());
        const float threshold = std::max(0.0f, base + k * 1.4826f * *dmid);
        if (!(v > threshold)) continue;
        Outlier o{x, y, half, {}};
        const float keep = threshold / v;
        for (int c = 0; c < 3; ++c) {
          float& value = color[half][std::size_t(c)].at(x, y);
          o.excess[c] = value * (1.0f - keep);
          value *= keep;  // disjoint pixels per row: safe in parallel
        }
        rows[std::size_t(y)].push_back(o);
      }
  });
  // Spread every excess, in a fixed order (the output does not depend on the threads).
  const int s = std::max(0, options.outlier_spread_radius);
  std::vector<float> weight;
  int count = 0;
  for (const auto& row : rows)
    for (const Outlier& o : row) {
      ++count;
      const int qx0 = std::max(0, o.x - s), qx1 = std::min(w - 1, o.x + s);
      const int qy0 = std::max(0, o.y - s), qy1 = std::min(h - 1, o.y + s);
      weight.clear();
      double total = 0.0;
      for (int qy = qy0; qy <= qy1; ++qy)
        for (int qx = qx0; qx <= qx1; ++qx) {
          if (environment(qx, qy)) {
            weight.push_back(0.0f);
            continue;
          }
          // The cross filter's feature weight (Rousselle et al. 2013, eq. 9).
          float d = 0.0f;
          for (const Feature* f : features) {
            float sq = 0.0f;
            for (const Plane& p : f->mean) {
              const float diff = p.at(o.x, o.y) - p.at(qx, qy);
              sq += diff * diff;
            }
            const float vp = f->variance.at(o.x, o.y), vq = f->variance.at(qx, qy);
            d = std::max(d, (sq / float(f->mean.size()) - (vp + std::min(vp, vq))) *
                                f->inv_norm.at(o.x, o.y));
          }
          const float wq = exp_neg(d);
          weight.push_back(wq);
          total += wq;
        }
      // total >= the pixel's own weight, exp(-0) = 1.
      std::size_t i = 0;
      for (int qy = qy0; qy <= qy1; ++qy)
        for (int qx = qx0; qx <= qx1; ++qx, ++i) {
          const float share = float(0.5 * weight[i] / total);
          for (int half = 0; half < 2; ++half)
            for (int c = 0; c < 3; ++c)
              color[half][std::size_t(c)].at(qx, qy) += share * o.excess[c];
        }
    }
  for (int half = 0; half < 2; ++half)
    for (Plane& p : color[half]) fill_padding(p);
  return count;
}

}  // namespace pbrkit::denoising
