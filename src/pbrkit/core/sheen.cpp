#include "pbrkit/core/sheen.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "pbrkit/core/math.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

namespace {

float clamp_sheen_roughness(float roughness) {
  return std::clamp(roughness, kMinSheenRoughness, 1.0f);
}

// The README's l(x, alphaG): the fit of Estevez & Kulla 2017 (table 1), its coefficients
// interpolated between the alphaG = 0 and 1 fits by (1 - alphaG)^2.
float sheen_l(float x, float r) {
  const float t = sqr(1.0f - r);
  const float a = glm::mix(21.5473f, 25.3245f, t);
  const float b = glm::mix(3.82987f, 3.32435f, t);
  const float c = glm::mix(0.19823f, 0.16801f, t);
  const float d = glm::mix(-1.97760f, -1.27393f, t);
  const float e = glm::mix(-4.32054f, -4.85967f, t);
  return a / (1.0f + b * std::pow(x, c)) + d * x + e;
}

}  // namespace

float DistributionCharlie(float NdotH, float roughness) {
  const float r = clamp_sheen_roughness(roughness);
  const float inv_r = 1.0f / r;
  const float sin2h = std::max(1.0f - NdotH * NdotH, 0.0f);
  // sin^(1/r) = (sin^2)^(1/(2r)).
  return (2.0f + inv_r) * std::pow(sin2h, 0.5f * inv_r) * kInv2Pi;
}

float SheenLambda(float cos_theta, float roughness) {
  const float r = clamp_sheen_roughness(roughness);
  const float c = std::min(std::abs(cos_theta), 1.0f);
  return c < 0.5f ? std::exp(sheen_l(c, r))
                  : std::exp(2.0f * sheen_l(0.5f, r) - sheen_l(1.0f - c, r));
}

float VisibilityCharlie(float NdotV, float NdotL, float roughness) {
  if (NdotV <= 0.0f || NdotL <= 0.0f) return 0.0f;
  return 1.0f / ((1.0f + SheenLambda(NdotV, roughness) + SheenLambda(NdotL, roughness)) *
                 (4.0f * NdotV * NdotL));
}

