// The split-sum BRDF LUT against a direct quadrature written out here, an independent
// integration (visible-normal sampling, the foundation's EnergyTable::integrate_AB) and the
// foundation's albedo tables.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/core/math.h"
#include "pbrkit/ibl/brdf_lut.h"

namespace pbrkit {
namespace {

// (A, B) of Karis 2013's split sum, A = int (1 - Fc) f_spec cos dl and B = int Fc f_spec cos dl
// with f_spec F-free (F = F0 (1 - Fc) + Fc, Fc = (1 - v.h)^5): f_spec cos = D G / (4 n.v).
// D (Walter 2007's tangent form) and G (Heitz 2014's height-correlated Smith, or the Smith
// product of Schlick-GGX with k = alpha / 2) are written out here in double, not through
// microfacet.h, and integrated by a midpoint rule over the light direction's (theta, phi):
// no sampling routine involved. V lies in the xz plane, so the integrand is even in phi and
// phi runs over [0, pi] (doubled). With n = 256 per dimension (0.35 degrees) this is within
// 3e-5 of n = 512 for roughness >= 0.5, where D is smooth at this spacing.
glm::dvec2 quadrature_AB(BrdfModel model, double mu, double roughness, int n = 256) {
  const double alpha = roughness * roughness, a2 = alpha * alpha;
  const glm::dvec3 V(std::sqrt(1.0 - mu * mu), 0.0, mu);
  // Heitz 2014, eq. 72, with cosines: Lambda = (sqrt(1 + alpha^2 tan^2) - 1) / 2.
  auto lambda = [&](double c) {
    return 0.5 * (std::sqrt(1.0 + a2 * (1.0 - c * c) / (c * c)) - 1.0);
  };
  auto schlick = [&](double c) { return c / (c * (1.0 - alpha / 2.0) + alpha / 2.0); };
  const double d_theta = (kPi / 2) / n, d_phi = kPi / n;
  glm::dvec2 sum(0.0);
  for (int i = 0; i < n; ++i) {
    const double theta = (i + 0.5) * d_theta;
    for (int j = 0; j < n; ++j) {
      const double phi = (j + 0.5) * d_phi;
      const glm::dvec3 L(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                         std::cos(theta));
      const glm::dvec3 H = glm::normalize(V + L);
      const double cos2 = H.z * H.z, tan2 = (H.x * H.x + H.y * H.y) / cos2;
      const double D = a2 / (kPi * cos2 * cos2 * (a2 + tan2) * (a2 + tan2));
      const double G = model == BrdfModel::kReference ? 1.0 / (1.0 + lambda(mu) + lambda(L.z))
                                                      : schlick(mu) * schlick(L.z);
      const double Fc = std::pow(1.0 - glm::dot(V, H), 5.0);
      const double dw = 2.0 * std::sin(theta) * d_theta * d_phi;
      sum += glm::dvec2(1.0 - Fc, Fc) * (D * G / (4.0 * mu)) * dw;
    }
  }
  return sum;
}

// E_avg = 2 int_0^1 (A + B)(mu) mu dmu (Kulla & Conty 2017) by 8-point Gauss-Legendre on
// [0, 0.25] and [0.25, 1] over the quadrature above at n = 128 (within 6e-5 of n = 256).
double quadrature_E_avg(BrdfModel model, double roughness) {
  constexpr double kNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                0.9602898564975363};
  constexpr double kWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                  0.1012285362903763};
  double E_avg = 0.0;
  for (const auto& [a, b] : {std::pair(0.0, 0.25), std::pair(0.25, 1.0)})
    for (int k = 0; k < 4; ++k)
      for (double side : {-1.0, 1.0}) {
        const double mu = 0.5 * (a + b) + side * 0.5 * (b - a) * kNodes[k];
        const glm::dvec2 ab = quadrature_AB(model, mu, roughness, 128);
        E_avg += 0.5 * (b - a) * kWeights[k] * 2.0 * (ab.x + ab.y) * mu;
      }
  return E_avg;
}

TEST(BrdfLutQuadrature, EveryChannelMatchesADirectQuadrature) {
  // Tolerance 1e-3: the LUT's 1024 Hammersley points carry an O(1/N) bias (measured
  // 2e-4..6.4e-4 in A against this quadrature, shrinking 4x with 4x the points and to
  // < 1e-5 at 65,536), plus the quadrature's 3e-5; E_avg adds the midpoint rule of the
  // LUT's row (16 texels), measured 7.5e-4 in all.
  constexpr int kSize = 16;
  for (BrdfModel model : {BrdfModel::kReference, BrdfModel::kClassic}) {
    const Image lut = compute_brdf_lut(model, kSize);
    for (int y : {8, 12, 15}) {
      const double roughness = (y + 0.5) / kSize;
      for (int x : {3, 8, 14}) {
        const double mu = (x + 0.5) / kSize;
        const glm::dvec2 ref = quadrature_AB(model, mu, roughness);
        const float* p = lut.pixel(x, y);
        EXPECT_NEAR(p[0], ref.x, 1e-3) << "A mu " << mu << " r " << roughness;
        EXPECT_NEAR(p[1], ref.y, 1e-3) << "B mu " << mu << " r " << roughness;
        // E = A + B is the albedo of the F0 = 1 lobe.
        EXPECT_NEAR(p[2], ref.x + ref.y, 1e-3) << "E mu " << mu << " r " << roughness;
      }
      // Every texel of a row holds E_avg of its roughness.
      const double E_avg = quadrature_E_avg(model, roughness);
      for (int x : {0, 7, kSize - 1})
        EXPECT_NEAR(lut.pixel(x, y)[3], E_avg, 1e-3) << "E_avg x " << x << " r " << roughness;
    }
  }
}

