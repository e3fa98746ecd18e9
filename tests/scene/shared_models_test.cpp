// Every model in tests/data/assets/models (the shared assets) loads, with key numbers checked
// against what the assets' README states (and `pbrkit info` reports them).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/util/log.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

std::string model(const std::string& name) {
  return test::shared_asset("models/" + name).string();
}

class SharedModels : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(std::filesystem::is_directory(test::shared_asset("models")));
    previous_ = set_log_sink([](LogLevel, const std::string&) {});
  }
  void TearDown() override {
    if (previous_) set_log_sink(previous_);
  }
  LogSink previous_;
};

TEST_F(SharedModels, AllLoad) {
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(test::shared_asset("models"))) {
    const auto ext = entry.path().extension();
    if (ext != ".gltf" && ext != ".glb") continue;
    SCOPED_TRACE(entry.path().string());
    const Scene s = load_scene(entry.path().string());
    EXPECT_GT(s.triangle_count(), 0u);
    EXPECT_FALSE(s.world_bounds().empty());
  }
}

TEST_F(SharedModels, DracoMatchesTheUncompressedMesh) {
  const Scene draco = load_scene(model("suzi.glb"));
  const Scene plain = load_scene(model("suzi_uncompressed.glb"));
  const Bounds a = draco.world_bounds(), b = plain.world_bounds();
  // Draco quantises positions: the boxes agree to its quantisation step.
  EXPECT_NEAR(glm::distance(a.min, b.min), 0.0f, 1e-3f);
  EXPECT_NEAR(glm::distance(a.max, b.max), 0.0f, 1e-3f);
  EXPECT_EQ(draco.meshes.at(0).positions.size(), 7503u);  // accessors[1].count in the file
  // suzi's material has no pbr factors: the spec's rough white metal.
  const Material& m = draco.material_of(draco.meshes[0]);
  EXPECT_EQ(m.metallic_factor, 1.0f);
  EXPECT_EQ(m.roughness_factor, 1.0f);
  const Scene bunny = load_scene(model("bunny.glb"));
  EXPECT_EQ(bunny.material_of(bunny.meshes.at(0)).alpha_mode, AlphaMode::kBlend);
  EXPECT_TRUE(bunny.material_of(bunny.meshes.at(0)).double_sided);
}

TEST_F(SharedModels, EngineHierarchy) {
  const Scene s = load_scene(model("2CylinderEngine/2CylinderEngine.glb"));
  EXPECT_EQ(s.materials.size(), 34u);
  EXPECT_EQ(s.cameras.size(), 1u);
  EXPECT_GT(s.instances.size(), s.meshes.size() / 2);
}

TEST_F(SharedModels, BoxTexturedGltfAndGlbAgree) {
  const Scene a = load_scene(model("BoxTextured/BoxTextured.gltf"));
  const Scene b = load_scene(model("BoxTextured/BoxTextured.glb"));
  ASSERT_EQ(a.textures.size(), 1u);
  ASSERT_EQ(b.textures.size(), 1u);
  EXPECT_TRUE(a.textures[0].srgb);
  EXPECT_EQ(a.textures[0].width(), b.textures[0].width());
  EXPECT_EQ(a.textures[0].texels8, b.textures[0].texels8);
}

TEST_F(SharedModels, CamerasAndMorphCube) {
  const Scene cams = load_scene(model("Cameras/Cameras.gltf"));
  ASSERT_EQ(cams.cameras.size(), 2u);
  EXPECT_EQ(cams.cameras[0].type, Camera::Type::kPerspective);
  EXPECT_EQ(cams.cameras[1].type, Camera::Type::kOrthographic);
  const Scene cube = load_scene(model("AnimatedMorphCube/AnimatedMorphCube.gltf"));
  EXPECT_EQ(cube.triangle_count(), 12u);
}

TEST_F(SharedModels, InfoReportsKeyNumbers) {
  std::string out;
  const int status = test::run_command(
      test::cli_path().string() + " info --json '" + model("suzi_uncompressed.glb") + "'", &out);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("\"triangles\": 15744"), std::string::npos) << out;
  EXPECT_NE(out.find("\"materials\": 1"), std::string::npos) << out;
  const int s2 =
      test::run_command(test::cli_path().string() + " info '" + model("bunny.glb") + "'", &out);
  ASSERT_EQ(s2, 0) << out;
  EXPECT_NE(out.find("KHR_draco_mesh_compression"), std::string::npos) << out;
}

// `pbrkit info` lists each material: checked against the .gltf's own JSON (read here with
// nlohmann::json, not through the loader), and the bunny's BLEND + doubleSided material
// (the reason the renderers treat BLEND with alpha 1 as opaque).
TEST_F(SharedModels, InfoListsMaterials) {
  const std::string gltf_path = model("BoxTextured/BoxTextured.gltf");
  std::string out;
  ASSERT_EQ(test::run_command(test::cli_path().string() + " info --json '" + gltf_path + "'", &out),
            0)
      << out;
  const nlohmann::json info = nlohmann::json::parse(out.substr(out.find('{')));
  std::ifstream in(gltf_path);
  const nlohmann::json gltf = nlohmann::json::parse(in);
  ASSERT_EQ(info["material_list"].size(), gltf["materials"].size());
  for (std::size_t i = 0; i < gltf["materials"].size(); ++i) {
    const nlohmann::json& g = gltf["materials"][i];
    const nlohmann::json& pbr = g.value("pbrMetallicRoughness", nlohmann::json::object());
    const nlohmann::json& m = info["material_list"][i];
    EXPECT_EQ(m["name"], g.value("name", ""));
    EXPECT_FLOAT_EQ(m["metallic"].get<float>(), pbr.value("metallicFactor", 1.0f));
    EXPECT_FLOAT_EQ(m["roughness"].get<float>(), pbr.value("roughnessFactor", 1.0f));
    const auto& textures = m["textures"];
    EXPECT_EQ(std::find(textures.begin(), textures.end(), "baseColor") != textures.end(),
              pbr.contains("baseColorTexture"));
    EXPECT_EQ(m["alpha_mode"],
              g.value("alphaMode", std::string("OPAQUE")) == "OPAQUE" ? "opaque" : "other");
    EXPECT_EQ(m["meshes"], 1);
  }
  ASSERT_EQ(test::run_command(
                test::cli_path().string() + " info --json '" + model("bunny.glb") + "'", &out),
            0);
  const nlohmann::json bunny = nlohmann::json::parse(out.substr(out.find('{')));
  ASSERT_EQ(bunny["material_list"].size(), 1u);
  EXPECT_EQ(bunny["material_list"][0]["alpha_mode"], "blend");
  EXPECT_EQ(bunny["material_list"][0]["double_sided"], true);
  ASSERT_EQ(
      test::run_command(test::cli_path().string() + " info '" + model("bunny.glb") + "'", &out), 0);
  EXPECT_NE(out.find("blend, double-sided; 1 mesh"), std::string::npos) << out;
}

}  // namespace
}  // namespace pbrkit
