// Pins the project's orientation convention end to end: Environment::eval (core/equirect.h)
// + the cube resampling + the GL cube face convention. The path tracer and the GL renderer
// use the same Environment, so this pins the whole project.
#include <gtest/gtest.h>

#include <cmath>

#include "pbrkit/core/equirect.h"
#include "pbrkit/core/math.h"
#include "pbrkit/ibl/cubemap.h"
#include "pbrkit/ibl/environment_cube.h"

namespace pbrkit {
namespace {

// A map whose texels store their own (u, v), written without equirect.h, so the expected
// values below come from the documented convention, not from the code under test.
Environment uv_environment(float rotation_deg = 0.0f) {
  Environment env;
  env.map = Image(512, 256, 3);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 512; ++x) env.map.set_rgb(x, y, {(x + 0.5f) / 512, (y + 0.5f) / 256, 1});
  env.rotation_deg = rotation_deg;
  return env;
}

// A map whose texels store their own direction (built through equirect.h's inverse).
Environment direction_environment(float rotation_deg = 0.0f) {
  Environment env;
  env.map = Image(512, 256, 3);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 512; ++x)
      env.map.set_rgb(x, y, equirect_direction({(x + 0.5f) / 512, (y + 0.5f) / 256}));
  env.rotation_deg = rotation_deg;
  return env;
}

void expect_near(glm::vec3 a, glm::vec3 b, float tol, const char* what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

TEST(Orientation, DocumentedConventionAtTheCubeFaces) {
  // 17 px faces: the face centre is the centre of texel (8, 8).
  const Cubemap cube = resample_to_cube(uv_environment(), 17);
  auto centre = [&](int face) { return cube.mips[0][face].rgb(8, 8); };
  // The image centre (u, v) = (0.5, 0.5) faces -Z; u = 0.75 faces +X, u = 0.25 faces -X.
  expect_near(centre(5), {0.5f, 0.5f, 1}, 2e-3f, "-Z");
  expect_near(centre(0), {0.75f, 0.5f, 1}, 2e-3f, "+X");
  expect_near(centre(1), {0.25f, 0.5f, 1}, 2e-3f, "-X");
  // Row 0 is the zenith: +Y sees v ~ 0, -Y sees v ~ 1.
  EXPECT_LT(centre(2).y, 0.02f);
  EXPECT_GT(centre(3).y, 0.98f);
  // +Z is the seam (u = 0 = 1). Turning from +Z towards +X lowers u from 1 towards 0.75:
  // d = (0.2, 0, 1) has u = 0.5 + atan2(0.2, -1) / (2 pi) = 1 - atan(0.2) / (2 pi).
  const glm::vec3 near_seam = sample_cubemap(cube, glm::vec3(0.2f, 0.0f, 1.0f));
  EXPECT_NEAR(near_seam.x, 1.0f - std::atan(0.2f) / (2.0f * kPi), 3e-3f);
}

TEST(Orientation, EveryCubeTexelSeesItsOwnDirection) {
  const Cubemap cube = resample_to_cube(direction_environment(), 16);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        const glm::vec3 d = cube_direction(f, {(x + 0.5f) / 16, (y + 0.5f) / 16});
        const glm::vec3 c = cube.mips[0][f].rgb(x, y);
        // The texel average of a unit vector field is a little shorter than 1.
        ASSERT_GT(glm::dot(glm::normalize(c), d), 0.999f) << f << " " << x << " " << y;
      }
}

TEST(Orientation, RotationOf90DegreesMovesMinusZToMinusX) {
  const Cubemap cube = resample_to_cube(direction_environment(90.0f), 17);
  auto centre = [&](int face) { return cube.mips[0][face].rgb(8, 8); };
  // Counter-clockwise seen from above: -Z -> -X, -X -> +Z, +Z -> +X, +X -> -Z.
  expect_near(centre(1), {0, 0, -1}, 2e-3f, "-X shows what was at -Z");
  expect_near(centre(4), {-1, 0, 0}, 2e-3f, "+Z shows what was at -X");
  expect_near(centre(0), {0, 0, 1}, 2e-3f, "+X shows what was at +Z");
  expect_near(centre(5), {1, 0, 0}, 2e-3f, "-Z shows what was at +X");
  expect_near(centre(2), {0, 1, 0}, 2e-3f, "+Y stays");
}

}  // namespace
}  // namespace pbrkit
