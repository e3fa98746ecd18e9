// Hand-checkable glTF files (written by tests/data/gltf/make_test_files.py from the spec,
// not by pbrkit): every expected number below is worked out in that script's comments.
#include <algorithm>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "pbrkit/core/color.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

std::string valid(const std::string& name) {
  return test::test_data("gltf/valid/" + name).string();
}

// Silences (and records) loader warnings for the duration of a test.
struct CaptureLog {
  std::vector<std::string> lines;
  LogSink previous;
  CaptureLog() {
    previous = set_log_sink([this](LogLevel, const std::string& m) { lines.push_back(m); });
  }
  ~CaptureLog() { set_log_sink(previous); }
};

glm::vec3 world(const Scene& s, const Instance& inst, std::size_t vertex) {
  return glm::vec3(inst.transform *
                   glm::vec4(s.meshes[std::size_t(inst.mesh)].positions[vertex], 1.0f));
}

void expect_near(glm::vec3 a, glm::vec3 b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(GltfLoader, TransformsAccumulateThroughThreeLevels) {
  const Scene s = load_scene(valid("hierarchy.gltf"));
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.node_count, 3u);
  EXPECT_EQ(s.instances[0].node, 2);
  // Flat normals were generated (no NORMAL), so vertices are in triangle order.
  expect_near(world(s, s.instances[0], 0), {10, 2, 0});
  expect_near(world(s, s.instances[0], 1), {10, 4, 0});
  expect_near(world(s, s.instances[0], 2), {8, 2, 0});
}

TEST(GltfLoader, TexturedQuadSamplesTheRightTexel) {
  const Scene s = load_scene(valid("textured_quad.gltf"));
  ASSERT_EQ(s.materials.size(), 2u);
  const Material& plain = s.materials[0];
  ASSERT_TRUE(plain.base_color_texture.valid());
  const Texture& tex = s.textures[std::size_t(plain.base_color_texture.texture)];
  EXPECT_EQ(tex.width(), 4);
  EXPECT_EQ(tex.height(), 4);
  EXPECT_TRUE(tex.srgb);
  EXPECT_EQ(tex.sampler.mag, FilterMode::kNearest);
  EXPECT_EQ(tex.sampler.wrap_s, WrapMode::kClampToEdge);
  EXPECT_EQ(tex.sampler.wrap_t, WrapMode::kMirroredRepeat);
  EXPECT_FALSE(tex.sampler.min_mipmap);
  EXPECT_EQ(tex.levels.size(), 3u);
  // Texel (x, y) holds sRGB bytes (60x, 60y, 200); uv (0, 0) is the top-left texel.
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const glm::vec4 v = tex.sample({(x + 0.5f) / 4.0f, (y + 0.5f) / 4.0f});
      EXPECT_NEAR(v.r, srgb_decode(60.0f * x / 255.0f), 1e-4f);
      EXPECT_NEAR(v.g, srgb_decode(60.0f * y / 255.0f), 1e-4f);
      EXPECT_NEAR(v.b, srgb_decode(200.0f / 255.0f), 1e-4f);
      EXPECT_NEAR(v.a, 1.0f, 1e-6f);
    }
  // The quad's vertex with uv (0, 0) is its top-left corner (0, 1, 0).
  const Mesh& quad = s.meshes[0];
  for (std::size_t i = 0; i < quad.positions.size(); ++i)
    if (quad.texcoords0[i] == glm::vec2(0.0f)) expect_near(quad.positions[i], {0, 1, 0});

  // The second material uses the same image as a normal map too: a second, linear texture.
  const Material& tr = s.materials[1];
  ASSERT_TRUE(tr.normal_texture.valid());
  EXPECT_NE(tr.normal_texture.texture, tr.base_color_texture.texture);
  const Texture& linear = s.textures[std::size_t(tr.normal_texture.texture)];
  EXPECT_FALSE(linear.srgb);
  EXPECT_NEAR(linear.sample({0.875f, 0.125f}).r, 180.0f / 255.0f, 1e-4f);
  EXPECT_FLOAT_EQ(tr.normal_scale, 0.5f);
  // A normal map without TANGENT: tangents were generated along +u = +X (with +Z normals).
  const Mesh& mapped = s.meshes[1];
  ASSERT_EQ(mapped.tangents.size(), mapped.positions.size());
  for (const glm::vec4& t : mapped.tangents) {
    expect_near(glm::vec3(t), {1, 0, 0});
    // v grows downwards (towards -Y), so the bitangent cross(N, T) = +Y is opposite: w = -1.
    EXPECT_EQ(t.w, -1.0f);
  }

  // KHR_texture_transform: the spec's example maps uv (1, 1) to (0.5, 0.5) and (0, 0) to
  // (0, 1) -- the lower-left quadrant, rotated.
  ASSERT_TRUE(tr.base_color_texture.transform.has_value());
  const glm::mat3 m = tr.base_color_texture.transform->matrix();
  const glm::vec2 a = glm::vec2(m * glm::vec3(1, 1, 1)), b = glm::vec2(m * glm::vec3(0, 0, 1));
  EXPECT_NEAR(a.x, 0.5f, 1e-6f);
  EXPECT_NEAR(a.y, 0.5f, 1e-6f);
  EXPECT_NEAR(b.x, 0.0f, 1e-6f);
  EXPECT_NEAR(b.y, 1.0f, 1e-6f);
  // So uv (0.25, 0.25) (texel (1, 1) without the transform) lands on texel (1, 2) + ...:
  // T R S (0.25, 0.25) = (0.125, 0.875) -> texel (0, 3) of the clamp/mirror texture.
  const glm::vec2 moved = glm::vec2(m * glm::vec3(0.25f, 0.25f, 1.0f));
  EXPECT_NEAR(moved.x, 0.125f, 1e-6f);
  EXPECT_NEAR(moved.y, 0.875f, 1e-6f);
  EXPECT_NEAR(tex.sample(moved).g, srgb_decode(180.0f / 255.0f), 1e-4f);
  EXPECT_NEAR(tex.sample(moved).r, 0.0f, 1e-6f);
}

