#include "pbrkit/pt/environment_sampler.h"

#include <algorithm>
#include <cmath>

#include "pbrkit/core/color.h"
#include "pbrkit/core/equirect.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"

namespace pbrkit {

Distribution1D::Distribution1D(std::vector<float> weights) {
  // The running sum is kept in double; the normalised CDF is stored in float (half the
  // memory of double, which matters for the per-row tables of large maps).
  const std::size_t n = weights.size();
  std::vector<double> cdf(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    weights[i] = std::isfinite(weights[i]) ? std::max(weights[i], 0.0f) : 0.0f;
    cdf[i + 1] = cdf[i] + double(weights[i]);
  }
  total_ = cdf.back();
  if (total_ <= 0.0) {
    // Nothing to prefer: uniform.
    std::fill(weights.begin(), weights.end(), 1.0f);
    for (std::size_t i = 0; i < n; ++i) cdf[i + 1] = double(i + 1);
    total_ = double(n);
  }
  bins_.resize(n + 1);
  for (std::size_t i = 0; i <= n; ++i)
    bins_[i] = {float(cdf[i] / total_), i < n ? weights[i] : 0.0f};
  bins_.back().cdf = 1.0f;
  inv_total_ = float(1.0 / total_);
  guide_.resize(n);
  std::size_t i = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const float u = float(k) / float(n);
    while (i + 1 < n && bins_[i + 1].cdf <= u) ++i;
    guide_[k] = std::uint32_t(i);
  }
}

float Distribution1D::sample(float u, float& pdf, std::size_t& index) const {
  index = sample_discrete(u, pdf);
  const float lo = bins_[index].cdf, hi = bins_[index + 1].cdf;
  const float du = hi > lo ? std::clamp((u - lo) / (hi - lo), 0.0f, 1.0f) : 0.5f;
  pdf = this->pdf(index);
  return std::min((float(index) + du) / float(size()), kOneMinusEpsilon);
}

std::size_t Distribution1D::sample_discrete(float u, float& probability) const {
  // The bin i with cdf[i] <= u < cdf[i + 1] (bins of zero weight have an empty interval
  // and are never chosen), found from the guide table's starting point.
  const std::size_t n = size();
  std::size_t i = guide_[std::min(std::size_t(std::max(u, 0.0f) * float(n)), n - 1)];
  while (i > 0 && bins_[i].cdf > u) --i;  // float rounding of u * n
  while (i + 1 < n && bins_[i + 1].cdf <= u) ++i;
  while (i > 0 && bins_[i].weight == 0.0f) --i;
  while (i + 1 < n && bins_[i].weight == 0.0f) ++i;
  probability = bins_[i].weight * inv_total_;
  return i;
}

float Distribution1D::pdf(std::size_t index) const {
  return bins_[index].weight * inv_total_ * float(size());
}

EnvironmentSampler::EnvironmentSampler(const Environment& env)
    : width_(env.map.width),
      height_(env.map.height),
      fw_(float(width_)),
      fh_(float(height_)),
      stride_(std::size_t(width_) + 2),
      intensity_(env.intensity) {
  // The same rotation as world_to_env(d, env.rotation_deg), evaluated once.
  const float a = -env.rotation_deg * (kPi / 180.0f);
  cos_rot_ = std::cos(a);
  sin_rot_ = std::sin(a);
  const float a_inv = -(-env.rotation_deg) * (kPi / 180.0f);  // env_to_world's
  cos_inv_ = std::cos(a_inv);
  sin_inv_ = std::sin(a_inv);

  // Environment::eval interpolates bilinearly, so radiance inside texel (x, y) can come
  // from its 8 neighbours; the weight takes their maximum so that the pdf is positive
  // wherever eval is (the estimator stays unbiased).
  std::vector<float> lum(std::size_t(width_) * height_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      lum[std::size_t(y) * width_ + x] = luminance(env.map.rgb(x, y));
  std::vector<float> row_weights(height_);
  std::vector<Distribution1D> conditional;
  conditional.reserve(height_);
  double mean = 0.0, solid = 0.0;
  for (int y = 0; y < height_; ++y) {
    const float sin_theta = std::sin(kPi * (float(y) + 0.5f) / float(height_));
    std::vector<float> w(width_);
    double row_sum = 0.0;
    for (int x = 0; x < width_; ++x) {
      float m = 0.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int yy = std::clamp(y + dy, 0, height_ - 1);
          const int xx = ((x + dx) % width_ + width_) % width_;
          m = std::max(m, lum[std::size_t(yy) * width_ + xx]);
        }
      w[x] = m * sin_theta;
      row_sum += double(w[x]);
      mean += double(lum[std::size_t(y) * width_ + x]) * sin_theta;
      solid += sin_theta;
    }
    conditional.emplace_back(std::move(w));
    row_weights[y] = float(row_sum);
  }
  marginal_ = Distribution1D(std::move(row_weights));
  mean_luminance_ = solid > 0.0 ? float(mean / solid) * env.intensity : 0.0f;

  // The texel table (see texels_): radiance and p(u, v) side by side.
  const std::size_t pw = std::size_t(width_) + 2;
  texels_.resize(pw * std::size_t(height_ + 2));
  for (int y = -1; y <= height_; ++y)
    for (int x = -1; x <= width_; ++x) {
      const int xx = (x + width_) % width_, yy = std::clamp(y, 0, height_ - 1);
      const bool inside = x == xx && y == yy;
      const float pdf_uv =
          inside ? conditional[std::size_t(y)].pdf(std::size_t(x)) * marginal_.pdf(std::size_t(y))
                 : 0.0f;
      texels_[std::size_t(y + 1) * pw + std::size_t(x + 1)] = {env.map.rgb(xx, yy), pdf_uv};
    }
  const std::size_t n = std::size_t(width_);
  lines_per_row_ = (n + 15) / 16;
  fine_cdf_.resize(lines_per_row_ * std::size_t(height_));
  coarse_cdf_.resize((lines_per_row_ + 1) * std::size_t(height_));
  for (std::size_t y = 0; y < std::size_t(height_); ++y) {
    auto cdf = [&](std::size_t i) { return i <= n ? conditional[y].cdf(i) : 2.0f; };
    for (std::size_t j = 0; j < lines_per_row_; ++j)
      for (std::size_t k = 0; k < 16; ++k)
        fine_cdf_[y * lines_per_row_ + j].cdf[k] = cdf(16 * j + k);
    for (std::size_t j = 0; j <= lines_per_row_; ++j)
      coarse_cdf_[y * (lines_per_row_ + 1) + j] = cdf(16 * j);
  }
}

