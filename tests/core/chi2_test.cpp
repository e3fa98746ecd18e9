// Tests of the test: the chi-square machinery in tests/support/chi2.cpp must accept a
// correct sampler/pdf pair and reject wrong pdfs (pbrt-v4 and Mitsuba 3 both rely on the
// same construction, so a harness that always passes would silently void every sampling
// test in this directory).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"
#include "support/chi2.h"

namespace pbrkit::test {
namespace {

constexpr double kPiD = std::numbers::pi;

TEST(Chi2Survival, KnownQuantiles) {
  // Upper 5% / 1% points of the chi-square distribution (standard tables).
  EXPECT_NEAR(chi2_survival(3.841459, 1), 0.05, 1e-6);
  EXPECT_NEAR(chi2_survival(6.634897, 1), 0.01, 1e-6);
  EXPECT_NEAR(chi2_survival(18.307038, 10), 0.05, 1e-6);
  EXPECT_NEAR(chi2_survival(124.342113, 100), 0.05, 1e-6);
  EXPECT_NEAR(chi2_survival(135.806723, 100), 0.01, 1e-6);
  // Two degrees of freedom: Q = exp(-x / 2) exactly.
  for (double x : {0.1, 1.0, 5.0, 30.0}) EXPECT_NEAR(chi2_survival(x, 2), std::exp(-x / 2), 1e-12);
  EXPECT_EQ(chi2_survival(0.0, 5), 1.0);
}

TEST(AdaptiveSimpson, ClosedForms) {
  EXPECT_NEAR(adaptive_simpson([](double x) { return std::sin(x); }, 0.0, kPiD, 1e-10), 2.0, 1e-9);
  // A narrow Lorentzian peak: int_0^1 w / (pi ((x - 0.3)^2 + w^2)) dx with w = 1e-4.
  const double w = 1e-4;
  const double exact = (std::atan(0.7 / w) + std::atan(0.3 / w)) / kPiD;
  EXPECT_NEAR(
      adaptive_simpson([&](double x) { return w / (kPiD * ((x - 0.3) * (x - 0.3) + w * w)); }, 0.0,
                       1.0, 1e-9),
      exact, 1e-7);
}

TEST(Chi2Bins, UniformPdfIntegratesToBinAreas) {
  Chi2Options options;
  const std::vector<double> bins =
      integrate_pdf_over_bins([](glm::vec3) { return 1.0 / (4.0 * kPiD); }, options);
  for (int i = 0; i < options.theta_bins; ++i)
    for (int j = 0; j < options.phi_bins; ++j) {
      const double t0 = kPiD * i / options.theta_bins, t1 = kPiD * (i + 1) / options.theta_bins;
      const double area = (std::cos(t0) - std::cos(t1)) * 2.0 * kPiD / options.phi_bins;
      EXPECT_NEAR(bins[std::size_t(i * options.phi_bins + j)], area / (4.0 * kPiD), 1e-9);
    }
}

TEST(Chi2Bins, SharpGgxLobeIsResolved) {
  // The NDF pdf D(h)(n.h) at alpha = 0.0025 (roughness 0.05) is a spike of width ~0.003
  // rad; the adaptive cubature must still find all of its mass.
  for (float alpha : {0.0025f, 0.01f}) {
    const std::vector<double> bins = integrate_pdf_over_bins(
        [alpha](glm::vec3 h) { return double(ggx_ndf_pdf(h, alpha)); }, Chi2Options{});
    double total = 0.0;
    for (double b : bins) total += b;
    EXPECT_NEAR(total, 1.0, 2e-6) << alpha;
  }
}

std::optional<glm::vec3> uniform_sphere(float, glm::vec2 u) {
  return sample_uniform_sphere(u).direction;
}

TEST(Chi2Test, AcceptsCorrectPdf) {
  Chi2Options options;
  options.runs = 2;
  const Chi2Result r = chi2_sphere_test(
      uniform_sphere, [](glm::vec3) { return 1.0 / (4.0 * kPiD); }, options);
  EXPECT_TRUE(r.passed) << r.report;
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-9);

