// `pbrkit view --variant`: the viewer's first scene takes the material variant
// (KHR_materials_variants) the flag names, as `pbrkit render --variant` does: a grey triangle
// shows blue under the variant that maps it to blue.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "pbrkit/image/image_io.h"
#include "support/test_paths.h"

namespace {

// A triangle facing the camera, grey; variant "Blue" makes it blue.
const char* kVariantsGltf = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_materials_variants"],
  "extensions": {"KHR_materials_variants": {"variants": [{"name": "Blue"}]}},
  "buffers": [{"byteLength": 36, "uri":
    "data:application/octet-stream;base64,AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAAAAAAAAgD8AAAAA"}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [-1, -1, 0], "max": [1, 1, 0]}],
  "materials": [
    {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0}},
    {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 1, 1], "metallicFactor": 0}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0, "extensions":
    {"KHR_materials_variants": {"mappings": [{"material": 1, "variants": [0]}]}}}]}],
  "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";

TEST(ViewerVariants, TheFlagsVariantIsShown) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed";
  const std::filesystem::path dir = pbrkit::test::scratch_dir();
  const std::filesystem::path gltf = dir / "variants.gltf", png = dir / "variant_shot.png";
  std::ofstream(gltf) << kVariantsGltf;
  const std::string command = std::string("xvfb-run -a -s '-screen 0 1280x720x24' ") +
                              pbrkit::test::cli_path().string() + " view " + gltf.string() +
                              " --variant Blue --width 96 --height 96 --frames 3 --msaa 1"
                              " --screenshot " +
                              png.string() + " > " + (dir / "variant_log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "variant_log.txt");
  const pbrkit::Image shot = pbrkit::read_image(png);
  const glm::vec3 c = shot.rgb(shot.width / 2, shot.height / 2 + 4);
  EXPECT_GT(c.b, 4.0f * c.r) << c.r << " " << c.g << " " << c.b;
}

}  // namespace
