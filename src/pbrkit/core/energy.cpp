#include "pbrkit/core/energy.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

glm::vec2 EnergyTable::integrate_AB(GeometryModel model, float mu, float roughness, int samples) {
  // With visible-normal sampling the estimator of int f cos dwi is G(wo, wi) F / G1(wo)
  // (the D and cosine terms cancel against the pdf G1 D / (4 n.wo)), which is bounded
  // and so converges much faster than the seeds' NDF sampling. Splitting Schlick's
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

glm::vec3 multiscatter_fresnel(glm::vec3 F0, float E_avg) {
  const glm::vec3 F_avg = fresnelSchlickAverage(F0);
  return F_avg * F_avg * E_avg / (1.0f - F_avg * (1.0f - E_avg));
}

}  // namespace pbrkit
