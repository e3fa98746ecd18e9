// GGX microfacet terms (core/microfacet.h) against closed forms written independently here,
// normalisation integrals by quadrature, and chi-square fits of NDF and visible-normal
// sampling against their pdfs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"
#include "support/chi2.h"

namespace pbrkit {
namespace {

constexpr double kPiD = std::numbers::pi;

glm::vec3 spherical(double theta, double phi) {
  return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                   float(std::cos(theta)));
}

// ---- Closed forms written out from the papers in double (not through microfacet.h) ----
// GGX NDF in Walter et al. 2007's tangent form (eq. 33):
//   D(h) = alpha^2 / (pi cos^4(theta_h) (alpha^2 + tan^2(theta_h))^2).
double walter_D(glm::dvec3 h, double alpha) {
  h = glm::normalize(h);
  if (h.z <= 0.0) return 0.0;
  const double cos2 = h.z * h.z, tan2 = (h.x * h.x + h.y * h.y) / cos2, a2 = alpha * alpha;
  return a2 / (kPiD * cos2 * cos2 * (a2 + tan2) * (a2 + tan2));
}
// Smith's masking for GGX in Walter et al. 2007's form (eq. 34):
//   G1(v) = 2 / (1 + sqrt(1 + alpha^2 tan^2(theta_v))).
double walter_G1(glm::dvec3 v, double alpha) {
  v = glm::normalize(v);
  if (v.z <= 0.0) return 0.0;
  const double tan2 = (v.x * v.x + v.y * v.y) / (v.z * v.z);
  return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}
// The density of half vectors drawn from D(h)(n.h) (Walter 2007, eq. 38: p_m = D |m.n|).
double ndf_pdf_closed_form(glm::dvec3 h, double alpha) {
  return walter_D(h, alpha) * std::max(glm::normalize(h).z, 0.0);
}
// The distribution of visible normals (Heitz 2018, eq. 3): G1(v) max(0, v.h) D(h) / (n.v).
double vndf_pdf_closed_form(glm::dvec3 v, glm::dvec3 h, double alpha) {
  v = glm::normalize(v);
  h = glm::normalize(h);
  return walter_G1(v, alpha) * std::max(glm::dot(v, h), 0.0) * walter_D(h, alpha) / v.z;
}

glm::vec3 random_upper_direction(Pcg32& rng) {
  glm::vec3 w = sample_uniform_hemisphere(rng.next_2d()).direction;
  w.z = std::max(w.z, 1e-3f);
  return glm::normalize(w);
}

TEST(DistributionGGX, IntegratesToOneOverHemisphere) {
  // int D(h) (n.h) dw = 2 pi int_0^{pi/2} D(theta) cos(theta) sin(theta) dtheta = 1
  // (MODEL.md: D is a density of projected microfacet area). Adaptive Simpson in theta
  // resolves the peak of width ~alpha at the pole.
  for (float alpha : {0.02f, 0.1f, 0.3f, 0.6f, 1.0f}) {
    const double vec_form = test::adaptive_simpson(
        [&](double t) {
          return 2.0 * kPiD * DistributionGGX(spherical(t, 0.3), alpha) * std::cos(t) * std::sin(t);
        },
        0.0, kPiD / 2, 1e-7, 20);
    const double cos_form = test::adaptive_simpson(
        [&](double t) {
          return 2.0 * kPiD * DistributionGGX(float(std::cos(t)), alpha) * std::cos(t) *
                 std::sin(t);
        },
        0.0, kPiD / 2, 1e-7, 20);
    EXPECT_NEAR(vec_form, 1.0, 1e-3) << "alpha " << alpha;
    EXPECT_NEAR(cos_form, 1.0, 1e-3) << "alpha " << alpha;
  }
}

TEST(DistributionGGX, ClosedFormValues) {
  for (float alpha : {0.01f, 0.2f, 0.7f}) {
    // At the normal: 1 / (pi alpha^2).
    EXPECT_NEAR(DistributionGGX(glm::vec3(0, 0, 1), alpha), 1.0 / (kPiD * alpha * alpha),
                1e-5 / (alpha * alpha));
    // The cosine form cancels in (n.h)^2 (alpha^2 - 1) + 1 at small alpha (which is why
    // microfacet.h also has the vector form), hence the looser tolerance.
    EXPECT_NEAR(DistributionGGX(1.0f, alpha), 1.0 / (kPiD * alpha * alpha), 2e-3 / (alpha * alpha));
  }
  // alpha = 1: uniform, 1/pi over the hemisphere, 0 below.
  for (double t : {0.1, 0.7, 1.4}) {
    EXPECT_NEAR(DistributionGGX(spherical(t, 1.0), 1.0f), 1.0 / kPiD, 1e-6);
    EXPECT_NEAR(DistributionGGX(float(std::cos(t)), 1.0f), 1.0 / kPiD, 1e-6);
  }
  EXPECT_EQ(DistributionGGX(glm::vec3(0.6f, 0.0f, -0.8f), 0.5f), 0.0f);
  EXPECT_EQ(DistributionGGX(-0.5f, 0.5f), 0.0f);
  // Both forms agree where the cosine form is well conditioned; against the textbook
  // formula alpha^2 / (pi (c^2 (alpha^2 - 1) + 1)^2) in double.
  Pcg32 rng(5);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 h = random_upper_direction(rng);
    const float alpha = 0.05f + 0.95f * rng.next_float();
    const double c = h.z, a2 = double(alpha) * alpha;
    const double d = (c * c * (a2 - 1.0) + 1.0);
    const double expected = a2 / (kPiD * d * d);
    EXPECT_NEAR(DistributionGGX(h, alpha), expected, 1e-5 * expected);
    EXPECT_NEAR(DistributionGGX(h.z, alpha), expected, 1e-4 * expected);
  }
}