class BrdfLut : public testing::TestWithParam<BrdfModel> {};

TEST_P(BrdfLut, MatchesIndependentIntegrationAndTheAlbedoTable) {
  const BrdfModel model = GetParam();
  const GeometryModel geometry = ibl_geometry(model);
  constexpr int kSize = 32;
  const Image lut = compute_brdf_lut(model, kSize);
  ASSERT_EQ(lut.width, kSize);
  ASSERT_EQ(lut.channels, 4);
  const EnergyTable& table = EnergyTable::get(geometry);
  for (int y : {2, 8, 15, 24, 31}) {
    for (int x : {1, 4, 10, 16, 23, 31}) {
      const float mu = (x + 0.5f) / kSize, roughness = (y + 0.5f) / kSize;
      const float* p = lut.pixel(x, y);
      const glm::vec2 ref = EnergyTable::integrate_AB(geometry, mu, roughness, 1 << 16);
      EXPECT_NEAR(p[0], ref.x, 1e-3f) << "A at mu " << mu << " r " << roughness;
      EXPECT_NEAR(p[1], ref.y, 1e-3f) << "B at mu " << mu << " r " << roughness;
      // The foundation's 32x32 table is bilinearly interpolated between its nodes; that is
      // within 3e-3 except at grazing n.v < 0.1, where E(mu) bends sharply between nodes
      // (measured up to 1.3e-2 at mu = 0.047).
      if (mu >= 0.1f) {
        EXPECT_NEAR(p[2], table.E(mu, roughness), 3e-3f) << "E at mu " << mu << " r " << roughness;
      }
    }
    // E_avg = 2 int E mu dmu, in every texel of a row.
    const float roughness = (y + 0.5f) / kSize;
    for (int x : {0, kSize - 1})
      EXPECT_NEAR(lut.pixel(x, y)[3], table.E_avg(roughness), 3e-3f) << x << " " << roughness;
  }
}

TEST_P(BrdfLut, SpecialisedLoopIsTheCoreVisibleNormalEstimator) {
  // compute_brdf_lut's loop is Heitz 2018's sampling specialised to v in the xz plane with
  // the disk points precomputed: the same 1024-point estimator as the core's
  // EnergyTable::integrate_AB (sample_ggx_vndf), up to float rounding.
  const BrdfModel model = GetParam();
  constexpr int kSize = 64;
  const Image lut = compute_brdf_lut(model, kSize);
  for (int y : {0, 5, 20, 41, 63})
    for (int x : {0, 2, 17, 40, 63}) {
      const float mu = (x + 0.5f) / kSize, roughness = (y + 0.5f) / kSize;
      const glm::vec2 ref = EnergyTable::integrate_AB(ibl_geometry(model), mu, roughness, 1024);
      EXPECT_NEAR(lut.pixel(x, y)[0], ref.x, 2e-5f) << "A at mu " << mu << " r " << roughness;
      EXPECT_NEAR(lut.pixel(x, y)[1], ref.y, 2e-5f) << "B at mu " << mu << " r " << roughness;
    }
}

INSTANTIATE_TEST_SUITE_P(Models, BrdfLut,
                         testing::Values(BrdfModel::kReference, BrdfModel::kClassic));

TEST(BrdfLutShape, SmoothMetalReflectsEverythingAtNormalIncidence) {
  // At tiny roughness and n.v ~ 1 the lobe is a mirror: A ~ 1, B ~ 0 (F(1) = F0).
  const Image lut = compute_brdf_lut(BrdfModel::kReference, 64);
  EXPECT_NEAR(lut.pixel(63, 0)[0], 1.0f, 2e-3f);
  EXPECT_NEAR(lut.pixel(63, 0)[1], 0.0f, 1e-3f);
  // Single scattering never creates energy (exact G): E <= 1, and rough surfaces lose some
  // (Kulla & Conty 2017: the loss the multiple-scattering term restores).
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) EXPECT_LE(lut.pixel(x, y)[2], 1.0f + 1e-4f) << x << " " << y;
  EXPECT_LT(lut.pixel(63, 0)[3], 1.0f + 1e-4f);
  EXPECT_LT(lut.pixel(32, 63)[2], 0.9f);
}

}  // namespace
}  // namespace pbrkit
