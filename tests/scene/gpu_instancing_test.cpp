// EXT_mesh_gpu_instancing in the loader: each row of a node's TRANSLATION / ROTATION /
// SCALE accessors is one Instance at NodeWorldXform * T * R * S (the README's order), with
// every component type the README's table allows; the node's mesh is not drawn besides
// its instances; bad attributes are errors naming the file and the JSON path; large files
// (10^6 instances, 176,400 nodes) load in seconds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/util/error.h"
#include "scene/gltf_builder.h"

namespace pbrkit {
namespace {

using nlohmann::json;

// A file with one triangle mesh and one node (translated by (0, 0, -5)) carrying the
// extension with `attributes`; `edit` may make it hostile.
struct InstancedFile {
  test::GltfBuilder b;
  int node = -1;
  InstancedFile() {
    b.gltf["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    b.gltf["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
    const int mesh = b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2})});
    node = b.node({{"mesh", mesh}, {"translation", {0, 0, -5}}});
  }
  void attribute(const char* name, int accessor) {
    b.gltf["nodes"][std::size_t(node)]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]
          [name] = accessor;
  }
};

void expect_near(const glm::mat4& a, const glm::mat4& b, float tolerance) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_NEAR(a[c][r], b[c][r], tolerance) << "[" << c << "][" << r << "]";
}

TEST(GpuInstancing, FloatTranslationRotationScaleMakeOneInstanceEach) {
  InstancedFile f;
  const float h = std::sqrt(0.5f);
  f.attribute("TRANSLATION", f.b.floats(std::vector<glm::vec3>{{1, 2, 3}, {-4, 0, 0}, {0, 0, 0}}));
  // Identity, 90 degrees about +Z, 180 degrees about +X: (x, y, z, w).
  f.attribute("ROTATION",
              f.b.floats(std::vector<glm::vec4>{{0, 0, 0, 1}, {0, 0, h, h}, {1, 0, 0, 0}}));
  f.attribute("SCALE", f.b.floats(std::vector<glm::vec3>{{1, 1, 1}, {2, 3, 4}, {-1, 1, 1}}));
  const Scene s = load_scene(f.b.write("instancing_float.glb").string());
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 3u);  // and not the node's mesh a fourth time
  // Columns written out: node T(0, 0, -5) times the instance's T R S.
  const glm::mat4 expected[3] = {
      {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {1, 2, -2, 1}},
      // R_z(90) maps x to y and y to -x; scaled by (2, 3, 4) first.
      {{0, 2, 0, 0}, {-3, 0, 0, 0}, {0, 0, 4, 0}, {-4, 0, -5, 1}},
      // R_x(180) maps y to -y and z to -z; x mirrored by the scale.
      {{-1, 0, 0, 0}, {0, -1, 0, 0}, {0, 0, -1, 0}, {0, 0, -5, 1}},
  };
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(s.instances[std::size_t(i)].mesh, 0);
    EXPECT_EQ(s.instances[std::size_t(i)].node, f.node);
    expect_near(s.instances[std::size_t(i)].transform, expected[i], 1e-6f);
  }
}

