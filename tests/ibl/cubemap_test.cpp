// Cube addressing (OpenGL 4.5, table 8.19), texel solid angles and lookups.
#include "pbrkit/ibl/cubemap.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"

namespace pbrkit {
namespace {

void expect_near(glm::vec3 a, glm::vec3 b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Cubemap, FaceCentresAreTheAxesInGlOrder) {
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) expect_near(cube_direction(f, {0.5f, 0.5f}), axes[f], 1e-6f);
}

// Values worked out by hand from table 8.19: s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2.
TEST(Cubemap, MatchesTable819) {
  // +X: sc = -rz, tc = -ry. d = (1, 0.5, -0.25): sc = 0.25, tc = -0.5.
  CubeCoord c = cube_coord({1.0f, 0.5f, -0.25f});
  EXPECT_EQ(c.face, 0);
  EXPECT_NEAR(c.st.x, 0.625f, 1e-6f);
  EXPECT_NEAR(c.st.y, 0.25f, 1e-6f);
  // -X: sc = +rz, tc = -ry. d = (-2, 1, 1): sc = 0.5, tc = -0.5.
  c = cube_coord({-2.0f, 1.0f, 1.0f});
  EXPECT_EQ(c.face, 1);
  EXPECT_NEAR(c.st.x, 0.75f, 1e-6f);
  EXPECT_NEAR(c.st.y, 0.25f, 1e-6f);
  // +Y: sc = +rx, tc = +rz. d = (0.5, 1, 0.25): sc = 0.5, tc = 0.25.
  c = cube_coord({0.5f, 1.0f, 0.25f});
  EXPECT_EQ(c.face, 2);
  EXPECT_NEAR(c.st.x, 0.75f, 1e-6f);
  EXPECT_NEAR(c.st.y, 0.625f, 1e-6f);
  // -Y: sc = +rx, tc = -rz. d = (0.5, -1, 0.25): sc = 0.5, tc = -0.25.
  c = cube_coord({0.5f, -1.0f, 0.25f});
  EXPECT_EQ(c.face, 3);
  EXPECT_NEAR(c.st.x, 0.75f, 1e-6f);
  EXPECT_NEAR(c.st.y, 0.375f, 1e-6f);
  // +Z: sc = +rx, tc = -ry. d = (0.5, 0.25, 1): sc = 0.5, tc = -0.25.
  c = cube_coord({0.5f, 0.25f, 1.0f});
  EXPECT_EQ(c.face, 4);
  EXPECT_NEAR(c.st.x, 0.75f, 1e-6f);
  EXPECT_NEAR(c.st.y, 0.375f, 1e-6f);
  // -Z: sc = -rx, tc = -ry. d = (0.5, 0.25, -1): sc = -0.5, tc = -0.25.
  c = cube_coord({0.5f, 0.25f, -1.0f});
  EXPECT_EQ(c.face, 5);
  EXPECT_NEAR(c.st.x, 0.25f, 1e-6f);
  EXPECT_NEAR(c.st.y, 0.375f, 1e-6f);
}

TEST(Cubemap, CoordInvertsDirection) {
  Pcg32 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const int face = int(rng.next_float() * 6.0f);
    const glm::vec2 st = rng.next_2d();
    const glm::vec3 d = cube_direction(face, st);
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    const CubeCoord c = cube_coord(d * 3.0f);
    ASSERT_EQ(c.face, face) << st.x << " " << st.y;
    EXPECT_NEAR(c.st.x, st.x, 1e-5f);
    EXPECT_NEAR(c.st.y, st.y, 1e-5f);
  }
}

TEST(Cubemap, TexelSolidAnglesSumToTheSphere) {
  EXPECT_NEAR(cube_texel_solid_angle(0, 0, 1), 4.0 * kPi / 6.0, 1e-6);
  for (int size : {2, 7, 64}) {
    double sum = 0.0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) sum += cube_texel_solid_angle(x, y, size);
    EXPECT_NEAR(6.0 * sum, 4.0 * kPi, 1e-4) << size;
  }
  // A texel at the centre of a large face subtends ~ (2/size)^2 sr; a corner one ~1/sqrt(27)
  // of that (area element (1 + x^2 + y^2)^(-3/2) at x = y = 1).
  const float c = cube_texel_solid_angle(512, 512, 1024);
  EXPECT_NEAR(c, std::pow(2.0f / 1024.0f, 2.0f), 1e-9f);
  EXPECT_NEAR(cube_texel_solid_angle(0, 0, 1024) / c, 1.0f / std::sqrt(27.0f), 1e-3f);
}

TEST(Cubemap, SampleIsBilinearWithinAFaceAndLinearAcrossLevels) {
  Cubemap cube;
  for (int level = 0; level < 2; ++level) {
    std::array<Image, 6> faces;
    const int size = 4 >> level;
    for (int f = 0; f < 6; ++f) {
      faces[f] = Image(size, size, 4, 1.0f);
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
          faces[f].set_rgb(x, y, glm::vec3(float(f), float(x) + 10.0f * level, float(y)));
    }
    cube.mips.push_back(faces);
  }
  // Texel centre (1, 2) of -Y at level 0.
  const glm::vec3 d = cube_direction(3, {1.5f / 4.0f, 2.5f / 4.0f});
  expect_near(sample_cubemap(cube, d), {3.0f, 1.0f, 2.0f}, 1e-5f);
  // Halfway between texels 1 and 2 in x.
  const glm::vec3 d2 = cube_direction(3, {2.0f / 4.0f, 2.5f / 4.0f});
  expect_near(sample_cubemap(cube, d2), {3.0f, 1.5f, 2.0f}, 1e-5f);
  // Level 1 (2 px) at the same point: x = 0.5, y = 0.625 * 2 - 0.5 = 0.75 in texel units.
  expect_near(sample_cubemap(cube, d2, 1.0f), {3.0f, 10.5f, 0.75f}, 1e-5f);
  const glm::vec3 a = sample_cubemap(cube, d2, 0.0f), b = sample_cubemap(cube, d2, 1.0f);
  expect_near(sample_cubemap(cube, d2, 0.25f), a + 0.25f * (b - a), 1e-5f);
  // Clamped at the edge of the face: beyond the last texel centre the value stays.
  expect_near(sample_cubemap(cube, cube_direction(3, {0.99f, 2.5f / 4.0f})), {3.0f, 3.0f, 2.0f},
              1e-5f);
}

}  // namespace
}  // namespace pbrkit
