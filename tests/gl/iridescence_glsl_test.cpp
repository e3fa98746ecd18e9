// iridescence.glsl evaluated on the GPU (llvmpipe in CI) must match the C++
// pbrkit::iridescence_fresnel to 1e-4 relative, over a grid that holds every limit (grazing
// and normal incidence, no film, 1200 nm, metal bases, F0 of 0 and 1) and random cases:
// the OpenGL renderer and the path tracer render one thin film.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gl/harness/iridescence_eval.h"
#include "gl_test_context.h"
#include "pbrkit/core/iridescence.h"

namespace pbrkit::gl {
namespace {

// The absolute floor for values near 0. The result is a sum of terms as large as the
// reflectance of the layers (up to 1) that cancel under destructive interference, and the
// cosines of the interference terms take arguments up to ~100 rad (an ulp of 7.6e-6) times
// amplitudes up to ~0.1: float rounding leaves absolute differences of up to ~1e-6 whatever
// the result's size (measured on llvmpipe: at most 5.2e-7). 1e-6 is 1/300 of the smallest
// 8-bit sRGB step (at black, 3e-4 linear).
constexpr double kFloor = 1e-6;

std::vector<IridescenceCase> test_cases() {
  std::vector<IridescenceCase> cases;
  const float cosines[] = {0.0f,  0.001f, 0.01f, 0.05f, 0.1f,  0.2f,
                           0.35f, 0.5f,   0.7f,  0.85f, 0.95f, 1.0f};
  const float film_iors[] = {1.0f, 1.2f, 1.3f, 1.5f, 1.8f, 2.0f, 2.5f};
  const float thicknesses[] = {0.0f,   0.01f,  1.0f,   50.0f,  100.0f,  200.0f, 300.0f,
                               400.0f, 550.0f, 700.0f, 850.0f, 1000.0f, 1200.0f};
  const glm::vec3 bases[] = {glm::vec3(0.0f),
                             glm::vec3(0.04f),
                             glm::vec3(0.02f, 0.05f, 0.1f),
                             glm::vec3(0.25f),
                             glm::vec3(1.0f, 0.782f, 0.344f),    // gold
                             glm::vec3(0.955f, 0.638f, 0.538f),  // copper
                             glm::vec3(0.972f, 0.960f, 0.915f),  // silver
                             glm::vec3(0.9999f),
                             glm::vec3(1.0f)};
  for (float c : cosines)
    for (float n : film_iors)
      for (float d : thicknesses)
        for (const glm::vec3& F0 : bases) cases.push_back({c, n, d, F0});
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 4000; ++i) {
    const glm::vec3 F0 = i % 2 == 0 ? glm::vec3(u(rng) * 0.1f) : glm::vec3(u(rng), u(rng), u(rng));
    cases.push_back({u(rng), 1.0f + 1.5f * u(rng), 1200.0f * u(rng), F0});
  }
  return cases;
}

TEST(IridescenceGlsl, MatchesCpp) {
  testing::context();
  const std::vector<IridescenceCase> cases = test_cases();
  const std::vector<glm::vec3> gpu = iridescence_fresnel_glsl(cases);
  ASSERT_EQ(gpu.size(), cases.size());
  double worst = 0.0, worst_relative = 0.0;
  std::size_t worst_index = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const IridescenceCase& c = cases[i];
    const glm::vec3 cpu = iridescence_fresnel(c.cos_theta, c.film_ior, c.thickness_nm, c.base_F0);
    ASSERT_TRUE(std::isfinite(gpu[i].r) && std::isfinite(gpu[i].g) && std::isfinite(gpu[i].b))
        << "case " << i;
    for (int k = 0; k < 3; ++k) {
      const double d = std::abs(double(gpu[i][k]) - cpu[k]);
      // 1e-4 relative, with an absolute floor of kFloor (see below) for values near 0.
      const double ratio = d / (1e-4 * std::abs(cpu[k]) + kFloor);
      worst_relative = std::max(worst_relative, d / std::max(std::abs(double(cpu[k])), 1e-12));
      if (ratio > worst) {
        worst = ratio;
        worst_index = i;
      }
    }
  }
  const IridescenceCase& w = cases[worst_index];
  const glm::vec3 w_cpu = iridescence_fresnel(w.cos_theta, w.film_ior, w.thickness_nm, w.base_F0);
  EXPECT_LE(worst, 1.0) << "worst case " << worst_index << ": cos " << w.cos_theta << ", film "
                        << w.film_ior << ", d " << w.thickness_nm << ", F0 (" << w.base_F0.r << " "
                        << w.base_F0.g << " " << w.base_F0.b << "), gpu (" << gpu[worst_index].r
                        << " " << gpu[worst_index].g << " " << gpu[worst_index].b << "), cpu ("
                        << w_cpu.r << " " << w_cpu.g << " " << w_cpu.b << ")";
  std::printf("%zu cases; worst %.3g of the allowed error; largest relative difference %.3g\n",
              cases.size(), worst, worst_relative);
}

}  // namespace
}  // namespace pbrkit::gl
