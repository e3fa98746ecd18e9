// Whether a surface closes a volume (mesh_closure.h), on surfaces whose closure is known by
// construction: a UV sphere written as three.js's SphereGeometry writes it (the seam and the
// south pole computed, not copied, so they miss the first column by rounding), a surface
// split across primitives, and open sheets; and the loader's decision for a glTF mesh whose
// shell is split across primitives.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/mesh_closure.h"
#include "pbrkit/scene/primitives.h"
#include "scene/gltf_builder.h"
#include "scene/threejs_sphere.h"

namespace pbrkit {
namespace {

TEST(MeshClosure, UvSphereWithARoundedSeamIsClosed) {
  for (const double r : {1.0, 0.01, 250.0}) {
    SCOPED_TRACE(r);
    const Mesh sphere = test::threejs_sphere(r, 32, 16);
    // The seam really is off: bit-exact welding would leave it open.
    ASSERT_NE(sphere.positions[1 * 33], sphere.positions[1 * 33 + 32]);  // ring 1, phi 0 and 2 pi
    const EdgeCount e = count_edges(sphere);
    EXPECT_EQ(e.unpaired, 0u);
    EXPECT_EQ(e.triangles, std::size_t(32 * 16 * 2 - 2 * 32));
    EXPECT_TRUE(e.closed());
  }
}

TEST(MeshClosure, PositionsFartherThanTheToleranceDoNotWeld) {
  // A tetrahedron of split vertices, one copy moved by 10x the tolerance of its size
  // (diagonal sqrt(3)): the three edges at that copy lose their partner.
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<std::uint32_t> faces = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  Mesh m;
  for (const std::uint32_t i : faces) {
    m.indices.push_back(std::uint32_t(m.positions.size()));
    m.positions.push_back(p[i]);
  }
  EXPECT_TRUE(count_edges(m).closed());
  const float step = float(10.0 * kWeldTolerance * std::sqrt(3.0));
  Mesh moved = m;
  moved.positions[9] += glm::vec3(step, 0.0f, 0.0f);  // face 3's copy of vertex 1
  EXPECT_EQ(count_edges(moved).unpaired, 4u);         // 2 edges of face 3, and their 2 partners
  // Within the tolerance (a tenth of it), the copy welds.
  Mesh near = m;
  near.positions[9] += glm::vec3(step / 100.0f, 0.0f, 0.0f);
  EXPECT_TRUE(count_edges(near).closed());
}

TEST(MeshClosure, ToleranceIsRelativeToTheSurfacesSize) {
  // A box and a sheet at 1e-4 and 1e3 scale, and far from the origin: closure does not
  // change.
  const std::pair<float, glm::vec3> cases[] = {
      {1e-4f, glm::vec3(0.0f)}, {1e3f, glm::vec3(0.0f)}, {1.0f, glm::vec3(1e4f, -3e3f, 7e3f)}};
  for (const auto& [scale, offset] : cases) {
    Mesh m = make_box(offset, offset + glm::vec3(scale, 2.0f * scale, 0.5f * scale));
    EXPECT_TRUE(count_edges(m).closed()) << scale;
    Mesh sheet = make_quad(offset, glm::vec3(scale, 0, 0), glm::vec3(0, scale, 0));
    EXPECT_EQ(count_edges(sheet).unpaired, 4u) << scale;
  }
}

TEST(MeshClosure, ShellSplitAcrossPrimitivesIsClosedTogether) {
  // A box cut into its +Z half's faces and the rest: each part is open, both together close.
  const Mesh box = make_box(glm::vec3(-0.3f, 0.0f, -0.2f), glm::vec3(0.3f, 1.2f, 0.2f));
  Mesh front = box, back = box;
  front.indices.assign(box.indices.begin(), box.indices.begin() + 6);  // the +Z face
  back.indices.assign(box.indices.begin() + 6, box.indices.end());
  EXPECT_FALSE(count_edges(front).closed());
  EXPECT_FALSE(count_edges(back).closed());
  const Mesh* both[] = {&front, &back};
  const EdgeCount e = count_edges(std::span<const Mesh* const>(both));
  EXPECT_EQ(e.triangles, 12u);
  EXPECT_TRUE(e.closed());
  // A truly open sheet stays open, alone or beside a closed box.
  const Mesh sheet = make_quad(glm::vec3(2, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0));
  const Mesh* with_sheet[] = {&box, &sheet};
  EXPECT_EQ(count_edges(std::span<const Mesh* const>(with_sheet)).unpaired, 4u);
}

// A glTF file of one mesh with a volume material (thicknessFactor 1): its primitives are
// `parts`, all with that material.
std::filesystem::path volume_file(const char* name, const std::vector<Mesh>& parts) {
  test::GltfBuilder b;
  b.gltf["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume"};
  b.gltf["materials"] = {
      {{"extensions",
        {{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
         {"KHR_materials_volume", {{"thicknessFactor", 1}, {"attenuationDistance", 0.5}}}}}}};
  std::vector<nlohmann::json> primitives;
  for (const Mesh& p : parts) primitives.push_back(b.primitive(p.positions, p.indices, 0));
  b.node({{"mesh", b.mesh(primitives)}});
  return b.write(name);
}

TEST(MeshClosure, LoaderClosesAShellSplitAcrossAMeshsPrimitives) {
  const Mesh box = make_box(glm::vec3(-0.3f, 0.0f, -0.2f), glm::vec3(0.3f, 1.2f, 0.2f));
  Mesh front = box, back = box;
  front.indices.assign(box.indices.begin(), box.indices.begin() + 6);
  back.indices.assign(box.indices.begin() + 6, box.indices.end());
  const Scene split = load_scene(volume_file("closure_split_box.glb", {front, back}).string());
  ASSERT_EQ(split.meshes.size(), 2u);
  EXPECT_TRUE(split.meshes[0].closed);
  EXPECT_TRUE(split.meshes[1].closed);
  EXPECT_TRUE(split.warnings.empty()) << split.warnings.front();

  // The three.js sphere loads closed: its volume is a volume, not a thin wall.
  const Scene sphere = load_scene(
      volume_file("closure_threejs_sphere.glb", {test::threejs_sphere(0.5, 48, 24)}).string());
  ASSERT_EQ(sphere.meshes.size(), 1u);
  EXPECT_TRUE(sphere.meshes[0].closed);
  EXPECT_TRUE(sphere.warnings.empty()) << sphere.warnings.front();

  // Half the box alone is open: thin-walled, with a warning naming the primitive.
  const Scene half = load_scene(volume_file("closure_half_box.glb", {back}).string());
  ASSERT_EQ(half.meshes.size(), 1u);
  EXPECT_FALSE(half.meshes[0].closed);
  ASSERT_EQ(half.warnings.size(), 1u);
  EXPECT_EQ(half.warnings[0].rfind("meshes[0].primitives[0]: ", 0), 0u) << half.warnings[0];
}

}  // namespace
}  // namespace pbrkit
