// `pbrkit render --animation/--animation-time/--frames` and `pbrkit info --animation` on a
// skinned strip: the posed bounds against the pose worked out here, a frame sequence's
// names and motion, and the silhouettes of one pose in both renderers (intersection over
// union at least 0.99).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "pbrkit/image/image_io.h"
#include "scene/gltf_builder.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr float kPi = 3.14159265358979f;

// A vertical strip 0.4 wide from y = 0 to 2 in five rows of vertices, unlit white, skinned
// to joint 0 at the origin (rows y <= 0.5) and joint 1 at y = 1 (rows y >= 1.5), half each
// at y = 1. Animation "bend": joint 1 turns 60 degrees about z over [0, 1] s; the root
// moves +1 in x over the same second. A camera at z = 6 looks down -z.
fs::path strip_file() {
  test::GltfBuilder b;
  std::vector<glm::vec3> p;
  std::vector<std::uint8_t> joints;
  std::vector<glm::vec4> weights;
  for (int row = 0; row < 5; ++row) {
    const float y = 0.5f * float(row);
    for (const float x : {-0.2f, 0.2f}) {
      p.push_back({x, y, 0});
      joints.insert(joints.end(), {0, 1, 0, 0});
      weights.push_back(row < 2    ? glm::vec4(1, 0, 0, 0)
                        : row == 2 ? glm::vec4(0.5f, 0.5f, 0, 0)
                                   : glm::vec4(0, 1, 0, 0));
    }
  }
  std::vector<std::uint32_t> idx;
  for (std::uint32_t row = 0; row < 4; ++row) {
    const std::uint32_t a = 2 * row;
    idx.insert(idx.end(), {a, a + 1, a + 3, a, a + 3, a + 2});
  }
  json prim = b.primitive(p, idx, 0);
  prim["attributes"]["JOINTS_0"] = b.accessor(joints.data(), joints.size(), 5121, "VEC4", p.size());
  prim["attributes"]["WEIGHTS_0"] = b.floats(weights);
  b.gltf["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}}},
                          {"doubleSided", true},
                          {"extensions", {{"KHR_materials_unlit", json::object()}}}}};
  b.gltf["extensionsUsed"] = {"KHR_materials_unlit"};
  const int mesh = b.mesh({prim});
  b.node({{"mesh", mesh}, {"skin", 0}});
  const int joint1 = int(b.gltf["nodes"].size()) + 1;
  const int joint0 = b.node({{"children", {joint1}}});
  b.gltf["nodes"].push_back({{"translation", {0, 1, 0}}});
  const std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,
                                  1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  b.gltf["skins"] = {
      {{"joints", {joint0, joint1}},
       {"inverseBindMatrices", b.accessor(ibm.data(), ibm.size() * 4, 5126, "MAT4", 2)}}};
  b.gltf["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}};
  b.node({{"camera", 0}, {"translation", {0.5, 1, 6}}});
  const std::vector<float> times = {0.0f, 1.0f};
  const int t = b.accessor(times.data(), 8, 5126, "SCALAR", 2);
  const float s = std::sin(kPi / 6), c = std::cos(kPi / 6);
  const std::vector<glm::vec4> turn = {{0, 0, 0, 1}, {0, 0, s, c}};
  const std::vector<glm::vec3> move = {{0, 0, 0}, {1, 0, 0}};
  b.gltf["animations"] = {
      {{"name", "bend"},
       {"samplers",
        {{{"input", t}, {"output", b.floats(turn)}}, {{"input", t}, {"output", b.floats(move)}}}},
       {"channels",
        {{{"sampler", 0}, {"target", {{"node", joint1}, {"path", "rotation"}}}},
         {{"sampler", 1}, {"target", {{"node", joint0}, {"path", "translation"}}}}}}}};
  return b.write("skinned_strip.glb");
}

std::string cli() {
  return test::cli_path().string();
}

TEST(AnimationCli, InfoReportsThePosedBounds) {
  std::string out;
  ASSERT_EQ(test::run_command(
                cli() + " info --json --animation bend --animation-time 1 " + strip_file().string(),
                &out),
            0)
      << out;
  const json j = json::parse(out.substr(out.find('{')));
  ASSERT_EQ(j["animations"].size(), 1u);
  EXPECT_EQ(j["animations"][0]["name"], "bend");
  EXPECT_EQ(j["skins"], 1);
  // By hand at t = 1: the root moved +1 in x. The top row (y = 2, x = +-0.2) on joint 1
  // turned 60 degrees about (1 + 0, 1): (x, 1) -> (x cos 60 - sin 60, x sin 60 + cos 60) + (0, 1).
  // The lowest x is the top row's left vertex: -0.2 c - s + 1; the highest y the top
  // right vertex's: 0.2 s + c + 1.
  const float s = std::sin(kPi / 3), c = std::cos(kPi / 3);
  EXPECT_NEAR(j["bounds"]["min"][0].get<float>(), 1.0f - 0.2f * c - s, 1e-4f);
  EXPECT_NEAR(j["bounds"]["max"][1].get<float>(), 1.0f + 0.2f * s + c, 1e-4f);
  EXPECT_NEAR(j["bounds"]["max"][0].get<float>(), 1.2f, 1e-4f);  // the unbent bottom rows
}

