// The procedural meshes of the transmission scenes: make_prism and make_lathe close their
// volume (mesh_closure.h), wind every triangle outwards (its face normal agrees with the
// vertex normals), and enclose the volume of the polygonal solid they approximate
// (divergence theorem: V = sum over triangles of dot(a, cross(b, c)) / 6, which is
// negative when the faces point inwards); make_checker_texture alternates its squares.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "pbrkit/core/math.h"
#include "pbrkit/scene/mesh_closure.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit {
namespace {

double enclosed_volume(const Mesh& m) {
  double v = 0.0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::dvec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                     c = m.positions[m.indices[t + 2]];
    v += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return v;
}

// Every triangle's winding normal points the way its vertices' normals do.
void expect_outward_winding(const Mesh& m) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                    c = m.positions[m.indices[t + 2]];
    const glm::vec3 face = glm::normalize(glm::cross(b - a, c - a));
    for (int k = 0; k < 3; ++k)
      ASSERT_GT(glm::dot(face, m.normals[m.indices[t + std::size_t(k)]]), 0.0f)
          << "triangle " << t / 3;
  }
}

TEST(Primitives, PrismIsClosedOutwardAndHasItsVolume) {
  // A right triangle (legs 1 and 2) in either winding, extruded by 3: volume 1 * 2 / 2 * 3.
  for (const auto& outline : {std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 2}},
                              std::vector<glm::vec2>{{0, 0}, {0, 2}, {1, 0}}}) {
    const Mesh prism = make_prism(outline, 3.0f);
    EXPECT_TRUE(count_edges(prism).closed());
    EXPECT_EQ(prism.triangle_count(), 3u * 2u + 2u);
    expect_outward_winding(prism);
    EXPECT_NEAR(enclosed_volume(prism), 3.0, 1e-6);
  }
}

TEST(Primitives, LatheIsClosedOutwardAndHasItsVolume) {
  // A cylinder (radius 0.5, height 2) turned 48 times: a 48-gon prism, of area
  // N/2 sin(2 pi / N) r^2.
  constexpr int kN = 48;
  const double polygon = 0.5 * kN * std::sin(2.0 * kPi / kN) * 0.25;
  const Mesh cylinder = make_lathe({{0, 0}, {0.5f, 0}, {0.5f, 2}, {0, 2}}, kN);
  EXPECT_TRUE(count_edges(cylinder).closed());
  expect_outward_winding(cylinder);
  EXPECT_NEAR(enclosed_volume(cylinder), polygon * 2.0, 1e-5);
  // A tumbler: the cylinder less its cavity (radius 0.4 from y = 0.2 up, open at the top).
  const Mesh tumbler =
      make_lathe({{0, 0}, {0.5f, 0}, {0.5f, 2}, {0.4f, 2}, {0.4f, 0.2f}, {0, 0.2f}}, kN);
  EXPECT_TRUE(count_edges(tumbler).closed());
  expect_outward_winding(tumbler);
  EXPECT_NEAR(enclosed_volume(tumbler), polygon * 2.0 - polygon * 0.64 * 1.8, 1e-5);
  // Reversed, the profile turns the faces inwards: the volume is negative.
  EXPECT_NEAR(enclosed_volume(make_lathe({{0, 2}, {0.5f, 2}, {0.5f, 0}, {0, 0}}, kN)),
              -polygon * 2.0, 1e-5);
  // A profile that does not end on the axis leaves a hole: open.
  const EdgeCount open = count_edges(make_lathe({{0, 0}, {0.5f, 0}, {0.5f, 2}}, kN));
  EXPECT_EQ(open.unpaired, std::size_t(kN));
}

TEST(Primitives, CheckerAlternatesItsSquares) {
  const Texture t = make_checker_texture(64, 4, glm::vec3(0.8f), glm::vec3(0.05f));
  EXPECT_TRUE(t.srgb);
  EXPECT_EQ(t.width(), 64);
  EXPECT_EQ(t.levels.size(), 7u);  // 64 .. 1
  for (int y = 0; y < 64; y += 8)
    for (int x = 0; x < 64; x += 8) {
      const bool first = (x / 16 + y / 16) % 2 == 0;
      EXPECT_EQ(t.texel(0, x, y).r, first ? 0.8f : 0.05f) << x << "," << y;
    }
  // The smallest mip is the mean of the two colours.
  EXPECT_NEAR(t.texel(6, 0, 0).g, 0.425f, 1e-5f);
}

}  // namespace
}  // namespace pbrkit
