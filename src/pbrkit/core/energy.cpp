#include "pbrkit/core/energy.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/core/transmission.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

glm::vec2 EnergyTable::integrate_AB(GeometryModel model, float mu, float roughness, int samples) {
  // With visible-normal sampling the estimator of int f cos dwi is G(wo, wi) F / G1(wo)
  // (the D and cosine terms cancel against the pdf G1 D / (4 n.wo)), which is bounded
  // and so converges much faster than NDF sampling (Karis 2013's). Splitting Schlick's
  // F = F0 (1 - Fc) + Fc gives A (the F0 scale) and B (the bias) of Karis 2013.
  roughness = std::clamp(roughness, kMinRoughness, 1.0f);
  mu = std::clamp(mu, 1e-4f, 1.0f);
  const float alpha = roughness * roughness;
  const glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
  const float g1 = SmithG1GGX(wo, alpha);
  double A = 0.0, B = 0.0;
  for (int i = 0; i < samples; ++i) {
    const glm::vec2 u = hammersley(std::uint32_t(i), std::uint32_t(samples));
    const glm::vec3 h = sample_ggx_vndf(wo, u, alpha).h;
    const glm::vec3 wi = reflect_about(wo, h);
    if (wi.z <= 0.0f) continue;
    const float WOdotH = std::max(glm::dot(wo, h), 0.0f);
    const float Fc = std::pow(1.0f - WOdotH, 5.0f);
    const double weight = double(GeometryG(model, wo, wi, roughness)) / double(g1);
    A += (1.0 - Fc) * weight;
    B += Fc * weight;
  }
  return {float(A / samples), float(B / samples)};
}

EnergyTable::EnergyTable(GeometryModel model)
    : model_(model), ab_(std::size_t(kMuSize) * kRoughnessSize), ab_avg_(kRoughnessSize) {
  // Each entry is independent and deterministic (Hammersley points), so the table is
  // the same whatever the thread count.
  pbrkit::parallel_for(0, kRoughnessSize * kMuSize, [&](int k) {
    const int i = k % kMuSize, j = k / kMuSize;
    const float r = float(j) / float(kRoughnessSize - 1);
    const float mu = float(i) / float(kMuSize - 1);
    ab_[std::size_t(k)] = integrate_AB(model, mu, r, kSamples);
  });
  // Cosine-weighted averages 2 int X(mu) mu dmu of the piecewise-linear interpolant, so
  // that E_avg is consistent with what E(mu) returns (the compensated albedo is then 1 up
  // to the interpolation error of E itself). Exact for a linear segment:
  // int_a^b (x0 + (x1 - x0)(mu - a)/(b - a)) mu dmu.
  for (int j = 0; j < kRoughnessSize; ++j) {
    glm::dvec2 sum(0.0);
    for (int i = 0; i + 1 < kMuSize; ++i) {
      const double a = double(i) / (kMuSize - 1), b = double(i + 1) / (kMuSize - 1);
      const glm::dvec2 x0 = glm::dvec2(ab_[std::size_t(j) * kMuSize + i]);
      const glm::dvec2 x1 = glm::dvec2(ab_[std::size_t(j) * kMuSize + i + 1]);
      const double h = b - a;
      // int_a^b ((b - mu) x0 + (mu - a) x1) / h * mu dmu = x0 i0 + x1 i1 with:
      const double i0 = (b * (b * b - a * a) / 2.0 - (b * b * b - a * a * a) / 3.0) / h;
      const double i1 = ((b * b * b - a * a * a) / 3.0 - a * (b * b - a * a) / 2.0) / h;
      sum += x0 * i0 + x1 * i1;
    }
    ab_avg_[j] = glm::vec2(2.0 * sum);
  }
}

const EnergyTable& EnergyTable::build(GeometryModel model) {
  static std::array<std::once_flag, 3> once;
  const auto index = std::size_t(model);
  std::call_once(once[index],
                 [&] { built_[index].store(new EnergyTable(model), std::memory_order_release); });
  return *built_[index].load(std::memory_order_acquire);
}

glm::vec2 EnergyTable::AB(float mu, float roughness) const {
  const float x = std::clamp(mu, 0.0f, 1.0f) * float(kMuSize - 1);
  const float y = std::clamp(roughness, 0.0f, 1.0f) * float(kRoughnessSize - 1);
  const int i0 = std::min(int(x), kMuSize - 2), j0 = std::min(int(y), kRoughnessSize - 2);
  const float fx = x - float(i0), fy = y - float(j0);
  auto at = [&](int i, int j) { return ab_[std::size_t(j) * kMuSize + i]; };
  return glm::mix(glm::mix(at(i0, j0), at(i0 + 1, j0), fx),
                  glm::mix(at(i0, j0 + 1), at(i0 + 1, j0 + 1), fx), fy);
}

