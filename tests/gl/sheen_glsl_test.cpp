// sheen.glsl's sheen_lobe_direction and sheen_E evaluated on the GPU (llvmpipe in CI) must
// match the C++ pbrkit::sheen_lobe_direction and SheenTable::E, over normal incidence,
// grazing views, roughness below and above the clamp, and random frames: the OpenGL
// renderer's sheen IBL looks up where the C++ table says the lobe gathers light.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "pbrkit/core/sheen.h"
#include "pbrkit/gl/sheen_eval.h"

namespace pbrkit::gl {
namespace {

// A unit vector at angle acos(mu) from n, towards `towards` (not parallel to n).
glm::vec3 at_angle(glm::vec3 n, glm::vec3 towards, float mu) {
  const glm::vec3 t = glm::normalize(towards - n * glm::dot(n, towards));
  return glm::normalize(mu * n + std::sqrt(std::max(1.0f - mu * mu, 0.0f)) * t);
}

std::vector<SheenLobeCase> test_cases() {
  std::vector<SheenLobeCase> cases;
  const glm::vec3 z(0.0f, 0.0f, 1.0f), x(1.0f, 0.0f, 0.0f);
  const float mus[] = {1.0f, 0.99999f, 0.999f, 0.9f, 0.7f, 0.5f, 0.3f, 0.1f, 0.02f, 0.001f};
  const float roughnesses[] = {0.0f, 0.07f, 0.1f, 0.3f, 0.5f, 0.6f, 0.8f, 1.0f, 1.3f};
  for (float mu : mus)
    for (float r : roughnesses) cases.push_back({z, at_angle(z, x, mu), r});
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto random_unit = [&] {
    const float cz = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
    const float s = std::sqrt(1.0f - cz * cz);
    return glm::vec3(s * std::cos(phi), s * std::sin(phi), cz);
  };
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 n = random_unit();
    glm::vec3 towards = random_unit();
    if (std::abs(glm::dot(n, towards)) > 0.99f) towards = glm::vec3(n.y, n.z, -n.x);
    cases.push_back({n, at_angle(n, towards, u(rng)), u(rng)});
  }
  return cases;
}

TEST(SheenGlsl, LobeDirectionAndAlbedoMatchCpp) {
  testing::context();
  const std::vector<SheenLobeCase> cases = test_cases();
  const std::vector<glm::vec4> gpu = sheen_lobe_glsl(cases);
  ASSERT_EQ(gpu.size(), cases.size());
  double worst_direction = 0.0, worst_e = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const SheenLobeCase& c = cases[i];
    const glm::vec3 want = sheen_lobe_direction(c.n, c.v, c.roughness);
    const float want_e = SheenTable::get().E(glm::dot(c.n, c.v), c.roughness);
    // Both interpolate the same float nodes; what differs is float rounding of cos, sin and
    // the normalisations (a few ulp of 1).
    const double d = glm::length(glm::vec3(gpu[i]) - want);
    const double e = std::abs(double(gpu[i].w) - double(want_e));
    worst_direction = std::max(worst_direction, d);
    worst_e = std::max(worst_e, e);
    ASSERT_LT(d, 1e-5) << "case " << i << ": n.v " << glm::dot(c.n, c.v) << ", roughness "
                       << c.roughness;
    ASSERT_LT(e, 1e-6 + 1e-5 * double(want_e)) << "case " << i;
  }
  std::printf("largest |d_glsl - d_cpp| %.2g, |E_glsl - E_cpp| %.2g\n", worst_direction, worst_e);
}

// The harness must see the table: at a grazing view the direction leans well towards v
// (a lookup along n, or along the mirror direction, would fail), and at normal incidence it
// is n.
TEST(SheenGlsl, HarnessSeesTheLobeAngle) {
  testing::context();
  const glm::vec3 n(0.0f, 0.0f, 1.0f), v(std::sqrt(1.0f - 0.01f), 0.0f, 0.1f);
  const std::vector<glm::vec4> gpu = sheen_lobe_glsl({{n, v, 0.3f}, {n, n, 0.3f}});
  ASSERT_EQ(gpu.size(), 2u);
  EXPECT_GT(gpu[0].x, std::sin(0.3f));  // > 17 degrees towards v
  EXPECT_GT(gpu[0].z, 0.5f);
  EXPECT_NEAR(gpu[1].z, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace pbrkit::gl