// The fraction of pixels brighter than half.
std::vector<bool> silhouette(const Image& image) {
  std::vector<bool> mask(std::size_t(image.width) * std::size_t(image.height));
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      mask[std::size_t(y) * std::size_t(image.width) + std::size_t(x)] =
          image.pixel(x, y)[1] > 0.5f;
  return mask;
}

TEST(AnimationCli, BothRenderersDrawThePoseWithOneSilhouette) {
  const fs::path dir = test::scratch_dir();
  std::string log;
  const std::string common = cli() + " render " + strip_file().string() +
                             " --animation 0 --animation-time 0.75 --no-env --width 256 "
                             "--height 256 --tonemap none ";
  ASSERT_EQ(test::run_command(
                common + "--renderer path --spp 64 -o " + (dir / "strip_path.exr").string(), &log),
            0)
      << log;
  ASSERT_EQ(test::run_command(
                common + "--renderer gl --msaa 1 -o " + (dir / "strip_gl.exr").string(), &log),
            0)
      << log;
  const std::vector<bool> a = silhouette(read_image(dir / "strip_path.exr"));
  const std::vector<bool> b = silhouette(read_image(dir / "strip_gl.exr"));
  std::size_t inter = 0, uni = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    inter += a[i] && b[i];
    uni += a[i] || b[i];
  }
  ASSERT_GT(inter, 2000u);  // the strip covers thousands of pixels
  EXPECT_GE(double(inter) / double(uni), 0.99) << inter << " of " << uni;
}

TEST(AnimationCli, FramesWriteANumberedSequenceThatMoves) {
  const fs::path out = test::scratch_dir() / "seq" / "strip.png";
  std::string log;
  ASSERT_EQ(test::run_command(cli() + " render " + strip_file().string() +
                                  " --renderer gl --animation bend --frames 0:4:2 --fps 4 "
                                  "--no-env --width 96 --height 96 -o " +
                                  out.string(),
                              &log),
            0)
      << log;
  // Frames 0, 2 and 4 at 0, 0.5 and 1 s: the strip's centroid moves right.
  float previous = -1.0f;
  for (const char* frame : {"0000", "0002", "0004"}) {
    const fs::path png = out.parent_path() / (std::string("strip_") + frame + ".png");
    const fs::path exr = out.parent_path() / (std::string("strip_") + frame + ".exr");
    ASSERT_TRUE(fs::exists(png)) << png;
    ASSERT_TRUE(fs::exists(exr)) << exr;
    const Image image = read_image(exr);
    double sum = 0, sx = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const float v = image.pixel(x, y)[1];
        sum += v;
        sx += v * x;
      }
    ASSERT_GT(sum, 0.0);
    const float centroid = float(sx / sum);
    EXPECT_GT(centroid, previous + 3.0f) << frame;
    previous = centroid;
  }
  EXPECT_FALSE(fs::exists(out.parent_path() / "strip_0001.png"));
  // A sequence needs an animation: an error that says so.
  EXPECT_NE(test::run_command(cli() + " render " + strip_file().string() +
                                  " --frames 0:3 --renderer gl -o " + out.string(),
                              &log),
            0);
  EXPECT_NE(log.find("--animation"), std::string::npos) << log;
  EXPECT_NE(test::run_command(cli() + " render " + strip_file().string() +
                                  " --animation 0 --frames 3:1 --renderer gl -o " + out.string(),
                              &log),
            0);
  EXPECT_NE(log.find("--frames 3:1"), std::string::npos) << log;
}

TEST(AnimationCli, ShutterBlursThePathTracersImageAndIsChecked) {
  const fs::path dir = test::scratch_dir();
  std::string log;
  const std::string common = cli() + " render " + strip_file().string() +
                             " --animation bend --animation-time 0.5 --no-env --width 64 "
                             "--height 64 --tonemap none --renderer path --spp 64 ";
  ASSERT_EQ(test::run_command(common + "-o " + (dir / "still.exr").string(), &log), 0) << log;
  ASSERT_EQ(
      test::run_command(common + "--shutter -0.5:0.5 -o " + (dir / "blur.exr").string(), &log), 0)
      << log;
  // The strip slides 1 unit in x over the second the shutter is open: the blurred image
  // has partly covered pixels where the still one has either the strip or black.
  auto partial = [](const Image& image) {
    int n = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const float v = image.pixel(x, y)[1];
        n += v > 0.2f && v < 0.8f;
      }
    return n;
  };
  const int still = partial(read_image(dir / "still.exr"));
  const int blurred = partial(read_image(dir / "blur.exr"));
  EXPECT_GT(blurred, 3 * still + 50) << still << " " << blurred;
  // The OpenGL renderer draws the shutter's centre and says so.
  ASSERT_EQ(test::run_command(cli() + " render " + strip_file().string() +
                                  " --renderer gl --animation 0 --shutter 0:0.1 --width 32 "
                                  "--height 32 -o " +
                                  (dir / "gl_shutter.png").string(),
                              &log),
            0)
      << log;
  EXPECT_NE(log.find("draws the shutter's centre"), std::string::npos) << log;
  EXPECT_NE(test::run_command(common + "--shutter 0.1:0 -o " + (dir / "bad.exr").string(), &log),
            0);
  EXPECT_NE(log.find("--shutter 0.1:0"), std::string::npos) << log;
}

}  // namespace
}  // namespace pbrkit
