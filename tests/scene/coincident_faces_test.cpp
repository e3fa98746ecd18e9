// Transmissive faces lying on another object's: found where a glass's face shares a plane
// and an area with another face, whatever the plane's orientation, and not where the
// objects only touch along an edge, are apart, or are opaque.
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/coincident_faces.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

int add_material(Scene& s, bool glass) {
  Material m;
  m.name = glass ? "glass" : "opaque";
  if (glass) {
    m.transmission.emplace().factor = 1.0f;
    m.volume.emplace().thickness_factor = 0.5f;
  }
  s.materials.push_back(m);
  return int(s.materials.size()) - 1;
}

// A 4 x 4 floor (y = 0, facing up) under a 0.5 box whose base is at `base`, both moved by
// `frame` (a tilted frame tests a plane that is not axis-aligned).
Scene box_on_floor(float base, bool glass, const glm::mat4& frame = glm::mat4(1.0f)) {
  Scene s;
  s.source = "test";
  const int floor = add_material(s, false);
  const int box = add_material(s, glass);
  Mesh quad = make_quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4});
  quad.name = "floor";
  add_mesh_instance(s, std::move(quad), floor, frame);
  Mesh cube = make_box({-0.25f, base, -0.25f}, {0.25f, base + 0.5f, 0.25f});
  cube.name = "box";
  add_mesh_instance(s, std::move(cube), box, frame);
  return s;
}

TEST(CoincidentFaces, AGlassStandingInTheFloorsPlaneIsFound) {
  const CoincidentFacesResult r = find_coincident_faces(box_on_floor(0.0f, true));
  EXPECT_FALSE(r.incomplete);
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_EQ(r.pairs[0].transmissive, 1u);
  EXPECT_EQ(r.pairs[0].other, 0u);
  EXPECT_EQ(r.pairs[0].triangles, 2u);  // the base's two triangles
}

TEST(CoincidentFaces, FoundOnATiltedPlaneFarFromTheOrigin) {
  const glm::mat4 frame = glm::rotate(glm::translate(glm::mat4(1.0f), {100.0f, -40.0f, 250.0f}),
                                      0.7f, glm::normalize(glm::vec3(1.0f, 0.3f, -0.5f)));
  const CoincidentFacesResult r = find_coincident_faces(box_on_floor(0.0f, true, frame));
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_EQ(r.pairs[0].triangles, 2u);
}

TEST(CoincidentFaces, ApartSunkOrOpaqueIsNotFound) {
  EXPECT_TRUE(find_coincident_faces(box_on_floor(0.001f, true)).pairs.empty());   // above
  EXPECT_TRUE(find_coincident_faces(box_on_floor(-0.001f, true)).pairs.empty());  // sunk
  EXPECT_TRUE(find_coincident_faces(box_on_floor(1e-4f, true)).pairs.empty());
  EXPECT_TRUE(find_coincident_faces(box_on_floor(0.0f, false)).pairs.empty());  // opaque
}

TEST(CoincidentFaces, TouchingAlongAnEdgeIsNotFound) {
  // A vertical glass sheet standing on the floor, and a glass box beside a second one,
  // face to face but offset so that only an edge is shared.
  Scene s = box_on_floor(0.001f, true);
  const int glass = add_material(s, true);
  add_mesh_instance(s, make_quad({1, 0, 1}, {0.5f, 0, 0}, {0, 0.5f, 0}), glass);
  add_mesh_instance(s, make_box({0.25f, 0.001f, 0.25f}, {0.75f, 0.501f, 0.75f}), glass);
  EXPECT_TRUE(find_coincident_faces(s).pairs.empty());
}

TEST(CoincidentFaces, TwoGlassesFaceToFaceAreOnePair) {
  Scene s = box_on_floor(0.001f, true);
  const int glass = add_material(s, true);
  add_mesh_instance(s, make_box({0.25f, 0.101f, -0.2f}, {0.75f, 0.401f, 0.2f}), glass);
  const CoincidentFacesResult r = find_coincident_faces(s);
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_EQ(r.pairs[0].transmissive, 1u);
  EXPECT_EQ(r.pairs[0].other, 2u);
  // The first box's +x face (two triangles) overlaps the second's -x face.
  EXPECT_EQ(r.pairs[0].triangles, 2u);
}

// A field of 10,000 glass tiles over one floor, each 1 mm above it but the last, which lies
// in its plane: found, and the search completes within its default bound, which comparing
// every tile with every instance (10^8 comparisons) would pass long before the last tile.
TEST(CoincidentFaces, AFieldOfGlassesIsSearchedWhole) {
  Scene s;
  s.source = "test";
  const int floor = add_material(s, false);
  const int glass = add_material(s, true);
  Mesh quad = make_quad({-60, 0, 60}, {120, 0, 0}, {0, 0, -120});
  quad.name = "floor";
  add_mesh_instance(s, std::move(quad), floor);
  Mesh tile = make_quad({-0.25f, 0, 0.25f}, {0.5f, 0, 0}, {0, 0, -0.5f});
  tile.name = "tile";
  constexpr int kSide = 100;
  for (int i = 0; i < kSide * kSide; ++i) {
    const bool last = i + 1 == kSide * kSide;
    const glm::vec3 at(float(i % kSide - kSide / 2), last ? 0.0f : 0.001f,
                       float(i / kSide - kSide / 2));
    add_mesh_instance(s, tile, glass, glm::translate(glm::mat4(1.0f), at));
  }
  const CoincidentFacesResult r = find_coincident_faces(s);
  EXPECT_FALSE(r.incomplete);
  EXPECT_EQ(r.checked, std::size_t(kSide * kSide));
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_EQ(r.pairs[0].transmissive, std::size_t(kSide * kSide));
  EXPECT_EQ(r.pairs[0].other, 0u);
  EXPECT_EQ(r.pairs[0].triangles, 2u);
}

TEST(CoincidentFaces, StopsAtItsWorkBound) {
  const CoincidentFacesResult r = find_coincident_faces(box_on_floor(0.0f, true), 5);
  EXPECT_TRUE(r.incomplete);
  EXPECT_EQ(r.transmissive, 1u);
  EXPECT_EQ(r.checked, 0u);
}

TEST(CoincidentFaces, LoadingAFileWarnsNamingBothNodes) {
  const auto path = test::scratch_dir() / "coincident_faces.glb";
  write_glb(box_on_floor(0.0f, true), path);
  const Scene s = load_scene(path.string());
  ASSERT_EQ(s.warnings.size(), 1u);
  const std::string& w = s.warnings[0];
  EXPECT_EQ(w.rfind("nodes[1] ('box') lies on nodes[0] ('floor'): 2 of its transmissive "
                    "triangles share a plane and an area",
                    0),
            0u)
      << w;
  // The same scene lifted off the floor loads without it.
  write_glb(box_on_floor(0.001f, true), path);
  EXPECT_TRUE(load_scene(path.string()).warnings.empty());
}

}  // namespace
}  // namespace pbrkit
