// The shader unit test of the base layer: brdf.glsl evaluated on the GPU (llvmpipe in CI) for
// many random inputs must match the C++ Brdf::eval to 1e-4 relative, for both G models,
// with and without multiple-scattering compensation. This is how we know the OpenGL
// renderer and the path tracer render one material model.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "brdf_conditioning.h"
#include "gl/harness/brdf_eval.h"
#include "gl_test_context.h"
#include "pbrkit/core/brdf.h"

namespace pbrkit::gl {
namespace {

glm::vec3 random_upper_direction(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  // Uniform on the hemisphere with z >= 0.02 (below that 1/(n.l n.v) makes every
  // implementation's rounding explode alike; the renderer clamps there anyway).
  const float z = 0.02f + 0.98f * u(rng);
  const float phi = 2.0f * 3.14159265f * u(rng);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

std::vector<BrdfCase> random_cases(unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<BrdfCase> cases;
  for (int i = 0; i < count; ++i) {
    BrdfCase c;
    c.wo = random_upper_direction(rng);
    c.wi = random_upper_direction(rng);
    c.base_color = glm::vec3(u(rng), u(rng), u(rng));
    // A third of the cases pure metals, a third pure dielectrics, the rest in between.
    const int kind = i % 3;
    c.metallic = kind == 0 ? 1.0f : kind == 1 ? 0.0f : u(rng);
    // Roughness over the whole range, including below the clamp and exactly 1.
    c.roughness = i % 17 == 0 ? 0.0f : i % 19 == 0 ? 1.0f : u(rng);
    cases.push_back(c);
  }
  return cases;
}

void expect_glsl_matches_cpp(const BrdfOptions& options, unsigned seed) {
  testing::context();
  const std::vector<BrdfCase> cases = random_cases(seed, 4000);
  const std::vector<glm::vec3> gpu = eval_brdf_glsl(cases, options);
  ASSERT_EQ(gpu.size(), cases.size());
  double worst = 0.0, worst_plain = 0.0;
  std::size_t worst_index = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const BrdfCase& c = cases[i];
    const Brdf brdf(c.layer(), options);
    const glm::vec3 cpu = brdf.eval(c.wo, c.wi);
    ASSERT_TRUE(std::isfinite(gpu[i].r) && std::isfinite(gpu[i].g) && std::isfinite(gpu[i].b))
        << "case " << i;
    const double scale = std::max({std::abs(cpu.r), std::abs(cpu.g), std::abs(cpu.b), 1e-12f});
    double d = 0.0;
    for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(double(gpu[i][k]) - cpu[k]));
    // In units of the allowed error: <= 1 passes.
    const double ratio = d / (1e-4 * scale + testing::conditioning_bound(c, options));
    worst_plain = std::max(worst_plain, d / scale);
    if (ratio > worst) {
      worst = ratio;
      worst_index = i;
    }
  }
  const BrdfCase& w = cases[worst_index];
  EXPECT_LE(worst, 1.0) << "worst case " << worst_index << ": roughness " << w.roughness
                        << ", metallic " << w.metallic << ", wo.z " << w.wo.z << ", wi.z " << w.wi.z
                        << ", gpu " << gpu[worst_index].r << ", cpu "
                        << Brdf(w.layer(), options).eval(w.wo, w.wi).r;
  if (!options.multiscatter) {
    EXPECT_LT(worst_plain, 1e-4);
  }
  std::printf("largest relative difference %.3g (%.3g of the allowed error)\n", worst_plain, worst);
}

TEST(BrdfGlsl, ReferenceMatchesCpp) {
  expect_glsl_matches_cpp({BrdfModel::kReference, false}, 1);
}
TEST(BrdfGlsl, ClassicMatchesCpp) {
  expect_glsl_matches_cpp({BrdfModel::kClassic, false}, 2);
}
TEST(BrdfGlsl, ReferenceMultiscatterMatchesCpp) {
  expect_glsl_matches_cpp({BrdfModel::kReference, true}, 3);
}
TEST(BrdfGlsl, ClassicMultiscatterMatchesCpp) {
  expect_glsl_matches_cpp({BrdfModel::kClassic, true}, 4);
}

TEST(BrdfGlsl, ZeroBelowTheHorizon) {
  testing::context();
  std::vector<BrdfCase> cases(2);
  cases[0].wi = glm::normalize(glm::vec3(1.0f, 0.0f, -0.3f));
  cases[1].wo = glm::normalize(glm::vec3(0.0f, 1.0f, -0.1f));
  for (const glm::vec3& v : eval_brdf_glsl(cases, {})) EXPECT_EQ(v, glm::vec3(0.0f));
}

TEST(BrdfGlsl, SphericalGaussianFresnelIsCloseToSchlick) {
  // The SG variant is an approximation of Schlick's (Karis 2013): within a few percent
  // on a smooth metal at normal incidence and at 60 degrees, and not identical.
  testing::context();
  std::vector<BrdfCase> cases(2);
  cases[0].metallic = cases[1].metallic = 1.0f;
  cases[0].base_color = cases[1].base_color = glm::vec3(0.5f);
  cases[1].wo = cases[1].wi = glm::vec3(std::sin(1.047f), 0.0f, std::cos(1.047f));
  cases[1].wi.x = -cases[1].wi.x;
  const auto schlick = eval_brdf_glsl(cases, {});
  const auto sg = eval_brdf_glsl(cases, {}, FresnelMode::kSphericalGaussian);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(sg[i].r / schlick[i].r, 1.0, 0.03) << i;
  }
  EXPECT_NE(sg[1].r, schlick[1].r);
}

}  // namespace
}  // namespace pbrkit::gl