  const float alpha = 0.3f;
  const Chi2Result g = chi2_sphere_test(
      [&](float, glm::vec2 u) -> std::optional<glm::vec3> { return sample_ggx_ndf(u, alpha).h; },
      [&](glm::vec3 h) { return double(ggx_ndf_pdf(h, alpha)); }, options);
  EXPECT_TRUE(g.passed) << g.report;
}

TEST(Chi2Test, RejectsPdfScaledInHalfTheDomain) {
  // The GGX NDF pdf scaled by 1.1 for phi in [0, pi) and renormalised (divided by 1.05):
  // a 5% error in two halves of the domain.
  const float alpha = 0.3f;
  auto sampler = [&](float, glm::vec2 u) -> std::optional<glm::vec3> {
    return sample_ggx_ndf(u, alpha).h;
  };
  const Chi2Result r = chi2_sphere_test(sampler, [&](glm::vec3 h) {
    const double scale = h.y >= 0.0f ? 1.1 : 1.0;
    return scale * ggx_ndf_pdf(h, alpha) / 1.05;
  });
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-5);
  EXPECT_FALSE(r.passed) << r.report;
  EXPECT_LT(r.p_value, 1e-6);
}

TEST(Chi2Test, RejectsWrongDistribution) {
  // The cosine pdf offered for the GGX sampler, and the uniform hemisphere pdf offered for
  // the cosine sampler.
  const float alpha = 0.5f;
  const Chi2Result a = chi2_sphere_test(
      [&](float, glm::vec2 u) -> std::optional<glm::vec3> { return sample_ggx_ndf(u, alpha).h; },
      [](glm::vec3 w) { return double(cosine_hemisphere_pdf(w.z)); });
  EXPECT_FALSE(a.passed) << a.report;
  const Chi2Result b = chi2_sphere_test(
      [](float, glm::vec2 u) -> std::optional<glm::vec3> {
        return sample_cosine_hemisphere(u).direction;
      },
      [](glm::vec3 w) { return w.z > 0.0f ? 1.0 / (2.0 * kPiD) : 0.0; });
  EXPECT_FALSE(b.passed) << b.report;
}

TEST(Chi2Test, RejectsSubtlyWrongBrdfPdf) {
  // The material sampler with compensation on, offered the pdf of the same material with
  // compensation off: only the lobe-selection probability differs (a few percent).
  const glm::vec3 wo = glm::normalize(glm::vec3(0.3f, 0.2f, 0.6f));
  const Brdf on(glm::vec3(0.8f), 0.5f, 0.6f, {BrdfModel::kReference, true});
  const Brdf off(glm::vec3(0.8f), 0.5f, 0.6f, {BrdfModel::kReference, false});
  ASSERT_NE(on.specular_probability(wo), off.specular_probability(wo));
  auto sampler = [&](float u_lobe, glm::vec2 u) -> std::optional<glm::vec3> {
    const BrdfSample s = on.sample(wo, u_lobe, u);
    if (!s.valid) return std::nullopt;
    return s.wi;
  };
  const Chi2Result wrong =
      chi2_sphere_test(sampler, [&](glm::vec3 wi) { return double(off.pdf(wo, wi)); });
  EXPECT_FALSE(wrong.passed) << wrong.report;
  const Chi2Result right =
      chi2_sphere_test(sampler, [&](glm::vec3 wi) { return double(on.pdf(wo, wi)); });
  EXPECT_TRUE(right.passed) << right.report;
}

TEST(Chi2Test, RejectsUnaccountedRejections) {
  // A sampler that silently drops 1% of its samples while its pdf claims full mass: the
  // rejected-samples cell must catch it.
  const Chi2Result r = chi2_sphere_test(
      [](float u_lobe, glm::vec2 u) -> std::optional<glm::vec3> {
        if (u_lobe < 0.01f) return std::nullopt;
        return sample_uniform_sphere(u).direction;
      },
      [](glm::vec3) { return 1.0 / (4.0 * kPiD); });
  EXPECT_FALSE(r.passed) << r.report;
  // ... and accepts it when the pdf is scaled to the mass it really has.
  const Chi2Result s = chi2_sphere_test(
      [](float u_lobe, glm::vec2 u) -> std::optional<glm::vec3> {
        if (u_lobe < 0.01f) return std::nullopt;
        return sample_uniform_sphere(u).direction;
      },
      [](glm::vec3) { return 0.99 / (4.0 * kPiD); });
  EXPECT_TRUE(s.passed) << s.report;
}

TEST(Chi2Test, RejectsSamplesWherePdfIsZero) {
  // A hemisphere sampler whose pdf is claimed to be the upper quarter only.
  const Chi2Result r = chi2_sphere_test(
      [](float, glm::vec2 u) -> std::optional<glm::vec3> {
        return sample_uniform_hemisphere(u).direction;
      },
      [](glm::vec3 w) { return w.z > 0.0f && w.y > 0.0f ? 1.0 / kPiD : 0.0; });
  EXPECT_FALSE(r.passed) << r.report;
}

}  // namespace
}  // namespace pbrkit::test