TEST(SmithGGX, LambdaClosedForms) {
  // alpha = 1: Lambda = (1/cos - 1) / 2; normal incidence: 0; grazing: infinite.
  for (double t : {0.0, 0.4, 1.0, 1.5}) {
    const glm::vec3 w = spherical(t, 0.2);
    EXPECT_NEAR(SmithLambdaGGX(w, 1.0f), 0.5 * (1.0 / std::cos(t) - 1.0),
                1e-5 * (1.0 + 1.0 / std::cos(t)));
    EXPECT_NEAR(SmithG1GGX(w, 1.0f), 2.0 * std::cos(t) / (1.0 + std::cos(t)), 1e-6);
  }
  EXPECT_EQ(SmithLambdaGGX(glm::vec3(0, 0, 1), 0.3f), 0.0f);
  EXPECT_EQ(SmithG1GGX(glm::vec3(1, 0, 0), 0.3f), 0.0f);
  EXPECT_EQ(SmithG1GGX(glm::vec3(0.6f, 0, -0.8f), 0.3f), 0.0f);
}

// Heitz 2014's height-correlated G2 in the algebraic form used by Filament and the glTF
// specification's reference BRDF (Vis = G2 / (4 NdotL NdotV)):
//   Vis = 0.5 / (NdotL sqrt(NdotV^2 (1 - a2) + a2) + NdotV sqrt(NdotL^2 (1 - a2) + a2)).
double heitz_g2(double NdotV, double NdotL, double alpha) {
  const double a2 = alpha * alpha;
  const double vis = 0.5 / (NdotL * std::sqrt(NdotV * NdotV * (1.0 - a2) + a2) +
                            NdotV * std::sqrt(NdotL * NdotL * (1.0 - a2) + a2));
  return vis * 4.0 * NdotL * NdotV;
}

TEST(SmithGGX, HeightCorrelatedMatchesHeitzClosedForm) {
  Pcg32 rng(8);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 wo = random_upper_direction(rng), wi = random_upper_direction(rng);
    const float roughness = 0.02f + 0.98f * rng.next_float();
    const float alpha = roughness * roughness;
    const double expected = heitz_g2(wo.z, wi.z, alpha);
    EXPECT_NEAR(SmithG2HeightCorrelated(wo, wi, alpha), expected, 1e-5 * expected + 1e-7);
    EXPECT_NEAR(GeometryG(GeometryModel::kReference, wo, wi, roughness), expected,
                1e-5 * expected + 1e-7);
  }
  EXPECT_EQ(SmithG2HeightCorrelated(glm::vec3(0, 0, 1), glm::vec3(0.6f, 0, -0.8f), 0.3f), 0.0f);
}

