// write_glb must write what the glTF 2.0 schema allows, not only what our own loader
// accepts: Blender, three.js and the Khronos validator read the same files. These tests
// read the written JSON chunk directly and check the properties the schema constrains.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

using nlohmann::json;

// The JSON chunk of a .glb (glTF 2.0 section 4.4: a 12-byte header whose length is the
// file's, then the first chunk's length and type "JSON", then its bytes).
json glb_json(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) {
    ADD_FAILURE() << path << " is not a GLB file";
    return json();
  }
  std::uint32_t total = 0, length = 0, type = 0;
  std::memcpy(&total, bytes.data() + 8, 4);
  std::memcpy(&length, bytes.data() + 12, 4);
  std::memcpy(&type, bytes.data() + 16, 4);
  EXPECT_EQ(total, bytes.size());
  EXPECT_EQ(type, 0x4E4F534Au);
  EXPECT_EQ(length % 4, 0u);
  EXPECT_LE(20 + std::size_t(length), bytes.size());
  return json::parse(bytes.substr(20, length));
}

Scene scene_with_camera(const Camera& camera) {
  Scene s;
  s.source = "test";
  s.materials.emplace_back();
  add_mesh_instance(s, make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 0);
  s.cameras.push_back(camera);
  return s;
}

// The camera.perspective schema: yfov > 0, znear > 0, zfar (if present) > 0 and > znear,
// aspectRatio (if present) > 0. camera.orthographic: xmag, ymag non-zero, zfar > 0 and
// > znear, znear >= 0.
void expect_cameras_follow_schema(const json& gltf) {
  if (!gltf.contains("cameras")) return;
  for (const json& camera : gltf["cameras"]) {
    SCOPED_TRACE(camera.dump());
    if (camera["type"] == "perspective") {
      const json& p = camera["perspective"];
      EXPECT_GT(p["yfov"].get<double>(), 0.0);
      EXPECT_GT(p["znear"].get<double>(), 0.0);
      if (p.contains("zfar")) {
        EXPECT_GT(p["zfar"].get<double>(), p["znear"].get<double>());
      }
      if (p.contains("aspectRatio")) {
        EXPECT_GT(p["aspectRatio"].get<double>(), 0.0);
      }
    } else {
      ASSERT_EQ(camera["type"], "orthographic");
      const json& o = camera["orthographic"];
      EXPECT_NE(o["xmag"].get<double>(), 0.0);
      EXPECT_NE(o["ymag"].get<double>(), 0.0);
      EXPECT_GE(o["znear"].get<double>(), 0.0);
      EXPECT_GT(o["zfar"].get<double>(), o["znear"].get<double>());
    }
  }
}