TEST(GpuInstancing, QuantizedRotationsAreNormalizedIntegers) {
  // 90 degrees about +Z as normalized BYTE (90 / 127) and SHORT (23170 / 32767): equal
  // components renormalize to the exact quaternion; -127 is -1 (glTF 2.0 section 3.11).
  const glm::mat4 rz90 = {{0, 1, 0, 0}, {-1, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, -5, 1}};
  const glm::mat4 rx180 = {{1, 0, 0, 0}, {0, -1, 0, 0}, {0, 0, -1, 0}, {0, 0, -5, 1}};
  {
    InstancedFile f;
    const std::int8_t q[8] = {0, 0, 90, 90, -127, 0, 0, 0};
    f.attribute("ROTATION", f.b.accessor(q, sizeof q, 5120, "VEC4", 2, true));
    const Scene s = load_scene(f.b.write("instancing_byte.glb").string());
    ASSERT_EQ(s.instances.size(), 2u);
    expect_near(s.instances[0].transform, rz90, 1e-6f);
    expect_near(s.instances[1].transform, rx180, 1e-6f);
  }
  {
    InstancedFile f;
    const std::int16_t q[8] = {0, 0, 23170, 23170, -32767, 0, 0, 0};
    f.attribute("ROTATION", f.b.accessor(q, sizeof q, 5122, "VEC4", 2, true));
    const Scene s = load_scene(f.b.write("instancing_short.glb").string());
    ASSERT_EQ(s.instances.size(), 2u);
    expect_near(s.instances[0].transform, rz90, 1e-6f);
    expect_near(s.instances[1].transform, rx180, 1e-6f);
  }
}

TEST(GpuInstancing, CustomAttributesAreCheckedAndIgnored) {
  InstancedFile f;
  f.attribute("TRANSLATION", f.b.floats(std::vector<glm::vec3>{{1, 0, 0}, {2, 0, 0}}));
  const std::uint32_t ids[2] = {7, 9};
  f.attribute("_ID", f.b.accessor(ids, sizeof ids, 5125, "SCALAR", 2));
  const Scene s = load_scene(f.b.write("instancing_custom.glb").string());
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_EQ(s.instances[1].transform[3], glm::vec4(2, 0, -5, 1));
}

