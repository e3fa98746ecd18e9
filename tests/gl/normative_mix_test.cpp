// A consistency check of the reference model's structure: the built-in `spheres`
// grid rendered by the OpenGL renderer in a uniform white environment (compensation off),
// where every sphere's centre shows its directional albedo at n.v ~ 1, against an
// independent quadrature of glTF 2.0 Appendix B's formula written out below
// (mix(dielectric, metal, metallic), the dielectric's diffuse weighted by 1 - F(v.h)). The
// Khronos Sample Viewer measured +11..25% brighter than our old renderer at metallic
// 0.17-0.67 for exactly this structure; the per-sphere table printed here (recorded in
// docs/SPLIT_SUM_ERRORS.md) shows the pattern is gone, and the old weighting, computed the
// same way, is shown to be far off (the test's sensitivity).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "gl_image_test_util.h"
#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/scene/load.h"
#include "support/chi2.h"

namespace pbrkit::gl {
namespace {

constexpr double kPiD = std::numbers::pi;

// The directional albedo at n.v = mu of the Appendix B material (height-correlated Smith
// GGX, Schlick Fresnel, F0 0.04 for the dielectric), or of LearnOpenGL's weighting
// (1 - F(v.h))(1 - metallic) with the mixed F0 when `old_weighting`.
double appendix_b_albedo(glm::dvec3 base, double metallic, double roughness, double mu, int ch,
                         bool old_weighting) {
  const double a = std::max(roughness, 0.02) * std::max(roughness, 0.02);
  const glm::dvec3 V(std::sqrt(1.0 - mu * mu), 0.0, mu);
  auto lambda = [a](glm::dvec3 w) {
    return (std::sqrt(1.0 + a * a * (w.x * w.x + w.y * w.y) / (w.z * w.z)) - 1.0) / 2.0;
  };
  return test::integrate_over_sphere(
      [&](glm::vec3 wi) {
        const glm::dvec3 L(wi);
        if (L.z <= 0.0) return 0.0;
        const glm::dvec3 H = glm::normalize(V + L);
        const double e = (H.x * H.x + H.y * H.y) / (a * a) + H.z * H.z;
        const double spec =
            1.0 / (kPiD * a * a * e * e) / (1.0 + lambda(V) + lambda(L)) / (4.0 * V.z * L.z);
        const double w5 = std::pow(1.0 - glm::dot(V, H), 5.0);
        double f;
        if (old_weighting) {
          const double F0 = 0.04 * (1.0 - metallic) + base[ch] * metallic;
          const double F = F0 + (1.0 - F0) * w5;
          f = (1.0 - F) * (1.0 - metallic) * base[ch] / kPiD + F * spec;
        } else {
          const double Fd = 0.04 + 0.96 * w5;
          const double dielectric = (1.0 - Fd) * base[ch] / kPiD + Fd * spec;
          const double metal = (base[ch] + (1.0 - base[ch]) * w5) * spec;
          f = (1.0 - metallic) * dielectric + metallic * metal;
        }
        return f * L.z;
      },
      1e-5);
}

TEST(NormativeMix, SpheresMatchAppendixBInAUniformEnvironment) {
  testing::context();
  Scene scene = builtin_scene("spheres");
  const Environment env = Environment::constant(glm::vec3(1.0f));
  BakeOptions bake;
  bake.face_size = 16;
  bake.min_face_size = 4;
  bake.samples = 64;
  bake.irradiance_size = 8;
  bake.lut_size = 64;
  const IblMaps maps = ibl_maps_from_bake(bake_environment(env, bake), env);
  constexpr int kSize = 448;
  const Camera camera = select_camera(scene, std::nullopt, 1.0f);
  RenderSettings settings;
  settings.msaa = 1;
  settings.brdf = {BrdfModel::kReference, false};
  const Image gl = render_headless(scene, camera, kSize, kSize, &env, &maps, settings);

  std::printf(
      "GL / Appendix B - 1 at each sphere's centre (n.v > 0.97), uniform white light;\n"
      "in brackets LearnOpenGL's weighting / Appendix B - 1. Rows metallic 1 (top) .. 0.\n");
  double worst = 0.0, worst_old = 0.0;
  for (int row = 6; row >= 0; --row) {
    double row_sum = 0.0;
    for (int col = 0; col < 7; ++col) {
      const Material& m = scene.materials[std::size_t(row * 7 + col)];
      const glm::vec3 centre(float(col - 3), float(row - 3), 0.0f);
      double sum = 0.0, mu_sum = 0.0;
      int n = 0;
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          const auto mu = testing::sphere_hit_cosine(testing::pixel_ray(camera, x, y, kSize, kSize),
                                                     centre, 0.4f);
          if (!mu || *mu < 0.97f) continue;
          sum += gl.rgb(x, y).g;
          mu_sum += *mu;
          ++n;
        }
      ASSERT_GT(n, 10);
      const double mu = mu_sum / n;
      const glm::dvec3 base(glm::vec3(m.base_color_factor));
      const double expected =
          appendix_b_albedo(base, m.metallic_factor, m.roughness_factor, mu, 1, false);
      const double old =
          appendix_b_albedo(base, m.metallic_factor, m.roughness_factor, mu, 1, true);
      const double err = sum / n / expected - 1.0;
      const double old_err = old / expected - 1.0;
      std::printf(" %+6.3f (%+6.3f)", err, old_err);
      row_sum += err;
      worst = std::max(worst, std::abs(err));
      worst_old = std::max(worst_old, std::abs(old_err));
    }
    std::printf("  row mean %+6.3f\n", row_sum / 7.0);
  }
  std::printf("largest |GL / Appendix B - 1| %.4f; LearnOpenGL's weighting up to %.4f\n", worst,
              worst_old);
  // Measured 2-core llvmpipe: largest 0.0016 (docs/SPLIT_SUM_ERRORS.md). At n.v ~ 1 the split
  // sum's own approximations (the diffuse weight at n.v instead of per v.h, the LUT's
  // bilinear lookup) are below 0.2%; the structure's 8-23% is gone.
  EXPECT_LT(worst, 0.01);
  // Sensitivity: the old weighting differs from Appendix B by far more than the bound.
  EXPECT_GT(worst_old, 0.12);
}

}  // namespace
}  // namespace pbrkit::gl