// The triangles of a mesh as sets of vertex positions in order.
std::vector<std::array<glm::vec3, 3>> triangles(const Mesh& m) {
  std::vector<std::array<glm::vec3, 3>> out;
  for (std::size_t t = 0; t < m.indices.size(); t += 3)
    out.push_back(
        {m.positions[m.indices[t]], m.positions[m.indices[t + 1]], m.positions[m.indices[t + 2]]});
  return out;
}

TEST(GltfLoader, StripsAndFansProduceTheSpecTriangles) {
  CaptureLog log;
  const Scene s = load_scene(valid("strip_fan.gltf"));
  // The LINES primitive is skipped with a warning.
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.warnings.size(), 1u);
  const glm::vec3 p[5] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}};
  const auto strip = triangles(s.meshes[0]);
  // glTF 2.0 section 3.7.2.1: strip triangle i = (v_i, v_{i+1+i%2}, v_{i+2-i%2}).
  const int strip_expected[3][3] = {{0, 1, 2}, {1, 3, 2}, {2, 3, 4}};
  ASSERT_EQ(strip.size(), 3u);
  for (int t = 0; t < 3; ++t)
    for (int k = 0; k < 3; ++k)
      expect_near(strip[std::size_t(t)][std::size_t(k)], p[strip_expected[t][k]]);
  const auto fan = triangles(s.meshes[1]);
  const int fan_expected[3][3] = {{1, 2, 0}, {2, 3, 0}, {3, 4, 0}};
  ASSERT_EQ(fan.size(), 3u);
  for (int t = 0; t < 3; ++t)
    for (int k = 0; k < 3; ++k)
      expect_near(fan[std::size_t(t)][std::size_t(k)], p[fan_expected[t][k]]);
}

TEST(GltfLoader, QuantizedAttributesDecodeToTheSpecFloats) {
  const Scene s = load_scene(valid("quantized.gltf"));
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.positions.size(), 3u);
  // SHORT normalized: max(c / 32767, -1), read through byteStride 8.
  expect_near(m.positions[0], {1, 0, 0});
  expect_near(m.positions[1], {0, 0, 0});
  expect_near(m.positions[2], {0, -1, 16384.0f / 32767.0f});
  // BYTE normalized normals (0, 0, 127) -> (0, 0, 1).
  expect_near(m.normals[0], {0, 0, 1});
  // UNSIGNED_BYTE normalized texcoords: 255 -> 1, 51 -> 0.2.
  EXPECT_NEAR(m.texcoords0[0].y, 1.0f, 1e-6f);
  EXPECT_NEAR(m.texcoords0[1].y, 0.2f, 1e-6f);
  // USHORT normalized colours: (65535, 0, 0, 65535) -> (1, 0, 0, 1).
  EXPECT_EQ(m.colors0[2], glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(s.extensions_required, std::vector<std::string>{"KHR_mesh_quantization"});
}

TEST(GltfLoader, SpecDefaultsApply) {
  const Scene s = load_scene(valid("defaults.gltf"));
  // No scene: every root node is shown.
  ASSERT_EQ(s.instances.size(), 2u);
  const Material& none = s.material_of(s.meshes[0]);
  EXPECT_EQ(&none, &Scene::default_material());
  const Material& empty = s.material_of(s.meshes[1]);
  EXPECT_EQ(empty.base_color_factor, glm::vec4(1.0f));
  EXPECT_EQ(empty.metallic_factor, 1.0f);
  EXPECT_EQ(empty.roughness_factor, 1.0f);
  EXPECT_EQ(empty.emissive_factor, glm::vec3(0.0f));
  EXPECT_EQ(empty.alpha_mode, AlphaMode::kOpaque);
  EXPECT_EQ(empty.alpha_cutoff, 0.5f);
  EXPECT_FALSE(empty.double_sided);
  EXPECT_EQ(empty.normal_scale, 1.0f);
  EXPECT_EQ(empty.occlusion_strength, 1.0f);
  // Flat normals of the counter-clockwise triangle in the XY plane: +Z.
  for (const glm::vec3& n : s.meshes[0].normals) expect_near(n, {0, 0, 1});
}