// The message load_scene throws for the file (empty, with a test failure, when it loads).
std::string load_error(const std::filesystem::path& path) {
  try {
    load_scene(path.string());
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded";
  return "";
}

TEST(GpuInstancing, BadAttributesAreErrorsNamingTheFileAndThePath) {
  const std::string at = "nodes[0].extensions.EXT_mesh_gpu_instancing";
  struct Case {
    const char* name;
    std::function<void(InstancedFile&)> edit;
    std::string where, what;
  };
  const std::vector<Case> cases = {
      {"count_mismatch",
       [](InstancedFile& f) {
         f.attribute("TRANSLATION", f.b.floats(std::vector<glm::vec3>{{1, 0, 0}, {2, 0, 0}}));
         f.attribute("SCALE", f.b.floats(std::vector<glm::vec3>{{1, 1, 1}}));
       },
       at + ".attributes.TRANSLATION", "must have the same count"},
      {"translation_vec4",
       [](InstancedFile& f) {
         f.attribute("TRANSLATION", f.b.floats(std::vector<glm::vec4>{{1, 0, 0, 0}}));
       },
       at + ".attributes.TRANSLATION", "is VEC4 of FLOAT; TRANSLATION must be VEC3 of FLOAT"},
      {"scale_bytes",
       [](InstancedFile& f) {
         const std::int8_t v[4] = {1, 1, 1, 0};
         f.attribute("SCALE", f.b.accessor(v, 3, 5120, "VEC3", 1, true));
       },
       at + ".attributes.SCALE", "SCALE must be VEC3 of FLOAT"},
      {"rotation_unnormalized_short",
       [](InstancedFile& f) {
         const std::int16_t q[4] = {0, 0, 0, 1};
         f.attribute("ROTATION", f.b.accessor(q, sizeof q, 5122, "VEC4", 1, false));
       },
       at + ".attributes.ROTATION",
       "ROTATION must be VEC4 of FLOAT, or of normalized BYTE or SHORT"},
      {"rotation_unsigned_byte",
       [](InstancedFile& f) {
         const std::uint8_t q[4] = {0, 0, 0, 255};
         f.attribute("ROTATION", f.b.accessor(q, sizeof q, 5121, "VEC4", 1, true));
       },
       at + ".attributes.ROTATION", "is VEC4 of normalized UNSIGNED_BYTE"},
      {"zero_scale",
       [](InstancedFile& f) {
         f.attribute("SCALE", f.b.floats(std::vector<glm::vec3>{{1, 1, 1}, {1, 0, 1}}));
       },
       at + ".attributes.SCALE", "instance 1's scale (1, 0, 1) makes a singular"},
      {"nan_translation",
       [](InstancedFile& f) {
         f.attribute("TRANSLATION", f.b.floats(std::vector<glm::vec3>{{1, std::nanf(""), 0}}));
       },
       at + ".attributes.TRANSLATION", "instance 0's translation"},
      {"nan_rotation",
       [](InstancedFile& f) {
         f.attribute("ROTATION", f.b.floats(std::vector<glm::vec4>{{0, 0, 0, std::nanf("")}}));
       },
       at + ".attributes.ROTATION", "is not a unit quaternion"},
      {"zero_rotation",
       [](InstancedFile& f) {
         f.attribute("ROTATION", f.b.floats(std::vector<glm::vec4>{{0, 0, 0, 0}}));
       },
       at + ".attributes.ROTATION", "is not a unit quaternion"},
      {"missing_accessor", [](InstancedFile& f) { f.attribute("TRANSLATION", 99); },
       at + ".attributes.TRANSLATION", "accessor 99 does not exist"},
      {"not_an_index",
       [](InstancedFile& f) {
         f.b.gltf["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["SCALE"] =
             "two";
       },
       at + ".attributes.SCALE", "must be an accessor index"},
      {"no_attributes",
       [](InstancedFile& f) {
         f.b.gltf["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"] = json::object();
       },
       at + ".attributes", "must be an object with at least one attribute"},
      {"not_an_object",
       [](InstancedFile& f) { f.b.gltf["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"] = 3; },
       at, "must be an object"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    InstancedFile f;
    c.edit(f);
    const auto path = f.b.write(std::string("instancing_bad_") + c.name + ".glb");
    const std::string message = load_error(path);
    EXPECT_EQ(message.rfind(path.string() + ": " + c.where + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(c.what), std::string::npos) << message;
  }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(GpuInstancing, AMillionInstancesLoadInSeconds) {
  // A 1000 x 1000 grid of one triangle: per-instance work must be constant (no allocation
  // or search per instance). The bound is loose (sanitizer builds, a loaded machine): a
  // quadratic step would take hours.
  constexpr std::size_t n = 1000000;
  InstancedFile f;
  std::vector<glm::vec3> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = glm::vec3(float(i % 1000), float(i / 1000), 0.0f);
  f.attribute("TRANSLATION", f.b.floats(t));
  const auto path = f.b.write("instancing_million.glb");
  const auto start = std::chrono::steady_clock::now();
  const Scene s = load_scene(path.string());
  const double elapsed = seconds_since(start);
  std::printf("10^6 instances: loaded in %.2f s\n", elapsed);
  ASSERT_EQ(s.instances.size(), n);
  EXPECT_EQ(s.instances[n - 1].transform[3], glm::vec4(999, 999, -5, 1));
  EXPECT_LT(elapsed, 30.0);
}

TEST(GpuInstancing, ManyNodesSharingAMeshLoadInSeconds) {
  // 176,400 nodes (a 420 x 420 grid) of one mesh, as the large scene has.
  constexpr int side = 420;
  test::GltfBuilder b;
  const int mesh = b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2})});
  json nodes = json::array();
  json roots = json::array();
  for (int i = 0; i < side * side; ++i) {
    nodes.push_back({{"mesh", mesh}, {"translation", {i % side, i / side, 0}}});
    roots.push_back(i);
  }
  b.gltf["nodes"] = std::move(nodes);
  b.gltf["scenes"] = {{{"nodes", std::move(roots)}}};
  b.gltf["scene"] = 0;
  const auto path = b.write("many_nodes.glb");
  // Progress is reported through the walk, rising, up to 1.
  std::vector<double> reports;
  LoadOptions options;
  options.progress = [&](double fraction, const std::string&) {
    reports.push_back(fraction);
    return true;
  };
  const auto start = std::chrono::steady_clock::now();
  const Scene s = load_scene(path.string(), options);
  const double elapsed = seconds_since(start);
  ASSERT_GT(reports.size(), 40u);  // every 4096 nodes
  EXPECT_TRUE(std::is_sorted(reports.begin(), reports.end()));
  EXPECT_EQ(reports.back(), 1.0);
  std::printf("%d nodes: loaded in %.2f s\n", side * side, elapsed);
  ASSERT_EQ(s.instances.size(), std::size_t(side * side));
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.instances.back().transform[3], glm::vec4(side - 1, side - 1, 0, 1));
  EXPECT_LT(elapsed, 30.0);
}