HalfVectorSample sample_charlie(glm::vec2 u, float roughness) {
  const float r = clamp_sheen_roughness(roughness);
  // P(theta_h < t) = int_0^t (2 + 1/r) sin^(1/r) cos sin dtheta = sin(t)^(2 + 1/r).
  const float sin_theta = std::min(std::pow(u.x, r / (2.0f * r + 1.0f)), 1.0f);
  const float cos_theta = safe_sqrt(1.0f - sin_theta * sin_theta);
  const float phi = 2.0f * kPi * u.y;
  const glm::vec3 h(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
  return {h, charlie_pdf(h, roughness)};
}

float charlie_pdf(glm::vec3 h, float roughness) {
  return h.z > 0.0f ? DistributionCharlie(h.z, roughness) * h.z : 0.0f;
}

SheenTable::Moments SheenTable::integrate_moments(float mu, float roughness, int samples) {
  // E = int_0^1 d(n.l) int_0^2pi dphi D(h) V (n.l), with v in the xz plane (t = +x). The
  // integrand is even in phi, so phi runs over [0, pi] and the sum is doubled (the mean's y
  // component cancels); n.l = s^2 (d(n.l) = 2 s ds) puts more nodes near the grazing l where
  // Lambda(l) changes fastest. Midpoint rule in (s, phi): 32 x 32 nodes are within 5e-4 of a
  // 2000 x 2000 (theta, phi) grid for E, and within 0.3 degrees for the mean's angle
  // (tests/core/sheen_test.cpp).
  const float r = clamp_sheen_roughness(roughness);
  mu = std::clamp(mu, 1e-4f, 1.0f);
  const float sin_v = std::sqrt(1.0f - mu * mu);
  const float lambda_v = SheenLambda(mu, r);
  const int n = std::max(samples, 1);
  std::vector<float> cos_phi(std::size_t(n), 0.0f);
  for (int k = 0; k < n; ++k)
    cos_phi[std::size_t(k)] = std::cos((float(k) + 0.5f) * kPi / float(n));
  const float exponent = 0.5f / r;  // sin^(1/r) = (sin^2)^(1/(2r))
  double sum = 0.0, sum_t = 0.0, sum_n = 0.0, sum_tt = 0.0, sum_nn = 0.0, sum_tn = 0.0;
  for (int i = 0; i < n; ++i) {
    const float s = (float(i) + 0.5f) / float(n);
    const float NdotL = s * s;
    const float sin_l = std::sqrt(1.0f - NdotL * NdotL);
    // V (n.l) = 1 / ((1 + Lambda(v) + Lambda(l)) 4 n.v), times the Jacobian 2 s.
    const float weight = 2.0f * s / ((1.0f + lambda_v + SheenLambda(NdotL, r)) * 4.0f * mu);
    // h = (v + l) / |v + l|: cos^2(theta_h) = (n.v + n.l)^2 / (2 + 2 v.l).
    const float hz_num = sqr(mu + NdotL);
    double row = 0.0, row_t = 0.0, row_tt = 0.0;
    for (int k = 0; k < n; ++k) {
      const float len2 = 2.0f + 2.0f * (mu * NdotL + sin_v * sin_l * cos_phi[std::size_t(k)]);
      const float sin2h = std::max(1.0f - hz_num / len2, 0.0f);
      const double d = double(std::pow(sin2h, exponent));
      const double lt = double(sin_l * cos_phi[std::size_t(k)]);  // l.t
      row += d;
      row_t += d * lt;
      row_tt += d * lt * lt;
    }
    const double w = double(weight), nl = double(NdotL);
    sum += row * w;
    sum_t += row_t * w;
    sum_n += row * w * nl;
    sum_tt += row_tt * w;
    sum_nn += row * w * nl * nl;
    sum_tn += row_t * w * nl;
  }
  const double norm = double(2.0f + 1.0f / r) * kInv2Pi;  // D = norm sin^(1/r)
  const double scale = 2.0 * norm / double(n) * (double(kPi) / double(n));
  return {sum * scale,    sum_t * scale,  sum_n * scale,
          sum_tt * scale, sum_nn * scale, sum_tn * scale};
}

float SheenTable::integrate_E(float mu, float roughness, int samples) {
  return float(integrate_moments(mu, roughness, samples).e);
}

SheenTable::SheenTable()
    : e_(std::size_t(kMuSize) * kRoughnessSize),
      mean_t_(e_.size()),
      mean_n_(e_.size()),
      e_max_avg_(e_.size()),
      tt_(e_.size()),
      nn_(e_.size()),
      tn_(e_.size()) {
  pbrkit::parallel_for(0, kMuSize * kRoughnessSize, [&](int k) {
    const int i = k % kMuSize, j = k / kMuSize;
    const float s = float(i) / float(kMuSize - 1);
    const float t = float(j) / float(kRoughnessSize - 1);
    const float r = glm::mix(kMinSheenRoughness, 1.0f, t * t);
    const Moments m = integrate_moments(s * s, r, kSamples);
    e_[std::size_t(k)] = float(m.e);
    mean_t_[std::size_t(k)] = m.e > 0.0 ? float(m.mean_t / m.e) : 0.0f;
    mean_n_[std::size_t(k)] = m.e > 0.0 ? float(m.mean_n / m.e) : 1.0f;
    // (At n.v = 1 and the smallest roughness E is ~3e-4, still far from 0.)
    const double inv_e = m.e > 0.0 ? 1.0 / m.e : 0.0;
    tt_[std::size_t(k)] = float(m.tt * inv_e);
    nn_[std::size_t(k)] = m.e > 0.0 ? float(m.nn * inv_e) : 1.0f;
    tn_[std::size_t(k)] = float(m.tn * inv_e);
  });
  // E_max_avg = 2 int_0^1 max(E(mu), E(mu_l)) mu_l dmu_l; with mu_l = s^2 (E's nodes are
  // uniform in s): 4 int_0^1 max(E(mu), E(s^2)) s^3 ds, midpoint rule over 256 intervals on
  // the roughness node's row of E (linear in s between nodes).
  pbrkit::parallel_for(0, kMuSize * kRoughnessSize, [&](int k) {
    const int i = k % kMuSize, j = k / kMuSize;
    const float* row = &e_[std::size_t(j) * kMuSize];
    constexpr int kNodes = 256;
    double sum = 0.0;
    for (int q = 0; q < kNodes; ++q) {
      const double s = (q + 0.5) / kNodes;
      const double x = s * (kMuSize - 1);
      const int x0 = std::min(int(x), kMuSize - 2);
      const double e = row[x0] + (x - x0) * (row[x0 + 1] - row[x0]);
      sum += std::max(double(row[i]), e) * s * s * s;
    }
    e_max_avg_[std::size_t(k)] = float(4.0 * sum / kNodes);
  });
}

const SheenTable& SheenTable::build() {
  static std::once_flag once;
  std::call_once(once, [] { built_.store(new SheenTable(), std::memory_order_release); });
  return *built_.load(std::memory_order_acquire);
}

float SheenTable::lerp_nodes(const std::vector<float>& nodes, float mu, float roughness) const {
  const float x = std::sqrt(std::clamp(mu, 0.0f, 1.0f)) * float(kMuSize - 1);
  // Roughness nodes r_j = 0.07 + 0.93 t_j^2, t_j uniform: E bends most at small roughness.
  const float y = std::sqrt((clamp_sheen_roughness(roughness) - kMinSheenRoughness) /
                            (1.0f - kMinSheenRoughness)) *
                  float(kRoughnessSize - 1);
  const int i0 = std::min(int(x), kMuSize - 2), j0 = std::min(int(y), kRoughnessSize - 2);
  const float fx = x - float(i0), fy = y - float(j0);
  auto at = [&](int i, int j) { return nodes[std::size_t(j) * kMuSize + i]; };
  return glm::mix(glm::mix(at(i0, j0), at(i0 + 1, j0), fx),
                  glm::mix(at(i0, j0 + 1), at(i0 + 1, j0 + 1), fx), fy);
}

float SheenTable::E(float mu, float roughness) const {
  return lerp_nodes(e_, mu, roughness);
}

float SheenTable::E_max_avg(float mu, float roughness) const {
  return lerp_nodes(e_max_avg_, mu, roughness);
}

glm::vec2 SheenTable::lobe_mean(float mu, float roughness) const {
  return {lerp_nodes(mean_t_, mu, roughness), lerp_nodes(mean_n_, mu, roughness)};
}

glm::vec3 SheenTable::lobe_second_moments(float mu, float roughness) const {
  return {lerp_nodes(tt_, mu, roughness), lerp_nodes(nn_, mu, roughness),
          lerp_nodes(tn_, mu, roughness)};
}

float SheenTable::lobe_angle(float mu, float roughness) const {
  const glm::vec2 m = lobe_mean(mu, roughness);
  return std::atan2(m.x, m.y);
}

}  // namespace pbrkit