TEST(SchlickGGX, SeedFormulas) {
  // LearnOpenGL: GeometrySchlickGGX(NdotV, roughness) with k = (r + 1)^2 / 8 (direct) and
  // k = r^2 / 2 (IBL), GeometrySmith = product.
  for (float r : {0.0f, 0.3f, 1.0f}) {
    EXPECT_FLOAT_EQ(k_direct(r), (r + 1) * (r + 1) / 8);
    EXPECT_FLOAT_EQ(k_ibl(r), r * r / 2);
    for (float nv : {0.05f, 0.5f, 1.0f})
      for (float nl : {0.1f, 0.7f}) {
        const double k = (r + 1.0) * (r + 1.0) / 8.0;
        const double g1v = nv / (nv * (1.0 - k) + k), g1l = nl / (nl * (1.0 - k) + k);
        EXPECT_NEAR(GeometrySchlickGGX(nv, float(k)), g1v, 1e-6);
        EXPECT_NEAR(GeometrySmithSchlick(nv, nl, float(k)), g1v * g1l, 1e-6);
        const glm::vec3 wo(std::sqrt(1 - nv * nv), 0, nv), wi(0, std::sqrt(1 - nl * nl), nl);
        EXPECT_NEAR(GeometryG(GeometryModel::kClassicDirect, wo, wi, r), g1v * g1l, 1e-6);
        const double ki = r * r / 2.0;
        EXPECT_NEAR(GeometryG(GeometryModel::kClassicIBL, wo, wi, r),
                    nv / (nv * (1 - ki) + ki) * nl / (nl * (1 - ki) + ki), 1e-6);
      }
  }
}

TEST(Fresnel, SchlickValuesAndAverage) {
  const glm::vec3 F0(0.04f, 0.5f, 0.95f);
  EXPECT_EQ(fresnelSchlick(1.0f, F0), F0);
  EXPECT_EQ(fresnelSchlick(0.0f, F0), glm::vec3(1.0f));
  const glm::vec3 f = fresnelSchlick(0.3f, F0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], F0[c] + (1.0 - F0[c]) * std::pow(0.7, 5.0), 1e-6);
  // Cosine-weighted hemispherical average 2 int F(mu) mu dmu = F0 + (1 - F0)/21.
  for (int c = 0; c < 3; ++c) {
    const double avg = test::adaptive_simpson(
        [&](double mu) { return 2.0 * fresnelSchlick(float(mu), F0)[c] * mu; }, 0.0, 1.0, 1e-10);
    EXPECT_NEAR(fresnelSchlickAverage(F0)[c], avg, 1e-6);
  }
  // Karis 2013's spherical-Gaussian variant stays close to Schlick's (what justifies it as
  // a cheaper real-time substitute): max difference measured < 0.01 for F0 = 0.
  for (int i = 0; i <= 100; ++i) {
    const float c = i / 100.0f;
    EXPECT_NEAR(fresnelSchlickSG(c, glm::vec3(0.0f)).x, fresnelSchlick(c, glm::vec3(0.0f)).x, 0.01f)
        << c;
  }
}

TEST(VisibleNormals, PdfIntegratesToOne) {
  // int G1(wo) max(0, wo.h) D(h) / wo.z dh = 1 is Smith's projected-area identity
  // (Heitz 2014, eq. 2 with G1 = 1/(1 + Lambda)): it checks Lambda against D.
  for (float mu : {0.05f, 0.3f, 0.7f, 1.0f})
    for (float alpha : {0.05f, 0.3f, 1.0f}) {
      const glm::vec3 wo(std::sqrt(1 - mu * mu), 0, mu);
      const std::vector<double> bins = test::integrate_pdf_over_bins(
          [&](glm::vec3 h) { return double(ggx_vndf_pdf(wo, h, alpha)); }, test::Chi2Options{});
      double total = 0.0;
      for (double b : bins) total += b;
      EXPECT_NEAR(total, 1.0, 2e-4) << "mu " << mu << " alpha " << alpha;
    }
}

TEST(GgxSampling, NdfChi2) {
  // Family: 5 roughnesses (0.05, 0.1, 0.3, 0.6, 1).
  test::Chi2Options options;
  options.runs = 5;
  for (float roughness : {0.05f, 0.1f, 0.3f, 0.6f, 1.0f}) {
    const float alpha = roughness * roughness;
    Pcg32 rng(3);
    for (int i = 0; i < 1000; ++i) {
      const HalfVectorSample s = sample_ggx_ndf(rng.next_2d(), alpha);
      EXPECT_NEAR(glm::length(s.h), 1.0f, 1e-5f);
      // The returned pdf against Walter 2007's closed form evaluated in double; the
      // sampler works in float (relative rounding ~1e-6).
      const double expected = ndf_pdf_closed_form(glm::dvec3(s.h), alpha);
      EXPECT_NEAR(s.pdf, expected, 1e-5 * expected) << "roughness " << roughness;
    }
    const test::Chi2Result r = test::chi2_sphere_test(
        [&](float, glm::vec2 u) -> std::optional<glm::vec3> { return sample_ggx_ndf(u, alpha).h; },
        [&](glm::vec3 h) { return double(ggx_ndf_pdf(h, alpha)); }, options);
    EXPECT_TRUE(r.passed) << "roughness " << roughness << "\n" << r.report;
    EXPECT_NEAR(r.pdf_integral, 1.0, 1e-5);
  }
}