// util/progress.h's rule for the load: a progress callback that returns false stops the
// node walk, and the load returns the nodes set up so far, marked interrupted.
TEST(GpuInstancing, AStoppedLoadReturnsTheNodesSetUpSoFar) {
  constexpr int count = 3 * 4096;
  test::GltfBuilder b;
  const int mesh = b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2})});
  json nodes = json::array();
  json roots = json::array();
  for (int i = 0; i < count; ++i) {
    nodes.push_back({{"mesh", mesh}, {"translation", {i, 0, 0}}});
    roots.push_back(i);
  }
  b.gltf["nodes"] = std::move(nodes);
  b.gltf["scenes"] = {{{"nodes", std::move(roots)}}};
  b.gltf["scene"] = 0;
  const auto path = b.write("stopped_nodes.glb");
  // Stopped at the report after the first 4096 nodes: those, and no more.
  LoadOptions options;
  options.progress = [](double fraction, const std::string&) { return fraction <= 0.5; };
  const Scene stopped = load_scene(path.string(), options);
  EXPECT_TRUE(stopped.interrupted);
  EXPECT_EQ(stopped.instances.size(), 4096u);
  ASSERT_FALSE(stopped.warnings.empty());
  EXPECT_NE(stopped.warnings.back().find("4096 of 12288 nodes"), std::string::npos)
      << stopped.warnings.back();
  // Stopped at the first report: no node.
  options.progress = [](double, const std::string&) { return false; };
  const Scene none = load_scene(path.string(), options);
  EXPECT_TRUE(none.interrupted);
  EXPECT_TRUE(none.instances.empty());
  // Not stopped: every node.
  const Scene all = load_scene(path.string());
  EXPECT_FALSE(all.interrupted);
  EXPECT_EQ(all.instances.size(), std::size_t(count));
}

// The JSON chunk of a GLB (glTF 2.0 section 4.4).
json glb_json(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::uint32_t length = 0;
  if (bytes.size() < 20) return json();
  std::memcpy(&length, bytes.data() + 12, 4);
  return json::parse(bytes.substr(20, length));
}

