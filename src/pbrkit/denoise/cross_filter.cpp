// The candidate filters (Rousselle et al. 2013, section 4.2): each half buffer is filtered
// with weights computed from the other half's colour and from the prefiltered features.
// Weights that do not depend on the data they average keep the noise of the weights out
// of the result (no correlated blotches) and make the filter linear in its data, so that
// Stein's unbiased risk estimate of its error is exact (section 4.3).
#include <algorithm>

#include "pbrkit/util/error.h"
#include "pbrkit/util/parallel.h"
#include "stages.h"

namespace pbrkit::denoising {

namespace {
constexpr int kStrip = 8;  // rows per parallel work item

// s[x] += a[x] * b[x] over [x0, x1): the first-order fit's normal-equation sums, most of
// the denoiser's time. Built twice, for AVX2's eight lanes and for x86-64's SSE2 four, and
// the first call picks the one the CPU runs (a branch, not target_clones' ifunc, whose
// resolver crashed the ThreadSanitizer build at start-up). Each element sees the same
// multiply and add in either (no fused multiply-add: -ffp-contract=off), so the image is
// the same bit for bit on any x86-64.
[[gnu::target("avx2")]] void add_products_avx2(float* __restrict s, const float* __restrict a,
                                               const float* __restrict b, int x0, int x1) {
  for (int x = x0; x < x1; ++x) s[x] += a[x] * b[x];
}
void add_products_sse2(float* __restrict s, const float* __restrict a, const float* __restrict b,
                       int x0, int x1) {
  for (int x = x0; x < x1; ++x) s[x] += a[x] * b[x];
}
void add_products(float* s, const float* a, const float* b, int x0, int x1) {
  static const bool avx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  (avx2 ? add_products_avx2 : add_products_sse2)(s, a, b, x0, x1);
}

// One filtered half at one pixel: its colour, its derivative in the pixel's own value and
// its variance.
struct HalfEstimate {
  float rgb[3];
  float dfdc, variance;
};

// Stores a candidate's two filtered halves at (x, y) and, per half, its SURE estimate
// (Stein 1981; Li et al. 2012): for a filter F linear in data of variance s^2,
// E[|F - mu|^2] = E[|F - c_p|^2] - s_p^2 + 2 s_p^2 dF/dc_p. The average of the two
// filtered halves has their bias and a quarter of their summed variance, so from one half
// alone its error is that half's SURE less half the half's variance.
void store_candidate(const CrossFilterInput& input, const Plane mean_variance[2], int x, int y,
                     const HalfEstimate halves[2], Candidates& out, std::size_t k) {
  for (int half = 0; half < 2; ++half) {
    const HalfEstimate& e = halves[half];
    const float s2 = mean_variance[half].at(x, y);
    float sq = 0.0f;
    for (int c = 0; c < 3; ++c) {
      const float d = e.rgb[c] - (*input.color[half])[std::size_t(c)].at(x, y);
      sq += d * d;
      out.color[half][k][std::size_t(c)].at(x, y) = e.rgb[c];
    }
    out.error[half][k].at(x, y) = sq / 3.0f - s2 + 2.0f * s2 * e.dfdc - 0.5f * e.variance;
  }
}
}  // namespace

Candidates cross_filter(const CrossFilterInput& input, const DenoiseOptions& options,
                        const std::function<bool()>& tick, int* strip_count) {
  const Channels& c0 = *input.color[0];
  const int w = c0.front().width, h = c0.front().height, pad = c0.front().pad;
  const int r = options.radius;
  const int k_count = int(options.candidates.size());
  // Per half: its colour and the channel mean of its variance.
  Plane mean_variance[2] = {channel_mean(*input.variance[0]), channel_mean(*input.variance[1])};
  std::vector<const Plane*> guide[2], guide_variance[2];
  for (int g = 0; g < 2; ++g)
    for (int c = 0; c < 3; ++c) {
      guide[g].push_back(&(*input.color[g])[std::size_t(c)]);
      guide_variance[g].push_back(&(*input.variance[g])[std::size_t(c)]);
    }
  std::vector<float> inv_k2(std::size_t(k_count), 0.0f);
  std::vector<int> k_radius;
  for (int k = 0; k < k_count; ++k) {
    const float kc = options.candidates[std::size_t(k)].color_k;
    inv_k2[std::size_t(k)] = kc > 0.0f ? 1.0f / (kc * kc) : 0.0f;
    const int rk = options.candidates[std::size_t(k)].radius;
    k_radius.push_back(rk > 0 ? std::min(rk, r) : r);
  }

  // First-order candidates (first_order.cpp) share the distances of the offset loop.
  const int fo_count = int(options.first_order_k.size());
  const bool first_order = fo_count > 0 && input.normal >= 0 && input.depth >= 0;
  std::vector<float> fo_inv_k2;
  for (float kc : options.first_order_k) fo_inv_k2.push_back(kc > 0.0f ? 1.0f / (kc * kc) : 0.0f);
  const Feature* normal = first_order ? input.features[std::size_t(input.normal)] : nullptr;
  const Feature* depth = first_order ? input.features[std::size_t(input.depth)] : nullptr;

  Candidates out;
  for (int k = 0; k < k_count + (first_order ? fo_count : 0); ++k)
    for (int half = 0; half < 2; ++half) {
      out.color[half].emplace_back();
      for (int c = 0; c < 3; ++c) out.color[half].back().emplace_back(w, h, 0);
      out.error[half].emplace_back(w, h, 0);
    }
  const int strips = (h + kStrip - 1) / kStrip;
  if (strip_count) *strip_count = strips;
  std::atomic<bool> stopped{false};

  pbrkit::parallel_for(0, strips, [&](int s) {
    if (stopped.load(std::memory_order_relaxed)) return;
    const int y0 = s * kStrip, y1 = std::min(h, y0 + kStrip);
    const std::size_t n = std::size_t(y1 - y0) * w;
    // Sums per candidate and half: weight * colour (3), weight, weight^2 * variance.
    constexpr int kSums = 5;
    std::vector<float> sums(n * kSums * 2 * std::size_t(k_count), 0.0f);
    auto sum = [&](int k, int half, int which) {
      return sums.data() + n * (std::size_t((k * 2 + half) * kSums + which));
    };
    std::vector<float> dist[2] = {std::vector<float>(n), std::vector<float>(n)};
    std::vector<float> feature_dist(n), weight(n), scratch;
    // First order: per candidate and half, the normal equations' sums, one row of n per sum.
    using first_order::kDim;
    constexpr int kFoSums = first_order::kSums;
    std::vector<float> fo_sums(first_order ? n * kFoSums * 2 * std::size_t(fo_count) : 0, 0.0f);
    auto fo_sum = [&](int k, int half, int which) {
      return fo_sums.data() + n * (std::size_t((k * 2 + half) * kFoSums + which));
    };
    std::vector<float> other_dist(first_order ? n : 0),
        regressors(first_order ? std::size_t(w) * kDim : 0),
        weighted(first_order ? std::size_t(w) * kDim : 0);
    // Adds offset (dx, dy) of row y to the first-order sums: with v the regressors of q
    // relative to p (first_order::kDim) and w_pq the weight, A += w v v^T and
    // b_c += w v c_q. Rows of w floats per regressor, so the loops over x vectorise.
    auto accumulate_first_order = [&](int y, int dx, int dy, int x0, int x1, std::size_t o) {
      float* v[kDim];
      float* wv[kDim];
      for (int i = 0; i < kDim; ++i) {
        v[i] = regressors.data() + std::size_t(i) * w;
        wv[i] = weighted.data() + std::size_t(i) * w;
      }
      for (int c = 0; c < 3; ++c) {
        const float* np = normal->mean[std::size_t(c)].row(y);
        const float* nq = normal->mean[std::size_t(c)].row(y + dy) + dx;
        for (int x = x0; x < x1; ++x) v[1 + c][x] = nq[x] - np[x];
      }
      const float* dp = depth->mean[0].row(y);
      const float* dq = depth->mean[0].row(y + dy) + dx;
      for (int x = x0; x < x1; ++x) v[4][x] = (dq[x] - dp[x]) * first_order::kDepthScale;
      const float px = float(dx) / float(r), py = float(dy) / float(r);
      for (int x = x0; x < x1; ++x) {
        v[5][x] = px;
        v[6][x] = py;
      }
      const float* od = other_dist.data() + o;
      for (int k = 0; k < fo_count; ++k) {
        const float ik2 = fo_inv_k2[std::size_t(k)];
        for (int half = 0; half < 2; ++half) {
          const float* cd = dist[1 - half].data() + o;
          if (ik2 > 0.0f)
            for (int x = x0; x < x1; ++x) wv[0][x] = exp_neg(std::max(cd[x] * ik2, od[x]));
          else
            for (int x = x0; x < x1; ++x) wv[0][x] = exp_neg(od[x]);
          for (int i = 1; i < kDim; ++i)
            for (int x = x0; x < x1; ++x) wv[i][x] = wv[0][x] * v[i][x];
          int which = 0;
          for (int i = 0; i < kDim; ++i)
            for (int j = i; j < kDim; ++j) {
              float* s_ij = fo_sum(k, half, which++) + o;
              if (j == 0) {
                for (int x = x0; x < x1; ++x) s_ij[x] += wv[0][x];
              } else {
                add_products(s_ij, wv[i], v[j], x0, x1);
              }
            }
          const Channels& data = *input.color[half];
          for (int c = 0; c < 3; ++c) {
            const float* q = data[std::size_t(c)].row(y + dy) + dx;
            for (int i = 0; i < kDim; ++i) {
              add_products(fo_sum(k, half, which++) + o, wv[i], q, x0, x1);
            }
          }
        }
      }
    };
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        for (int g = 0; g < 2; ++g)
          patch_distance(guide[g], guide_variance[g], dx, dy, options.patch_radius, y0, y1,
                         dist[g].data(), scratch, options.symmetric_colour_distance);
        const int x0 = std::max(0, -dx), x1 = std::min(w, w - dx);
        for (int y = y0; y < y1; ++y) {
          if (y + dy < 0 || y + dy >= h) continue;
          const std::size_t o = std::size_t(y - y0) * w;
          // The feature distance: the largest over the features of
          // (mean_c (f_p - f_q)^2 - (Var_p + min(Var_p, Var_q))) / (k_f^2 max(tau, Var_p,
          // |grad_p|^2)).
          float* fd = feature_dist.data() + o;
          for (int x = x0; x < x1; ++x) fd[x] = 0.0f;
          // For the first-order candidates: the same distance without the normal's (it
          // enters the fit instead of the weight).
          float* od = first_order ? other_dist.data() + o : nullptr;
          if (od)
            for (int x = x0; x < x1; ++x) od[x] = 0.0f;
          for (std::size_t fi = 0; fi < input.features.size(); ++fi) {
            const Feature* f = input.features[fi];
            const float inv_channels = 1.0f / float(f->mean.size());
            const float* vp = f->variance.row(y);
            const float* vq = f->variance.row(y + dy) + dx;
            const float* norm = f->inv_norm.row(y);
            float* tmp = weight.data() + o;
            for (int x = x0; x < x1; ++x) tmp[x] = 0.0f;
            for (const Plane& p : f->mean) {
              const float* fp = p.row(y);
              const float* fq = p.row(y + dy) + dx;
              for (int x = x0; x < x1; ++x) {
                const float d = fp[x] - fq[x];
                tmp[x] += d * d;
              }
            }
            for (int x = x0; x < x1; ++x) {
              const float d = (tmp[x] * inv_channels - (vp[x] + std::min(vp[x], vq[x]))) * norm[x];
              tmp[x] = d;
              fd[x] = std::max(fd[x], d);
            }
            if (od && int(fi) != input.normal)
              for (int x = x0; x < x1; ++x) od[x] = std::max(od[x], tmp[x]);
          }
          if (first_order) accumulate_first_order(y, dx, dy, x0, x1, o);
          const float* q_var[2] = {mean_variance[0].row(y + dy) + dx,
                                   mean_variance[1].row(y + dy) + dx};
          for (int k = 0; k < k_count; ++k) {
            const int rk = k_radius[std::size_t(k)];
            if (dx < -rk || dx > rk || dy < -rk || dy > rk) continue;
            const float ik2 = inv_k2[std::size_t(k)];
            for (int half = 0; half < 2; ++half) {
              // Half `half` is filtered with the colour distance of the other half; one
              // fused pass per candidate and half computes the weight and all five sums.
              float* wt = weight.data() + o;
              const float* cd = dist[1 - half].data() + o;
              const Channels& data = *input.color[half];
              const float* q0 = data[0].row(y + dy) + dx;
              const float* q1 = data[1].row(y + dy) + dx;
              const float* q2 = data[2].row(y + dy) + dx;
              float* s0 = sum(k, half, 0) + o;
              float* s1 = sum(k, half, 1) + o;
              float* s2 = sum(k, half, 2) + o;
              float* s_w = sum(k, half, 3) + o;
              float* s_v = sum(k, half, 4) + o;
              const float* qv = q_var[half];
              auto accumulate = [&](int x, float wx) {
                s0[x] += wx * q0[x];
                s1[x] += wx * q1[x];
                s2[x] += wx * q2[x];
                s_w[x] += wx;
                s_v[x] += wx * wx * qv[x];
              };
              if (ik2 > 0.0f) {
                for (int x = x0; x < x1; ++x) accumulate(x, exp_neg(std::max(cd[x] * ik2, fd[x])));
              } else if (half == 0) {  // features alone: one weight for both halves
                for (int x = x0; x < x1; ++x) {
                  wt[x] = exp_neg(fd[x]);
                  accumulate(x, wt[x]);
                }
              } else {
                for (int x = x0; x < x1; ++x) accumulate(x, wt[x]);
              }
            }
          }
        }
      }
    // Every candidate's output and error estimate, from each pixel's two HalfEstimates.
    auto store_strip = [&](std::size_t k_out, const auto& estimate) {
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
          const std::size_t i = std::size_t(y - y0) * w + std::size_t(x);
          HalfEstimate halves[2];
          for (int half = 0; half < 2; ++half) estimate(half, x, y, i, halves[half]);
          store_candidate(input, mean_variance, x, y, halves, out, k_out);
        }
    };
    // A weighted mean F = sum_q w_q c_q / W: dF/dc_p = w_pp / W = 1 / W, and its variance
    // is sum w^2 s^2 / W^2.
    for (int k = 0; k < k_count; ++k)
      store_strip(std::size_t(k), [&](int half, int, int, std::size_t i, HalfEstimate& e) {
        const float inv_W = 1.0f / sum(k, half, 3)[i];  // W >= 1: the pixel itself weighs 1
        for (int c = 0; c < 3; ++c) e.rgb[c] = sum(k, half, c)[i] * inv_W;
        e.dfdc = inv_W;
        e.variance = sum(k, half, 4)[i] * inv_W * inv_W;
      });
    // The first-order fits: solve each pixel's normal equations; the intercept is the fit
    // at the pixel and [A^-1]_00 its derivative in c_p; the variance of the fit is
    // approximated by s_p^2 [A^-1]_00 (exact for 0/1 weights and equal variances, as
    // sum w^2 s^2 / W^2 is for the weighted mean).
    for (int k = 0; first_order && k < fo_count; ++k)
      store_strip(std::size_t(k_count + k),
                  [&](int half, int x, int y, std::size_t i, HalfEstimate& e) {
                    float a[kFoSums];
                    for (int j = 0; j < kFoSums; ++j) a[j] = fo_sum(k, half, j)[i];
                    first_order::solve(a, options.first_order_ridge, e.rgb, e.dfdc);
                    for (float& v : e.rgb) v = std::clamp(v, input.lowest, input.highest);
                    e.variance = mean_variance[half].at(x, y) * e.dfdc;
                  });
    if (tick && !tick()) stopped.store(true, std::memory_order_relaxed);
  });
  (void)pad;
  return out;
}

}  // namespace pbrkit::denoising
