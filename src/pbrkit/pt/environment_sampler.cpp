#include "pbrkit/pt/environment_sampler.h"

#include <algorithm>
#include <cmath>

#include "pbrkit/core/color.h"
#include "pbrkit/core/equirect.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"

namespace pbrkit {

Distribution1D::Distribution1D(std::vector<float> weights) : weights_(std::move(weights)) {
  // The running sum is kept in double; the normalised CDF is stored in float (half the
  // memory of double, which matters for the per-row tables of large maps).
  std::vector<double> cdf(weights_.size() + 1, 0.0);
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    weights_[i] = std::isfinite(weights_[i]) ? std::max(weights_[i], 0.0f) : 0.0f;
    cdf[i + 1] = cdf[i] + double(weights_[i]);
  }
  total_ = cdf.back();
  if (total_ <= 0.0) {
    // Nothing to prefer: uniform.
    std::fill(weights_.begin(), weights_.end(), 1.0f);
    for (std::size_t i = 0; i < weights_.size(); ++i) cdf[i + 1] = double(i + 1);
    total_ = double(weights_.size());
  }
  cdf_.resize(cdf.size());
  for (std::size_t i = 0; i < cdf.size(); ++i) cdf_[i] = float(cdf[i] / total_);
  cdf_.back() = 1.0f;
  inv_total_ = float(1.0 / total_);
  const std::size_t n = weights_.size();
  guide_.resize(n);
  std::size_t i = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const float u = float(k) / float(n);
    while (i + 1 < n && cdf_[i + 1] <= u) ++i;
    guide_[k] = std::uint32_t(i);
  }
}

float Distribution1D::sample(float u, float& pdf, std::size_t& index) const {
  index = sample_discrete(u, pdf);
  const float lo = cdf_[index], hi = cdf_[index + 1];
  const float du = hi > lo ? std::clamp((u - lo) / (hi - lo), 0.0f, 1.0f) : 0.5f;
  pdf = this->pdf(index);
  return std::min((float(index) + du) / float(size()), kOneMinusEpsilon);
}

std::size_t Distribution1D::sample_discrete(float u, float& probability) const {
  // The bin i with cdf_[i] <= u < cdf_[i + 1] (bins of zero weight have an empty interval
  // and are never chosen), found from the guide table's starting point.
  const std::size_t n = size();
  std::size_t i = guide_[std::min(std::size_t(std::max(u, 0.0f) * float(n)), n - 1)];
  while (i > 0 && cdf_[i] > u) --i;  // float rounding of u * n
  while (i + 1 < n && cdf_[i + 1] <= u) ++i;
  while (i > 0 && weights_[i] == 0.0f) --i;
  while (i + 1 < n && weights_[i] == 0.0f) ++i;
  probability = weights_[i] * inv_total_;
  return i;
}

float Distribution1D::pdf(std::size_t index) const {
  return weights_[index] * inv_total_ * float(size());
}

EnvironmentSampler::EnvironmentSampler(const Environment& env)
    : env_(env), width_(env.map.width), height_(env.map.height) {
  // Environment::eval interpolates bilinearly, so radiance inside texel (x, y) can come
  // from its 8 neighbours; the weight takes their maximum so that the pdf is positive
  // wherever eval is (the estimator stays unbiased).
  std::vector<float> lum(std::size_t(width_) * height_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      lum[std::size_t(y) * width_ + x] = luminance(env.map.rgb(x, y));
  std::vector<float> row_weights(height_);
  conditional_.reserve(height_);
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
    conditional_.emplace_back(std::move(w));
    row_weights[y] = float(row_sum);
  }
  marginal_ = Distribution1D(std::move(row_weights));
  mean_luminance_ = solid > 0.0 ? float(mean / solid) * env.intensity : 0.0f;
}

EnvironmentSampler::Sample EnvironmentSampler::sample(glm::vec2 u) const {
  Sample s;
  float pdf_v = 0.0f, pdf_u = 0.0f;
  std::size_t row = 0, col = 0;
  const float v = marginal_.sample(u.y, pdf_v, row);
  const float uu = conditional_[row].sample(u.x, pdf_u, col);
  const float sin_theta = std::sin(kPi * v);
  if (!(sin_theta > 0.0f)) return s;
  // p(omega) = p(u, v) / (2 pi^2 sin(theta)): the Jacobian of the lat-long map.
  s.pdf = pdf_u * pdf_v / (2.0f * kPi * kPi * sin_theta);
  s.direction = env_to_world(equirect_direction({uu, v}), env_.rotation_deg);
  s.radiance = env_.eval(s.direction);
  return s;
}

float EnvironmentSampler::pdf(glm::vec3 d) const {
  const glm::vec3 local = world_to_env(d, env_.rotation_deg);
  const glm::vec2 uv = equirect_uv(local);
  // sqrt(x^2 + z^2) rather than sqrt(1 - y^2): no cancellation near the poles.
  const float sin_theta = std::sqrt(local.x * local.x + local.z * local.z);
  if (!(sin_theta > 0.0f)) return 0.0f;
  const int x = std::clamp(int(uv.x * float(width_)), 0, width_ - 1);
  const int y = std::clamp(int(uv.y * float(height_)), 0, height_ - 1);
  const float pdf_v = marginal_.pdf(std::size_t(y));
  const float pdf_u = conditional_[std::size_t(y)].pdf(std::size_t(x));
  return pdf_u * pdf_v / (2.0f * kPi * kPi * sin_theta);
}

}  // namespace pbrkit