float EnergyTable::E(float mu, float roughness) const {
  const glm::vec2 ab = AB(mu, roughness);
  return ab.x + ab.y;
}

glm::vec2 EnergyTable::AB_avg(float roughness) const {
  const float y = std::clamp(roughness, 0.0f, 1.0f) * float(kRoughnessSize - 1);
  const int j0 = std::min(int(y), kRoughnessSize - 2);
  return glm::mix(ab_avg_[j0], ab_avg_[j0 + 1], y - float(j0));
}

namespace {

// 2 int X(mu) mu dmu of the piecewise-linear interpolant of X over n equally spaced mu
// nodes in [0, 1] (exact for each linear segment, as EnergyTable's averages).
double cosine_average(const float* x, int n) {
  double sum = 0.0;
  for (int i = 0; i + 1 < n; ++i) {
    const double a = double(i) / (n - 1), b = double(i + 1) / (n - 1), h = b - a;
    const double i0 = (b * (b * b - a * a) / 2.0 - (b * b * b - a * a * a) / 3.0) / h;
    const double i1 = ((b * b * b - a * a * a) / 3.0 - a * (b * b - a * a) / 2.0) / h;
    sum += double(x[i]) * i0 + double(x[i + 1]) * i1;
  }
  return 2.0 * sum;
}

}  // namespace

glm::vec2 DielectricEnergyTable::integrate(float mu, float roughness, float eta, int samples) {
  // For a visible normal h from wo, the reflection carries F G2(wo, wr) / G1(wo) and the
  // refraction (1 - F) G2(wo, wt) / G1(wo) (the sampler weights of core/transmission.h in
  // importance transport); both branches are summed for each h, which halves the noise of
  // choosing one.
  roughness = std::clamp(roughness, kMinRoughness, 1.0f);
  mu = std::clamp(mu, 1e-4f, 1.0f);
  const float alpha = roughness * roughness;
  const glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
  const float lambda_o = SmithLambdaGGX(wo, alpha);
  const float g1 = 1.0f / (1.0f + lambda_o);
  double E = 0.0, R = 0.0;
  for (int i = 0; i < samples; ++i) {
    const glm::vec2 u = hammersley(std::uint32_t(i), std::uint32_t(samples));
    const glm::vec3 h = sample_ggx_visible_normal(wo, u, alpha);
    const float oh = glm::dot(wo, h);
    if (!(oh > 0.0f)) continue;
    const float F = fresnel_dielectric(oh, eta);
    const glm::vec3 wr = reflect_about(wo, h);
    if (wr.z > 0.0f && F > 0.0f) {
      const double r = double(F) / (1.0 + lambda_o + SmithLambdaGGX(wr, alpha)) / g1;
      R += r;
      E += r;
    }
    glm::vec3 wt;
    if (F < 1.0f && refract(wo, h, eta, wt) && wt.z < 0.0f) {
      const glm::vec3 wt_up(wt.x, wt.y, -wt.z);  // Lambda depends on tan^2 only
      E += double(1.0f - F) / (1.0 + lambda_o + SmithLambdaGGX(wt_up, alpha)) / g1;
    }
  }
  return {float(E / samples), float(R / samples)};
}

float DielectricEnergyTable::eta_of_node(int k) {
  const float x = 0.5f * float(k) / float(kEtaSize - 1);
  return (1.0f + x) / (1.0f - x);
}

void DielectricEnergyTable::compute(int samples, std::vector<float>& E, std::vector<float>& R_avg) {
  constexpr int kRows = kEtaSize * kRoughnessSize;
  E.assign(kEntries, 0.0f);
  R_avg.assign(std::size_t(2) * kRows, 0.0f);
  // Deterministic (Hammersley points) and independent entries: the same for any thread count.
  pbrkit::parallel_for(0, 2 * kRows, [&](int row) {
    const int side = row / kRows, k = (row % kRows) / kRoughnessSize, j = row % kRoughnessSize;
    const float eta = side == 0 ? eta_of_node(k) : 1.0f / eta_of_node(k);
    const float r = float(j) / float(kRoughnessSize - 1);
    float R[kMuSize];
    for (int i = 0; i < kMuSize; ++i) {
      const glm::vec2 er = integrate(float(i) / float(kMuSize - 1), r, eta, samples);
      E[std::size_t(row) * kMuSize + std::size_t(i)] = er.x;
      R[i] = er.y;
    }
    R_avg[std::size_t(row)] = float(cosine_average(R, kMuSize));
  });
}

