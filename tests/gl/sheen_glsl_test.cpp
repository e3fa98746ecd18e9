// sheen.glsl's sheen_sh_radiance and sheen_E evaluated on the GPU (llvmpipe in CI) must
// match the C++ pbrkit::sheen_sh_radiance and SheenTable::E, over normal incidence, grazing
// views, roughness below and above the clamp, random frames and random SH: the OpenGL
// renderer's sheen IBL averages the environment over the lobe the C++ table describes.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gl/harness/sheen_eval.h"
#include "gl_test_context.h"
#include "pbrkit/core/sheen.h"
#include "pbrkit/ibl/sheen_sh.h"

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

TEST(SheenGlsl, ShRadianceAndAlbedoMatchCpp) {
  testing::context();
  const std::vector<SheenLobeCase> cases = test_cases();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  SH9 sh;
  double scale = 0.0;  // the largest possible |result| is below sum |sh_lm| |Y_lm|max / A_l
  for (glm::vec3& c : sh) {
    c = glm::vec3(u(rng), u(rng), u(rng));
    scale += double(glm::length(c));
  }
  const std::vector<glm::vec4> gpu = sheen_sh_glsl(cases, sh);
  ASSERT_EQ(gpu.size(), cases.size());
  double worst_radiance = 0.0, worst_e = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const SheenLobeCase& c = cases[i];
    const glm::vec3 want = sheen_sh_radiance(sh, c.n, c.v, c.roughness);
    const float want_e = SheenTable::get().E(glm::dot(c.n, c.v), c.roughness);
    // Both interpolate the same float nodes; what differs is float rounding of the frame,
    // the outer products and the sums (a few ulp of the coefficients' size).
    const double d = glm::length(glm::vec3(gpu[i]) - want);
    const double e = std::abs(double(gpu[i].w) - double(want_e));
    worst_radiance = std::max(worst_radiance, d);
    worst_e = std::max(worst_e, e);
    ASSERT_LT(d, 1e-5 * scale) << "case " << i << ": n.v " << glm::dot(c.n, c.v) << ", roughness "
                               << c.roughness;
    ASSERT_LT(e, 1e-6 + 1e-5 * double(want_e)) << "case " << i;
  }
  std::printf("largest |L_glsl - L_cpp| %.2g (SH scale %.2g), |E_glsl - E_cpp| %.2g\n",
              worst_radiance, scale, worst_e);
}

// The harness must see the table: an environment brighter towards +x (SH band 1 only),
// viewed from a grazing +x direction, gives the back-scattering lobe more light than it
// gives at normal incidence (a lookup about the mirror direction, -x, would give less).
TEST(SheenGlsl, HarnessSeesTheLobesDirection) {
  testing::context();
  SH9 sh{};
  sh[0] = glm::vec3(1.0f);
  sh[3] = glm::vec3(0.5f);  // + x
  const glm::vec3 n(0.0f, 0.0f, 1.0f), v(std::sqrt(1.0f - 0.01f), 0.0f, 0.1f);
  const std::vector<glm::vec4> gpu = sheen_sh_glsl({{n, v, 0.3f}, {n, n, 0.3f}}, sh);
  ASSERT_EQ(gpu.size(), 2u);
  EXPECT_GT(gpu[0].x, gpu[1].x * 1.1f);
  // At normal incidence the lobe is symmetric about n: band 1 along x contributes nothing.
  EXPECT_NEAR(gpu[1].x, sh[0].x * 0.282095f / 3.14159265f, 1e-4f);
}

}  // namespace
}  // namespace pbrkit::gl
