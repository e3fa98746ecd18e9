// --variant (KHR_materials_variants) on `pbrkit render`, both renderers, and the variants
// `pbrkit info` lists: the triangle's grey is red or blue under the variant chosen by name
// or index; an unknown variant is an error naming the flag and listing the variants.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "pbrkit/image/image_io.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

// A triangle facing the camera, grey; variant 0 "Red" makes it red, 1 "Blue shoe" blue.
fs::path variants_file() {
  const fs::path path = test::scratch_dir() / "variants.gltf";
  // The three vertices (-1,-1,0), (1,-1,0), (0,1,0) as little-endian floats, base64.
  const char* positions = "AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAAAAAAAAgD8AAAAA";
  const nlohmann::json mappings = {{{"material", 1}, {"variants", {0}}},
                                   {{"material", 2}, {"variants", {1}}}};
  auto material = [](const char* name, float r, float g, float b) {
    return nlohmann::json{
        {"name", name},
        {"pbrMetallicRoughness", {{"baseColorFactor", {r, g, b, 1}}, {"metallicFactor", 0}}}};
  };
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_materials_variants"}},
      {"extensionsRequired", {"KHR_materials_variants"}},
      {"extensions",
       {{"KHR_materials_variants", {{"variants", {{{"name", "Red"}}, {{"name", "Blue shoe"}}}}}}}},
      {"buffers",
       {{{"byteLength", 36},
         {"uri", std::string("data:application/octet-stream;base64,") + positions}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 3},
         {"type", "VEC3"},
         {"min", {-1, -1, 0}},
         {"max", {1, 1, 0}}}}},
      {"materials",
       {material("grey", 0.5f, 0.5f, 0.5f), material("red", 1, 0, 0), material("blue", 0, 0, 1)}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}}},
            {"material", 0},
            {"extensions", {{"KHR_materials_variants", {{"mappings", mappings}}}}}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  std::ofstream(path) << gltf.dump();
  return path;
}

// The centre pixel of a 16 x 16 render with `args`.
glm::vec3 centre(const std::string& args, const std::string& name) {
  const fs::path out = test::scratch_dir() / (name + ".exr");
  std::string log;
  EXPECT_EQ(test::run_command(test::cli_path().string() + " render " + variants_file().string() +
                                  " --width 16 --height 16 -o " + out.string() + " " + args,
                              &log),
            0)
      << log;
  const Image image = read_image(out);
  const float* p = image.pixel(8, 9);
  return {p[0], p[1], p[2]};
}

TEST(VariantCli, RenderTakesTheVariantByNameOrIndexWithEitherRenderer) {
  for (const std::string renderer : {"path --spp 16", "gl"}) {
    SCOPED_TRACE(renderer);
    const glm::vec3 grey = centre("--renderer " + renderer, "variant_none");
    // Grey under the environment's colour: neither channel dominates as under a variant.
    EXPECT_LT(std::max(grey.r, grey.b), 2.0f * std::min(grey.r, grey.b));
    const glm::vec3 red = centre("--renderer " + renderer + " --variant Red", "variant_red");
    EXPECT_GT(red.r, 10.0f * red.b);
    const glm::vec3 blue = centre("--renderer " + renderer + " --variant 1", "variant_blue");
    EXPECT_GT(blue.b, 10.0f * blue.r);
  }
  std::string log;
  EXPECT_EQ(test::run_command(test::cli_path().string() + " render " + variants_file().string() +
                                  " --renderer gl --variant Green -o " +
                                  (test::scratch_dir() / "variant_bad.png").string(),
                              &log),
            1);
  EXPECT_NE(log.find("--variant: "), std::string::npos) << log;
  EXPECT_NE(log.find("the scene's variants are 0 'Red', 1 'Blue shoe'"), std::string::npos) << log;
}

TEST(VariantCli, InfoListsTheVariants) {
  std::string out;
  ASSERT_EQ(test::run_command(
                test::cli_path().string() + " info --json " + variants_file().string(), &out),
            0)
      << out;
  const nlohmann::json j = nlohmann::json::parse(out.substr(out.find('{')));
  ASSERT_EQ(j["variants"].size(), 2u);
  EXPECT_EQ(j["variants"][1]["name"], "Blue shoe");
  EXPECT_EQ(j["variants"][1]["meshes"], 1);
  ASSERT_EQ(
      test::run_command(test::cli_path().string() + " info " + variants_file().string(), &out), 0);
  EXPECT_NE(out.find("1 'Blue shoe'"), std::string::npos) << out;
}

}  // namespace
}  // namespace pbrkit