float EnvironmentSampler::sample_column(std::size_t row, int footprint_row, float u,
                                        float& pdf_uv) const {
  // The bin i < width with cdf[i] <= u < cdf[i + 1]: the largest i with cdf[i] <= u, as
  // the CDF is non-decreasing, cdf[0] = 0 <= u and cdf[width] = 1 > u. Its interval is
  // not empty, so its weight is positive (a zero weight repeats the CDF value exactly).
  // Line: the largest j with coarse[j] <= u (branch-free binary search).
  const float* coarse = coarse_cdf_.data() + row * (lines_per_row_ + 1);
  std::size_t j = 0;
  for (std::size_t len = lines_per_row_; len > 1;) {
    const std::size_t half = len / 2;
    j = coarse[j + half] <= u ? j + half : j;
    len -= half;
  }
  // The bin is one of the line's 16: start loading their texels now, so that their
  // misses overlap the line's (p(u, v) is read below and the radiance after the bilinear
  // footprint, rows footprint_row and footprint_row + 1, columns 16 j - 1 to 16 j + 16).
  const std::size_t pw = std::size_t(width_) + 2;
  for (std::size_t r = 0; r < 2; ++r) {
    const char* first = reinterpret_cast<const char*>(
        texels_.data() + std::size_t(footprint_row + 1 + int(r)) * pw + 16 * j);
    for (std::size_t b = 0; b < 18 * sizeof(glm::vec4); b += 64) __builtin_prefetch(first + b);
    __builtin_prefetch(first + 18 * sizeof(glm::vec4) - 1);
  }
  // Bin within the line: how many of its values after the first are <= u.
  const float* line = fine_cdf_[row * lines_per_row_ + j].cdf;
  std::size_t k = 0;
  for (std::size_t m = 1; m < 16; ++m) k += line[m] <= u ? 1u : 0u;
  const std::size_t i = 16 * j + k;
  const float lo = line[k], hi = k < 15 ? line[k + 1] : coarse[j + 1];
  pdf_uv = texels_[(row + 1) * pw + i + 1].w;
  const float du = hi > lo ? std::clamp((u - lo) / (hi - lo), 0.0f, 1.0f) : 0.5f;
  return std::min((float(i) + du) / float(width_), kOneMinusEpsilon);
}

EnvironmentSampler::Sample EnvironmentSampler::sample(glm::vec2 u) const {
  Sample s;
  float pdf_v = 0.0f, pdf_uv = 0.0f;
  std::size_t row = 0;
  const float v = marginal_.sample(u.y, pdf_v, row);
  // The first row of the bilinear footprint of v (at()'s, less its border row).
  const int y0 = int(v * fh_ + 0.5f) - 1;
  const float uu = sample_column(row, y0, u.x, pdf_uv);
  // equirect_direction({uu, v}), sharing sin(theta) with the Jacobian.
  const float phi = (uu - 0.5f) * 2.0f * kPi, theta = v * kPi;
  const float sin_theta = std::sin(theta);
  if (!(sin_theta > 0.0f)) return s;
  // p(omega) = p(u, v) / (2 pi^2 sin(theta)): the Jacobian of the lat-long map.
  s.pdf = pdf_uv / (2.0f * kPi * kPi * sin_theta);
  s.direction = to_world({sin_theta * std::sin(phi), std::cos(theta), -sin_theta * std::cos(phi)});
  // The radiance at the sampled (u, v) itself: the same as eval(direction) up to the
  // rounding of the round trip through the direction, without its atan2 and acos.
  s.radiance = eval(at({uu, v}, sin_theta));
  return s;
}

float EnvironmentSampler::pdf(glm::vec3 d) const {
  float p = 0.0f;
  eval(d, &p);
  return p;
}

}  // namespace pbrkit