TEST(GltfWriter, InfinitePerspectiveCameraHasNoZfar) {
  // Absent zfar means an infinite projection (camera.perspective schema); a written
  // "zfar": 0 is out of range and makes Blender clip everything.
  Camera camera;
  camera.name = "infinite";
  camera.yfov = 0.5f;
  camera.znear = 0.25f;
  const auto path = test::scratch_dir() / "infinite.glb";
  write_glb(scene_with_camera(camera), path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
  const json gltf = glb_json(path);
  ASSERT_EQ(gltf["cameras"].size(), 1u);
  const json& p = gltf["cameras"][0]["perspective"];
  EXPECT_FALSE(p.contains("zfar")) << p.dump();
  EXPECT_FALSE(p.contains("aspectRatio")) << p.dump();
  EXPECT_EQ(p["yfov"], 0.5);
  EXPECT_EQ(p["znear"], 0.25);
  expect_cameras_follow_schema(gltf);

  const Scene loaded = load_scene(path.string());
  ASSERT_EQ(loaded.cameras.size(), 1u);
  EXPECT_FALSE(loaded.cameras[0].zfar.has_value());
  EXPECT_FALSE(loaded.cameras[0].aspect_ratio.has_value());
}

TEST(GltfWriter, FiniteZfarAndAspectRatioRoundTrip) {
  Camera camera;
  camera.name = "finite";
  camera.znear = 0.5f;
  camera.zfar = 250.0f;
  camera.aspect_ratio = 1.5f;
  const auto path = test::scratch_dir() / "finite.glb";
  write_glb(scene_with_camera(camera), path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
  const json gltf = glb_json(path);
  const json& p = gltf["cameras"][0]["perspective"];
  EXPECT_EQ(p["zfar"], 250.0);
  EXPECT_EQ(p["aspectRatio"], 1.5);
  expect_cameras_follow_schema(gltf);

  const Scene loaded = load_scene(path.string());
  ASSERT_EQ(loaded.cameras.size(), 1u);
  EXPECT_EQ(loaded.cameras[0].zfar, 250.0f);
  EXPECT_EQ(loaded.cameras[0].aspect_ratio, 1.5f);
}

TEST(GltfWriter, OrthographicCameraAlwaysHasZfar) {
  // camera.orthographic requires zfar; a camera without one gets a far plane 1e6 beyond
  // its near plane.
  Camera camera;
  camera.type = Camera::Type::kOrthographic;
  camera.znear = 0.0f;
  camera.xmag = 2.0f;
  camera.ymag = 3.0f;
  const auto path = test::scratch_dir() / "ortho.glb";
  write_glb(scene_with_camera(camera), path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
  const json gltf = glb_json(path);
  EXPECT_EQ(gltf["cameras"][0]["orthographic"]["zfar"], 1e6);
  expect_cameras_follow_schema(gltf);
}

TEST(GltfWriter, BuiltinScenesFollowTheCameraSchema) {
  // What `pbrkit scene write <name> file.glb` writes.
  const auto dir = test::scratch_dir();
  for (const std::string& name : builtin_scene_names()) {
    SCOPED_TRACE(name);
    const auto path = dir / (name + ".glb");
    write_glb(builtin_scene(name), path);
    EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
    const json gltf = glb_json(path);
    ASSERT_TRUE(gltf.contains("cameras"));
    expect_cameras_follow_schema(gltf);
  }
}

TEST(GltfWriter, SceneWithoutGeometryHasNoEmptyBuffer) {
  // buffer.byteLength has a minimum of 1, so a scene with nothing to store has no buffer.
  Scene s;
  s.source = "test";
  Camera camera;
  camera.name = "only";
  s.cameras.push_back(camera);
  const auto path = test::scratch_dir() / "no_geometry.glb";
  write_glb(s, path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
  const json gltf = glb_json(path);
  EXPECT_FALSE(gltf.contains("buffers")) << gltf.dump();
  const Scene loaded = load_scene(path.string());
  EXPECT_EQ(loaded.cameras.size(), 1u);
  EXPECT_TRUE(loaded.meshes.empty());
}

TEST(GltfWriter, AlphaCutoffOnlyForMaskMaterials) {
  // The material schema: alphaCutoff is ignored unless alphaMode is MASK and must not be
  // defined when alphaMode is not (OPAQUE is written as no alphaMode).
  Scene s;
  s.source = "test";
  for (AlphaMode mode : {AlphaMode::kOpaque, AlphaMode::kBlend, AlphaMode::kMask}) {
    Material m;
    m.alpha_mode = mode;
    m.alpha_cutoff = 0.25f;
    s.materials.push_back(m);
  }
  add_mesh_instance(s, make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 2);
  const auto path = test::scratch_dir() / "alpha.glb";
  write_glb(s, path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
  const json gltf = glb_json(path);
  ASSERT_EQ(gltf["materials"].size(), 3u);
  EXPECT_FALSE(gltf["materials"][0].contains("alphaMode"));
  EXPECT_FALSE(gltf["materials"][0].contains("alphaCutoff"));
  EXPECT_EQ(gltf["materials"][1]["alphaMode"], "BLEND");
  EXPECT_FALSE(gltf["materials"][1].contains("alphaCutoff"));
  EXPECT_EQ(gltf["materials"][2]["alphaMode"], "MASK");
  EXPECT_EQ(gltf["materials"][2]["alphaCutoff"], 0.25);
  const Scene loaded = load_scene(path.string());
  EXPECT_EQ(loaded.materials[2].alpha_cutoff, 0.25f);
}

TEST(GltfWriter, DirectionalLightHasNoRange) {
  // KHR_lights_punctual: range bounds point and spot lights; a directional light's would
  // never be used.
  Scene s;
  s.source = "test";
  Light sun;
  sun.type = Light::Type::kDirectional;
  sun.range = 5.0f;
  sun.direction = {0, -1, 0};
  s.lights.push_back(sun);
  Light bulb;
  bulb.type = Light::Type::kPoint;
  bulb.range = 7.0f;
  bulb.position = {0, 2, 0};
  s.lights.push_back(bulb);
  const auto path = test::scratch_dir() / "lights.glb";
  write_glb(s, path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
  const json lights = glb_json(path)["extensions"]["KHR_lights_punctual"]["lights"];
  ASSERT_EQ(lights.size(), 2u);
  EXPECT_FALSE(lights[0].contains("range")) << lights[0].dump();
  EXPECT_EQ(lights[1]["range"], 7.0);
}

TEST(GltfWriter, IdentityTransformsAreLeftOut) {
  // node.matrix defaults to the identity (the validator's NODE_MATRIX_DEFAULT).
  Scene s;
  s.source = "test";
  s.materials.emplace_back();
  const Mesh quad = make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  add_mesh_instance(s, quad, 0);
  add_mesh_instance(s, quad, 0, glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3)));
  const auto path = test::scratch_dir() / "matrices.glb";
  write_glb(s, path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
  const json nodes = glb_json(path)["nodes"];
  ASSERT_EQ(nodes.size(), 2u);
  EXPECT_FALSE(nodes[0].contains("matrix")) << nodes[0].dump();
  ASSERT_EQ(nodes[1]["matrix"].size(), 16u);
  EXPECT_EQ(nodes[1]["matrix"][12], 1.0);
  EXPECT_EQ(nodes[1]["matrix"][13], 2.0);
  EXPECT_EQ(nodes[1]["matrix"][14], 3.0);
  const Scene loaded = load_scene(path.string());
  ASSERT_EQ(loaded.instances.size(), 2u);
  EXPECT_EQ(loaded.instances[0].transform, glm::mat4(1.0f));
  EXPECT_EQ(loaded.instances[1].transform[3], glm::vec4(1, 2, 3, 1));
}

}  // namespace
}  // namespace pbrkit
