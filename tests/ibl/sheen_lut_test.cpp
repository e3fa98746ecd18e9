// The sheen LUT (ibl/sheen_lut.h) against an independent quadrature of the Charlie lobe.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "pbrkit/core/sheen.h"
#include "pbrkit/ibl/sheen_lut.h"
#include "support/chi2.h"

namespace pbrkit {
namespace {

constexpr double kPiD = std::numbers::pi;

// int D V (n.l) dl over the hemisphere by a midpoint (theta, phi) grid in double, h from
// normalize(v + l) (no substitution, no symmetry: not the library's quadrature).
double directional_albedo(double mu, double r, int n_theta = 800, int n_phi = 1600) {
  const glm::dvec3 v(std::sqrt(1.0 - mu * mu), 0.0, mu);
  double sum = 0.0;
  for (int i = 0; i < n_theta; ++i) {
    const double theta = (i + 0.5) * (kPiD / 2.0) / n_theta;
    const double ct = std::cos(theta), st = std::sin(theta);
    const double vis = VisibilityCharlie(float(mu), float(ct), float(r));
    double row = 0.0;
    for (int k = 0; k < n_phi; ++k) {
      const double phi = (k + 0.5) * 2.0 * kPiD / n_phi;
      const glm::dvec3 l(st * std::cos(phi), st * std::sin(phi), ct);
      row += DistributionCharlie(float(glm::normalize(v + l).z), float(r));
    }
    sum += row * vis * ct * st;
  }
  return sum * (kPiD / 2.0 / n_theta) * (2.0 * kPiD / n_phi);
}

TEST(SheenLut, ChannelsMatchIndependentQuadrature) {
  const int size = 32;
  const Image lut = compute_sheen_lut(size);
  ASSERT_EQ(lut.width, size);
  ASSERT_EQ(lut.channels, 4);
  double worst_dg = 0.0, worst_avg = 0.0;
  for (int y : {0, 1, 5, 13, 22, 31}) {
    const double r = (y + 0.5) / size;
    // G: E_avg = 2 int_0^1 E(mu) mu dmu, by adaptive Simpson over mu of the grid quadrature.
    const double e_avg =
        2.0 *
        test::adaptive_simpson(
            [&](double mu) { return mu <= 0.0 ? 0.0 : directional_albedo(mu, r, 200, 400) * mu; },
            0.0, 1.0, 2e-4, 6);
    for (int x : {0, 3, 10, 20, 31}) {
      const double mu = (x + 0.5) / size;
      const double dg = directional_albedo(mu, r);
      EXPECT_NEAR(lut.pixel(x, y)[0], dg, 1e-3) << "R (DG) at n.v " << mu << " roughness " << r;
      if (std::abs(lut.pixel(x, y)[0] - dg) > worst_dg)
        std::printf("  worst so far: n.v %.4f r %.4f LUT %.5f quadrature %.5f\n", mu, r,
                    lut.pixel(x, y)[0], dg);
      worst_dg = std::max(worst_dg, std::abs(lut.pixel(x, y)[0] - dg));
      EXPECT_NEAR(lut.pixel(x, y)[1], e_avg, 1e-3) << "G (E_avg) at roughness " << r;
      EXPECT_EQ(lut.pixel(x, y)[2], 0.0f);
      EXPECT_EQ(lut.pixel(x, y)[3], 1.0f);
    }
    worst_avg = std::max(worst_avg, std::abs(lut.pixel(0, y)[1] - e_avg));
  }
  std::printf("sheen LUT vs quadrature: max |error| DG %.2e, E_avg %.2e\n", worst_dg, worst_avg);
}

TEST(SheenLut, RejectsBadSize) {
  EXPECT_THROW(compute_sheen_lut(0), std::exception);
  EXPECT_THROW(compute_sheen_lut(4097), std::exception);
}

}  // namespace
}  // namespace pbrkit
