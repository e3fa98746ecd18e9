// The Charlie lobe's moments that the real-time sheen IBL uses (core/sheen.h: SheenTable's
// lobe_mean, lobe_angle, lobe_second_moments and E_max_avg) against independent brute-force
// quadratures of the cosine-weighted lobe.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include "pbrkit/core/sheen.h"

namespace pbrkit {
namespace {

constexpr double kPiD = std::numbers::pi;

// The lobe's normalised moments by a (theta, phi) midpoint grid over the whole upper
// hemisphere, in double, n = +z, v in the xz plane (t = +x).
struct BruteMoments {
  double e = 0.0, mx = 0.0, mz = 0.0, xx = 0.0, zz = 0.0, xz = 0.0;
};
BruteMoments brute_force_moments(double mu, float r) {
  const glm::dvec3 v(std::sqrt(1.0 - mu * mu), 0.0, mu);
  constexpr int kTheta = 240, kPhi = 480;
  BruteMoments m;
  for (int i = 0; i < kTheta; ++i) {
    const double theta = (i + 0.5) * (kPiD / 2.0) / kTheta;
    const double ct = std::cos(theta), st = std::sin(theta);
    for (int k = 0; k < kPhi; ++k) {
      const double phi = (k + 0.5) * (2.0 * kPiD) / kPhi;
      const glm::dvec3 l(st * std::cos(phi), st * std::sin(phi), ct);
      const glm::dvec3 h = glm::normalize(v + l);
      const double w = double(DistributionCharlie(float(h.z), r)) *
                       double(VisibilityCharlie(float(mu), float(ct), r)) * ct * st;
      m.e += w;
      m.mx += w * l.x;
      m.mz += w * l.z;
      m.xx += w * l.x * l.x;
      m.zz += w * l.z * l.z;
      m.xz += w * l.x * l.z;
    }
  }
  for (double* x : {&m.mx, &m.mz, &m.xx, &m.zz, &m.xz}) *x /= m.e;
  m.e *= (kPiD / 2.0 / kTheta) * (2.0 * kPiD / kPhi);
  return m;
}
double brute_force_angle(double mu, float r) {
  const BruteMoments m = brute_force_moments(mu, r);
  return std::atan2(m.mx, m.mz);
}

TEST(SheenLobeAngle, MatchesBruteForceMean) {
  const SheenTable& table = SheenTable::get();
  double worst = 0.0;
  for (float r : {0.07f, 0.12f, 0.3f, 0.45f, 0.6f, 0.83f, 1.0f})
    for (double mu : {0.03, 0.1, 0.26, 0.5, 0.77, 0.95}) {
      const double ref = brute_force_angle(mu, r);
      const double got = table.lobe_angle(float(mu), r);
      worst = std::max(worst, std::abs(got - ref));
      // 0.75 degrees (measured: 0.49, at n.v 0.95): a lookup direction that much off moves a
      // cosine-weighted average of a smooth environment by about 1%. (Not tested: the last
      // cell, n.v > 0.9685, where the mean's angle drops to 0 faster than its bilinear
      // interpolation, e.g. 0.36 rad for 0.46 at n.v 0.98 and roughness 0.3; there the mean
      // is short, the lobe close to a ring about n, and E small.)
      EXPECT_NEAR(got, ref, 0.75 * kPiD / 180.0) << "mu " << mu << " roughness " << r;
      // The lobe back-scatters: its mean lies on the viewer's side of n.
      EXPECT_GT(got, 0.0) << "mu " << mu << " roughness " << r;
    }
  std::printf("lobe angle vs brute force: max |error| %.3f degrees\n", worst * 180.0 / kPiD);
  EXPECT_NEAR(table.lobe_angle(1.0f, 0.5f), 0.0, 1e-6);  // normal incidence: n by symmetry
}

TEST(SheenLobeMoments, SecondMomentsMatchBruteForce) {
  const SheenTable& table = SheenTable::get();
  double worst = 0.0;
  for (float r : {0.07f, 0.2f, 0.45f, 0.83f, 1.0f})
    for (double mu : {0.03, 0.26, 0.5, 0.77, 0.95}) {
      const BruteMoments ref = brute_force_moments(mu, r);
      const glm::vec3 got = table.lobe_second_moments(float(mu), r);
      const glm::vec2 mean = table.lobe_mean(float(mu), r);
      // 0.005: the moments are 0.05-0.6; an error of 0.005 moves a band-2 term of the
      // environment by under 1% of its size.
      EXPECT_NEAR(got.x, ref.xx, 0.005) << "tt, mu " << mu << " roughness " << r;
      EXPECT_NEAR(got.y, ref.zz, 0.005) << "nn, mu " << mu << " roughness " << r;
      EXPECT_NEAR(got.z, ref.xz, 0.005) << "tn, mu " << mu << " roughness " << r;
      // The mean's t component falls steeply towards normal incidence (0 at n.v = 1): 0.01
      // there (measured 0.008 at n.v 0.95, roughness 0.07-0.2).
      EXPECT_NEAR(mean.x, ref.mx, 0.01) << "t, mu " << mu << " roughness " << r;
      EXPECT_NEAR(mean.y, ref.mz, 0.005) << "n, mu " << mu << " roughness " << r;
      worst = std::max(
          {worst, std::abs(got.x - ref.xx), std::abs(got.y - ref.zz), std::abs(got.z - ref.xz)});
      // The moments of a distribution on the sphere: tt + nn <= 1, tn^2 <= tt nn.
      EXPECT_LE(got.x + got.y, 1.0f + 1e-5f);
      EXPECT_LE(got.z * got.z, got.x * got.y + 1e-5f);
    }
  std::printf("second moments vs brute force: max |error| %.4f\n", worst);
}

TEST(SheenLobeMoments, MaxAlbedoAverageMatchesQuadrature) {
  // E_max_avg = 2 int max(E(mu), E(mu_l)) mu_l dmu_l, here by a plain midpoint rule in mu_l
  // over SheenTable::E (the quantity is defined on E; its own quadrature runs in sqrt(mu_l)).
  const SheenTable& table = SheenTable::get();
  for (float r : {0.07f, 0.3f, 0.61f, 1.0f})
    for (float mu : {0.02f, 0.2f, 0.5f, 0.9f, 1.0f}) {
      constexpr int kN = 4000;
      double sum = 0.0;
      const double e_v = table.E(mu, r);
      for (int k = 0; k < kN; ++k) {
        const double mu_l = (k + 0.5) / kN;
        sum += std::max(e_v, double(table.E(float(mu_l), r))) * mu_l;
      }
      EXPECT_NEAR(table.E_max_avg(mu, r), 2.0 * sum / kN, 2e-3) << mu << " " << r;
      // Between E(mu) and the largest E: max(E(mu), E(mu_l)) >= E(mu).
      EXPECT_GE(table.E_max_avg(mu, r), e_v - 1e-4);
    }
}

}  // namespace
}  // namespace pbrkit