TEST(GpuInstancing, WriterInstancesARepeatedMeshAndItReadsBack) {
  // One mesh drawn five times (turned, mirrored, squashed, scaled, moved) and a second
  // mesh drawn once, between them.
  Scene s;
  s.source = "test";
  s.materials.emplace_back();
  s.meshes.push_back(make_box(glm::vec3(-0.5f), glm::vec3(0.5f)));
  s.meshes.back().material = 0;
  s.meshes.push_back(make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  s.meshes.back().material = 0;
  const glm::vec3 up(0, 1, 0);
  const std::vector<glm::mat4> box = {
      glm::translate(glm::mat4(1.0f), {1, 2, 3}),
      glm::rotate(glm::translate(glm::mat4(1.0f), {-2, 0, 1}), 0.7f,
                  glm::normalize(glm::vec3(1, 2, 3))),
      glm::scale(glm::rotate(glm::mat4(1.0f), 2.5f, up), {-1.5f, 1.5f, 1.5f}),
      glm::scale(glm::rotate(glm::mat4(1.0f), -1.0f, up), {1.9f, 0.45f, 1.0f}),
      glm::scale(glm::mat4(1.0f), glm::vec3(0.01f)),
  };
  for (const glm::mat4& m : box) s.instances.push_back({0, m, -1});
  s.instances.insert(s.instances.begin() + 2, {1, glm::translate(glm::mat4(1.0f), {0, -1, 0}), -1});
  const auto path = test::scratch_dir() / "instancing_written.glb";
  write_glb(s, path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator

  const json gltf = glb_json(path);
  EXPECT_EQ(gltf["extensionsRequired"], json::array({"EXT_mesh_gpu_instancing"}));
  ASSERT_EQ(gltf["nodes"].size(), 2u);  // the instanced box (at its first instance), the quad
  const json& ext = gltf["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  for (const char* name : {"TRANSLATION", "ROTATION", "SCALE"})
    EXPECT_EQ(gltf["accessors"][ext[name].get<std::size_t>()]["count"], 5) << name;
  EXPECT_FALSE(gltf["nodes"][0].contains("matrix"));
  EXPECT_EQ(gltf["nodes"][1]["matrix"].size(), 16u);

  // Read back: the box's five instances first (its node comes first), then the quad.
  const Scene loaded = load_scene(path.string());
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  ASSERT_EQ(loaded.instances.size(), 6u);
  for (std::size_t i = 0; i < 5; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(loaded.instances[i].mesh, 0);
    expect_near(loaded.instances[i].transform, box[i], 1e-6f);
  }
  EXPECT_EQ(loaded.instances[5].mesh, 1);
  expect_near(loaded.instances[5].transform, s.instances[2].transform, 0.0f);
}

// Flattened (for importers that refuse EXT_mesh_gpu_instancing, Blender 3.4 among them):
// the built-in `instances` field as 10,001 nodes of its own that share the rock mesh by
// index, no extension, the validator clean, and read back the same placements in the same
// order (mirrored and squashed rocks included) and the same triangles.
TEST(GpuInstancing, WriterFlattensInstancesIntoNodesSharingTheMesh) {
  const Scene s = load_scene("instances");
  const auto path = test::scratch_dir() / "instances_flat.glb";
  GltfWriteOptions options;
  options.flatten_instances = true;
  write_glb(s, path, options);
  EXPECT_EQ(test::validate_gltf(path), "");

  const json gltf = glb_json(path);
  EXPECT_FALSE(gltf.contains("extensionsRequired")) << gltf["extensionsRequired"];
  for (const json& name : gltf.value("extensionsUsed", json::array()))
    EXPECT_NE(name, "EXT_mesh_gpu_instancing");
  // One node per instance plus the camera; the meshes are written once each.
  ASSERT_EQ(gltf["nodes"].size(), s.instances.size() + 1);
  EXPECT_EQ(gltf["meshes"].size(), s.meshes.size());
  for (const json& node : gltf["nodes"]) EXPECT_FALSE(node.contains("extensions"));

  const Scene loaded = load_scene(path.string());
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  EXPECT_TRUE(loaded.extensions_required.empty());
  EXPECT_EQ(loaded.node_count, s.instances.size() + 1);
  EXPECT_EQ(loaded.meshes.size(), s.meshes.size());  // shared by index, not copied
  EXPECT_EQ(loaded.triangle_count(), s.triangle_count());
  ASSERT_EQ(loaded.instances.size(), s.instances.size());
  int mirrored = 0;
  for (std::size_t i = 0; i < s.instances.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(loaded.instances[i].mesh, s.instances[i].mesh);
    expect_near(loaded.instances[i].transform, s.instances[i].transform, 0.0f);
    mirrored += glm::determinant(glm::mat3(loaded.instances[i].transform)) < 0.0f;
    if (HasFailure()) break;
  }
  EXPECT_GE(mirrored, 40);
}

}  // namespace
}  // namespace pbrkit