TEST(GgxSampling, VisibleNormalChi2) {
  // Family: 3 view angles (including grazing mu = 0.05) x 4 roughnesses.
  test::Chi2Options options;
  options.runs = 12;
  for (float mu : {0.05f, 0.5f, 0.95f})
    for (float roughness : {0.05f, 0.3f, 0.7f, 1.0f}) {
      const float alpha = roughness * roughness;
      const glm::vec3 wo = glm::normalize(
          glm::vec3(std::sqrt(1 - mu * mu) * 0.6f, std::sqrt(1 - mu * mu) * 0.8f, mu));
      Pcg32 rng(4);
      for (int i = 0; i < 1000; ++i) {
        const HalfVectorSample s = sample_ggx_vndf(wo, rng.next_2d(), alpha);
        EXPECT_NEAR(glm::length(s.h), 1.0f, 1e-5f);
        EXPECT_GT(s.h.z, 0.0f);
        // Heitz 2018 eq. 3 with Walter 2007's D and G1, in double.
        const double expected = vndf_pdf_closed_form(glm::dvec3(wo), glm::dvec3(s.h), alpha);
        EXPECT_NEAR(s.pdf, expected, 1e-5 * expected) << "mu " << mu << " roughness " << roughness;
      }
      const test::Chi2Result r = test::chi2_sphere_test(
          [&](float, glm::vec2 u) -> std::optional<glm::vec3> {
            return sample_ggx_vndf(wo, u, alpha).h;
          },
          [&](glm::vec3 h) { return double(ggx_vndf_pdf(wo, h, alpha)); }, options);
      EXPECT_TRUE(r.passed) << "mu " << mu << " roughness " << roughness << "\n" << r.report;
      EXPECT_NEAR(r.pdf_integral, 1.0, 1e-4);
    }
}

TEST(GgxSampling, ReflectedDirectionsMatchClosedFormPdfChi2) {
  // The density of the reflected direction l = 2 (v.h) h - v, written out here from the
  // papers (not through ggx_*_pdf or reflected_pdf): the half-vector density times the
  // Jacobian |dh/dl| = 1 / (4 v.h) (Walter 2007, eq. 14), i.e.
  //   NDF sampling:  D(h)(n.h) / (4 v.h)   (Walter 2007, eqs. 17 and 38; MODEL.md)
  //   VNDF sampling: G1(v) D(h) / (4 n.v)  (Heitz 2018, eq. 17).
  // NDF samples with v.h <= 0 reflect nothing and are rejected; the chi-square helper
  // compares their number with the closed form's missing mass.
  struct Case {
    bool visible;
    float mu, roughness;
  };
  const Case cases[] = {
      {false, 0.4f, 0.3f}, {false, 0.9f, 0.8f}, {true, 0.1f, 0.2f}, {true, 0.6f, 0.6f}};
  test::Chi2Options options;
  options.runs = int(std::size(cases));
  for (const Case& c : cases) {
    const float alpha = c.roughness * c.roughness;
    const glm::vec3 wo(0.6f * std::sqrt(1 - c.mu * c.mu), 0.8f * std::sqrt(1 - c.mu * c.mu), c.mu);
    const glm::dvec3 v(wo);
    const test::Chi2Result r = test::chi2_sphere_test(
        [&](float, glm::vec2 u) -> std::optional<glm::vec3> {
          const glm::vec3 h =
              c.visible ? sample_ggx_vndf(wo, u, alpha).h : sample_ggx_ndf(u, alpha).h;
          const float VdotH = glm::dot(wo, h);
          if (VdotH <= 0.0f) return std::nullopt;
          return 2.0f * VdotH * h - wo;
        },
        [&](glm::vec3 l) {
          const glm::dvec3 sum = v + glm::dvec3(l);
          if (glm::length(sum) < 1e-9) return 0.0;
          const glm::dvec3 h = glm::normalize(sum);
          const double VdotH = glm::dot(v, h);
          if (h.z <= 0.0 || VdotH <= 0.0) return 0.0;
          return c.visible ? walter_G1(v, alpha) * walter_D(h, alpha) / (4.0 * v.z)
                           : ndf_pdf_closed_form(h, alpha) / (4.0 * VdotH);
        },
        options);
    EXPECT_TRUE(r.passed) << (c.visible ? "VNDF" : "NDF") << " mu " << c.mu << " roughness "
                          << c.roughness << "\n"
                          << r.report;
    // VNDF sampling never rejects (Heitz 2018 samples only v.h > 0).
    if (c.visible) {
      EXPECT_NEAR(r.pdf_integral, 1.0, 1e-4);
    }
  }
}

}  // namespace
}  // namespace pbrkit