TEST(GltfLoader, SparseAccessorAndMorphTargetAtDefaultWeight) {
  const Scene s = load_scene(valid("sparse_morph.gltf"));
  const Mesh& m = s.meshes.at(0);
  // Sparse replaces vertex 2 by (0, 5, 0); the morph target adds 0.5 * (2, 0, 0) to vertex 1.
  expect_near(m.positions[0], {0, 0, 0});
  expect_near(m.positions[1], {2, 0, 0});  // (1, 0, 0) + 0.5 * (2, 0, 0)
  expect_near(m.positions[2], {0, 5, 0});
}

TEST(GltfLoader, CamerasAndPunctualLights) {
  CaptureLog log;
  const Scene s = load_scene(valid("cameras_lights.gltf"));
  // The unsupported optional extension is a warning, not an error.
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("EXT_fancy_optional"), std::string::npos);
  ASSERT_EQ(s.cameras.size(), 2u);
  const Camera& p = s.cameras[0];
  EXPECT_EQ(p.type, Camera::Type::kPerspective);
  EXPECT_FLOAT_EQ(p.yfov, 0.5f);
  EXPECT_FLOAT_EQ(*p.aspect_ratio, 1.5f);
  EXPECT_FLOAT_EQ(*p.zfar, 100.0f);
  expect_near(p.position(), {0, 0, 5});
  expect_near(p.forward(), {0, 0, -1});
  const Camera& o = s.cameras[1];
  EXPECT_EQ(o.type, Camera::Type::kOrthographic);
  EXPECT_FLOAT_EQ(o.xmag, 2.0f);
  EXPECT_FLOAT_EQ(o.ymag, 1.0f);
  expect_near(o.position(), {0, 3, 0});
  expect_near(o.forward(), {0, -1, 0});  // rotated -90 degrees about X
  // Scale is removed from the camera transform.
  EXPECT_NEAR(glm::length(glm::vec3(o.camera_to_world[0])), 1.0f, 1e-6f);
  // select_camera by index.
  EXPECT_EQ(select_camera(s, 1, 1.0f).type, Camera::Type::kOrthographic);

  ASSERT_EQ(s.lights.size(), 3u);
  const Light& point = s.lights[0];
  EXPECT_EQ(point.type, Light::Type::kPoint);
  EXPECT_EQ(point.color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(point.intensity, 40.0f);
  EXPECT_FLOAT_EQ(*point.range, 10.0f);
  expect_near(point.position, {1, 2, 3});
  const Light& spot = s.lights[1];
  EXPECT_EQ(spot.type, Light::Type::kSpot);
  EXPECT_FLOAT_EQ(spot.inner_cone_angle, 0.2f);
  EXPECT_FLOAT_EQ(spot.outer_cone_angle, 0.6f);
  EXPECT_FALSE(spot.range.has_value());
  expect_near(spot.direction, {0, -1, 0});
  const Light& sun = s.lights[2];
  EXPECT_EQ(sun.type, Light::Type::kDirectional);
  expect_near(sun.direction, {0, 0, -1});
}

TEST(GltfLoader, GlbWithBinChunk) {
  const Scene s = load_scene(valid("triangle.glb"));
  ASSERT_EQ(s.triangle_count(), 1u);
  const Bounds b = s.world_bounds();
  expect_near(b.max, {1, 1, 0});
}

TEST(GltfLoader, MissingFileIsAClearError) {
  try {
    load_scene("/nonexistent/dir/model.gltf");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/model.gltf: no such file"),
              std::string::npos)
        << e.what();
  }
}

TEST(GltfLoader, LimitsAreEnforced) {
  LoadOptions tight;
  tight.limits.max_triangles = 0;
  EXPECT_THROW(load_scene(valid("hierarchy.gltf"), tight), Error);
  tight = {};
  tight.limits.max_image_pixels = 15;  // the 4x4 texture has 16
  try {
    load_scene(valid("textured_quad.gltf"), tight);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("images[0]"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pbrkit

namespace pbrkit {
namespace {

TEST(GltfLoader, InfoListsUnsupportedExtensionsAndCounts) {
  std::string out;
  const int status = test::run_command(
      test::cli_path().string() + " info --json '" + valid("cameras_lights.gltf") + "'", &out);
  ASSERT_EQ(status, 0) << out;
  const auto json_start = out.find('{');
  ASSERT_NE(json_start, std::string::npos) << out;
  const nlohmann::json j = nlohmann::json::parse(out.substr(json_start));
  EXPECT_EQ(j["extensions_unsupported"], nlohmann::json::array({"EXT_fancy_optional"}));
  EXPECT_EQ(j["lights"].size(), 3u);
  EXPECT_EQ(j["cameras"].size(), 2u);
  EXPECT_EQ(j["triangles"], 1);
  EXPECT_EQ(j["nodes"], 6);
}

}  // namespace
}  // namespace pbrkit
