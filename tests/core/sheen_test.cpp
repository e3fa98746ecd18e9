// The Charlie sheen lobe (core/sheen.h): D's normalisation, the sampler against its pdf
// (chi-square, with a demonstration that wrong pdfs are rejected), the visibility against a
// transcription of the KHR_materials_sheen README, reciprocity, and SheenTable against an
// independent brute-force quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "pbrkit/core/sampling.h"
#include "pbrkit/core/sheen.h"
#include "support/chi2.h"

namespace pbrkit {
namespace {

constexpr double kPiD = std::numbers::pi;

// The README's lambdaSheen, written out again in double (not calling the library).
double readme_l(double x, double alphaG) {
  const double t = (1.0 - alphaG) * (1.0 - alphaG);
  auto mix = [&](double a, double b) { return a * (1.0 - t) + b * t; };
  return mix(21.5473, 25.3245) /
             (1.0 + mix(3.82987, 3.32435) * std::pow(x, mix(0.19823, 0.16801))) +
         mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967);
}
double readme_lambda(double c, double alphaG) {
  return std::abs(c) < 0.5 ? std::exp(readme_l(c, alphaG))
                           : std::exp(2.0 * readme_l(0.5, alphaG) - readme_l(1.0 - c, alphaG));
}
double readme_D(double NdotH, double alphaG) {
  const double inv_r = 1.0 / alphaG;
  return (2.0 + inv_r) * std::pow(1.0 - NdotH * NdotH, 0.5 * inv_r) / (2.0 * kPiD);
}

const float kRoughnesses[] = {0.0f, 0.07f, 0.1f, 0.2f, 0.35f, 0.5f, 0.75f, 1.0f};

TEST(SheenDistribution, CosineWeightedIntegratesToOne) {
  // int D(h) cos(theta_h) dh over the hemisphere = 2 pi int_0^pi/2 D cos sin dtheta.
  for (float r : kRoughnesses) {
    const double integral = 2.0 * kPiD *
                            test::adaptive_simpson(
                                [&](double theta) {
                                  return double(DistributionCharlie(float(std::cos(theta)), r)) *
                                         std::cos(theta) * std::sin(theta);
                                },
                                0.0, kPiD / 2.0, 1e-9);
    EXPECT_NEAR(integral, 1.0, 1e-5) << "roughness " << r;
  }
}

TEST(SheenDistribution, MatchesReadmeAndClampsRoughness) {
  for (float r : {0.07f, 0.3f, 1.0f})
    for (float c : {0.0f, 0.2f, 0.7f, 0.99f})
      EXPECT_NEAR(DistributionCharlie(c, r), readme_D(c, r), 1e-5 * (1.0 + readme_D(c, r)));
  // Below kMinSheenRoughness the lobe is that of 0.07 (Filament, three.js).
  for (float c : {0.1f, 0.5f})
    EXPECT_FLOAT_EQ(DistributionCharlie(c, 0.0f), float(readme_D(c, 0.07)));
  EXPECT_EQ(DistributionCharlie(1.0f, 0.5f), 0.0f);  // sin(theta_h) = 0: no fibre faces n
}

TEST(SheenVisibility, MatchesReadme) {
  for (float r : {0.07f, 0.25f, 0.6f, 1.0f})
    for (float v : {0.05f, 0.3f, 0.5f, 0.8f, 1.0f})
      for (float l : {0.02f, 0.45f, 0.55f, 0.9f}) {
        const double expected =
            1.0 / ((1.0 + readme_lambda(v, r) + readme_lambda(l, r)) * (4.0 * v * l));
        EXPECT_NEAR(VisibilityCharlie(v, l, r), expected, 1e-5 * expected)
            << r << " " << v << " " << l;
      }
  // Lambda is continuous where the README switches branches.
  for (float r : {0.07f, 0.5f, 1.0f})
    EXPECT_NEAR(SheenLambda(0.4999f, r), SheenLambda(0.5001f, r), 1e-3 * SheenLambda(0.5f, r));
  EXPECT_EQ(VisibilityCharlie(0.0f, 0.5f, 0.5f), 0.0f);
  EXPECT_EQ(VisibilityCharlie(0.5f, -0.1f, 0.5f), 0.0f);
}

TEST(SheenBrdf, DTimesVIsReciprocal) {
  Pcg32 rng(7);
  for (int i = 0; i < 200; ++i) {
    const float r = rng.next_float();
    const glm::vec3 v = sample_uniform_hemisphere(rng.next_2d()).direction;
    const glm::vec3 l = sample_uniform_hemisphere(rng.next_2d()).direction;
    auto f = [&](glm::vec3 a, glm::vec3 b) {
      return DistributionCharlie(glm::normalize(a + b).z, r) * VisibilityCharlie(a.z, b.z, r);
    };
    const float fvl = f(v, l), flv = f(l, v);
    EXPECT_NEAR(fvl, flv, 1e-5f * std::max(1.0f, fvl));
    EXPECT_GE(fvl, 0.0f);
  }
}

TEST(SheenSampling, PdfMatchesCharliePdf) {
  Pcg32 rng(3);
  for (float r : kRoughnesses)
    for (int i = 0; i < 50; ++i) {
      const HalfVectorSample s = sample_charlie(rng.next_2d(), r);
      EXPECT_NEAR(glm::length(s.h), 1.0f, 1e-5f);
      EXPECT_GE(s.h.z, 0.0f);
      EXPECT_NEAR(s.pdf, readme_D(s.h.z, std::max(r, 0.07f)) * s.h.z, 1e-4 * (1.0 + s.pdf));
    }
}

TEST(SheenSampling, ChiSquare) {
  // 12 settings; Sidak-corrected. Includes the clamp (0 -> 0.07), 0.07 and 1.
  const float settings[] = {0.0f, 0.07f, 0.1f, 0.15f, 0.2f, 0.3f,
                            0.4f, 0.5f,  0.6f, 0.75f, 0.9f, 1.0f};
  test::Chi2Options options;
  options.runs = int(std::size(settings));
  for (float r : settings) {
    const test::Chi2Result res = test::chi2_sphere_test(
        [&](float, glm::vec2 u) -> std::optional<glm::vec3> { return sample_charlie(u, r).h; },
        [&](glm::vec3 h) { return double(charlie_pdf(h, r)); }, options);
    EXPECT_TRUE(res.passed) << "roughness " << r << ": " << res.report;
    EXPECT_NEAR(res.pdf_integral, 1.0, 1e-4) << r;
  }
}

TEST(SheenSampling, ChiSquareRejectsWrongPdfs) {
  // Sensitivity demonstration: the same harness must reject (a) the pdf of a neighbouring
  // roughness, (b) the right pdf scaled by 1.1 in half of phi (renormalised), (c) the pdf of
  // the sin^(1/r) distribution with the exponent read as 1/r^2 (alphaG squared) at r = 0.5.
  const float r = 0.5f;
  auto sampler = [&](float, glm::vec2 u) -> std::optional<glm::vec3> {
    return sample_charlie(u, r).h;
  };
  const test::Chi2Result a =
      test::chi2_sphere_test(sampler, [&](glm::vec3 h) { return double(charlie_pdf(h, 0.45f)); });
  EXPECT_FALSE(a.passed) << a.report;
  const test::Chi2Result b = test::chi2_sphere_test(sampler, [&](glm::vec3 h) {
    return (h.y >= 0.0f ? 1.1 : 1.0) * double(charlie_pdf(h, r)) / 1.05;
  });
  EXPECT_NEAR(b.pdf_integral, 1.0, 1e-4);
  EXPECT_FALSE(b.passed) << b.report;
  const test::Chi2Result c =
      test::chi2_sphere_test(sampler, [&](glm::vec3 h) { return double(charlie_pdf(h, r * r)); });
  EXPECT_FALSE(c.passed) << c.report;
}

// E(mu, r) = int D V (n.l) dl by a midpoint (theta, phi) grid over the hemisphere in double,
// with h = normalize(v + l) and dl = sin(theta) dtheta dphi (no substitution, no symmetry).
double brute_force_E(double mu, float r) {
  const int n_theta = 800, n_phi = 1600;
  const glm::dvec3 v(std::sqrt(1.0 - mu * mu), 0.0, mu);
  double sum = 0.0;
  for (int i = 0; i < n_theta; ++i) {
    const double theta = (i + 0.5) * (kPiD / 2.0) / n_theta;
    const double ct = std::cos(theta), st = std::sin(theta);
    const double vis = double(VisibilityCharlie(float(mu), float(ct), r));
    double row = 0.0;
    for (int k = 0; k < n_phi; ++k) {
      const double phi = (k + 0.5) * 2.0 * kPiD / n_phi;
      const glm::dvec3 l(st * std::cos(phi), st * std::sin(phi), ct);
      row += double(DistributionCharlie(float(glm::normalize(v + l).z), r));
    }
    sum += row * vis * ct * st;
  }
  return sum * (kPiD / 2.0 / n_theta) * (2.0 * kPiD / n_phi);
}

TEST(SheenTable, MatchesBruteForceQuadrature) {
  // Off the table's nodes (bilinear interpolation included) and on a few.
  const SheenTable& table = SheenTable::get();
  // E bends most at grazing n.v and small roughness: sampled densely there.
  const double mus[] = {0.015, 0.02, 0.05, 0.13, 0.3, 0.55, 0.8, 1.0};
  const float rs[] = {0.0f, 0.07f, 0.085f, 0.1f, 0.13f, 0.17f, 0.23f, 0.4f, 0.66f, 1.0f};
  double worst = 0.0;
  for (float r : rs)
    for (double mu : mus) {
      const double ref = brute_force_E(mu, r);
      const double got = table.E(float(mu), r);
      worst = std::max(worst, std::abs(got - ref));
      EXPECT_NEAR(got, ref, 1e-3) << "mu " << mu << " roughness " << r;
    }
  std::printf("SheenTable vs brute force: max |error| %.2e\n", worst);
}

TEST(SheenTable, AlbedoInUnitInterval) {
  const SheenTable& table = SheenTable::get();
  for (int j = 0; j <= 40; ++j)
    for (int i = 0; i <= 200; ++i) {
      const float mu = float(i) / 200.0f, r = float(j) / 40.0f;
      const float e = table.E(mu, r);
      EXPECT_GE(e, 0.0f) << mu << " " << r;
      EXPECT_LE(e, 1.0f) << mu << " " << r;
    }
  // Grazing directions straight from the quadrature too.
  for (float r : {0.07f, 0.3f, 1.0f})
    for (float mu : {1e-3f, 1e-2f}) {
      const float e = SheenTable::integrate_E(mu, r, 64);
      EXPECT_GT(e, 0.0f);
      EXPECT_LE(e, 1.0f);
    }
}

}  // namespace
}  // namespace pbrkit
