// The split-sum BRDF LUT against an independent integration (visible-normal sampling, the
// foundation's EnergyTable::integrate_AB) and the foundation's albedo tables.
#include <gtest/gtest.h>

#include <cmath>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/core/math.h"
#include "pbrkit/ibl/brdf_lut.h"

namespace pbrkit {
namespace {

// (A, B) by a midpoint rule over the light direction's spherical coordinates:
// int D G F / (4 n.v) dl with F = F0 (1 - Fc) + Fc. Independent of any sampling routine;
// accurate for roughness >= 0.5, where D is smooth at this grid's 0.2 degree spacing.
glm::dvec2 quadrature_AB(GeometryModel geometry, float mu, float roughness) {
  const int n_theta = 512, n_phi = 1024;
  const float alpha = roughness * roughness;
  const glm::vec3 V(std::sqrt(1.0f - mu * mu), 0.0f, mu);
  glm::dvec2 sum(0.0);
  for (int i = 0; i < n_theta; ++i) {
    const double theta = (i + 0.5) * (kPi / 2) / n_theta;
    for (int j = 0; j < n_phi; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPi / n_phi;
      const glm::vec3 L(float(std::sin(theta) * std::cos(phi)),
                        float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
      const glm::vec3 H = glm::normalize(V + L);
      const double f = double(DistributionGGX(H.z, alpha)) *
                       double(GeometryG(geometry, V, L, roughness)) / (4.0 * mu);
      const double Fc = std::pow(1.0 - double(glm::dot(V, H)), 5.0);
      const double dw = std::sin(theta) * (kPi / 2 / n_theta) * (2.0 * kPi / n_phi);
      sum += glm::dvec2(1.0 - Fc, Fc) * f * dw;
    }
  }
  return sum;
}

TEST(BrdfLutQuadrature, MatchesADirectQuadrature) {
  constexpr int kSize = 16;
  for (BrdfModel model : {BrdfModel::kReference, BrdfModel::kClassic}) {
    const Image lut = compute_brdf_lut(model, kSize);
    for (int y : {8, 12, 15})
      for (int x : {3, 8, 14}) {
        const float mu = (x + 0.5f) / kSize, roughness = (y + 0.5f) / kSize;
        const glm::dvec2 ref = quadrature_AB(ibl_geometry(model), mu, roughness);
        EXPECT_NEAR(lut.pixel(x, y)[0], ref.x, 1e-3) << "A mu " << mu << " r " << roughness;
        EXPECT_NEAR(lut.pixel(x, y)[1], ref.y, 1e-3) << "B mu " << mu << " r " << roughness;
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
      EXPECT_FLOAT_EQ(p[2], p[0] + p[1]);
      // The foundation's 32x32 table is bilinearly interpolated between its nodes; that is
      // within 3e-3 except at grazing n.v < 0.1, where E(mu) bends sharply between nodes
      // (measured up to 1.3e-2 at mu = 0.047).
      if (mu >= 0.1f) {
        EXPECT_NEAR(p[2], table.E(mu, roughness), 3e-3f) << "E at mu " << mu << " r " << roughness;
      }
    }
    // E_avg = 2 int E mu dmu, the same for every texel of a row.
    const float roughness = (y + 0.5f) / kSize;
    EXPECT_NEAR(lut.pixel(0, y)[3], table.E_avg(roughness), 3e-3f) << roughness;
    EXPECT_EQ(lut.pixel(0, y)[3], lut.pixel(kSize - 1, y)[3]);
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