namespace {
#include "dielectric_energy_data.inc"  // kBakedE, kBakedRavg: compute(kSamples, ...)
}  // namespace

DielectricEnergyTable::DielectricEnergyTable() {
  constexpr std::size_t kPerSide = std::size_t(kEtaSize) * kRoughnessSize;
  static_assert(std::size(kBakedE) == kEntries && std::size(kBakedRavg) == 2 * kPerSide);
  for (int side = 0; side < 2; ++side) {
    E_[side].assign(kBakedE + side * kPerSide * kMuSize, kBakedE + (side + 1) * kPerSide * kMuSize);
    avg_[side].resize(kPerSide);
    // E_avg of the interpolant, so that the compensated albedo is 1 up to the interpolation
    // error of E itself.
    for (std::size_t row = 0; row < kPerSide; ++row)
      avg_[side][row] = glm::vec2(float(cosine_average(&E_[side][row * kMuSize], kMuSize)),
                                  kBakedRavg[side * kPerSide + row]);
  }
}

const DielectricEnergyTable& DielectricEnergyTable::build() {
  static std::once_flag once;
  std::call_once(once,
                 [] { built_.store(new DielectricEnergyTable(), std::memory_order_release); });
  return *built_.load(std::memory_order_acquire);
}

namespace {

// The table side and the fractional eta node for a ratio.
struct EtaNode {
  int side, k0;
  float fk;
};
EtaNode eta_node(float eta) {
  EtaNode n{};
  n.side = eta >= 1.0f ? 0 : 1;
  const float e = eta >= 1.0f ? eta : 1.0f / std::max(eta, 1e-6f);
  const float x = std::clamp((e - 1.0f) / (e + 1.0f), 0.0f, 0.5f);
  const float y = x / 0.5f * float(DielectricEnergyTable::kEtaSize - 1);
  n.k0 = std::min(int(y), DielectricEnergyTable::kEtaSize - 2);
  n.fk = y - float(n.k0);
  return n;
}

}  // namespace

float DielectricEnergyTable::E(float mu, float roughness, float eta) const {
  const EtaNode n = eta_node(eta);
  const float x = std::clamp(mu, 0.0f, 1.0f) * float(kMuSize - 1);
  const float y = std::clamp(roughness, 0.0f, 1.0f) * float(kRoughnessSize - 1);
  const int i0 = std::min(int(x), kMuSize - 2), j0 = std::min(int(y), kRoughnessSize - 2);
  const float fx = x - float(i0), fy = y - float(j0);
  const std::vector<float>& t = E_[n.side];
  auto at = [&](int i, int j, int k) {
    return t[(std::size_t(k) * kRoughnessSize + std::size_t(j)) * kMuSize + std::size_t(i)];
  };
  auto plane = [&](int k) {
    return glm::mix(glm::mix(at(i0, j0, k), at(i0 + 1, j0, k), fx),
                    glm::mix(at(i0, j0 + 1, k), at(i0 + 1, j0 + 1, k), fx), fy);
  };
  return glm::mix(plane(n.k0), plane(n.k0 + 1), n.fk);
}

glm::vec2 DielectricEnergyTable::averages(float roughness, float eta) const {
  const EtaNode n = eta_node(eta);
  const float y = std::clamp(roughness, 0.0f, 1.0f) * float(kRoughnessSize - 1);
  const int j0 = std::min(int(y), kRoughnessSize - 2);
  const float fy = y - float(j0);
  const std::vector<glm::vec2>& a = avg_[n.side];
  auto at = [&](int j, int k) { return a[std::size_t(k) * kRoughnessSize + std::size_t(j)]; };
  return glm::mix(glm::mix(at(j0, n.k0), at(j0 + 1, n.k0), fy),
                  glm::mix(at(j0, n.k0 + 1), at(j0 + 1, n.k0 + 1), fy), n.fk);
}

glm::vec3 multiscatter_fresnel(glm::vec3 F0, float E_avg) {
  const glm::vec3 F_avg = fresnelSchlickAverage(F0);
  return F_avg * F_avg * E_avg / (1.0f - F_avg * (1.0f - E_avg));
}

}  // namespace pbrkit
