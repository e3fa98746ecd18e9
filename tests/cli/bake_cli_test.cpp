// `pbrkit bake` end to end: the built binary on small synthetic environments.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "pbrkit/core/math.h"
#include "pbrkit/ibl/ktx2.h"
#include "pbrkit/image/image_io.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

const std::string kSmall = " --size 16 --min-size 4 --samples 64 --irradiance-size 4 --lut-size 16";

fs::path write_env(const fs::path& dir, const std::string& name, int w, int h, glm::vec3 L) {
  Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.set_rgb(x, y, L);
  write_exr(dir / name, img, ExrPixelType::kFloat);
  return dir / name;
}

std::string bake(const fs::path& env, const fs::path& out, const std::string& extra, int* code) {
  std::string output;
  *code = test::run_command(test::cli_path().string() + " bake " + env.string() + " -o " +
                                out.string() + kSmall + " " + extra,
                            &output);
  return output;
}

TEST(BakeCli, ConstantEnvironmentProducesEveryOutput) {
  const fs::path dir = test::scratch_dir();
  const glm::vec3 L(0.5f, 1.0f, 2.0f);
  const fs::path env = write_env(dir, "flat.exr", 64, 32, L);
  int code = 0;
  const std::string log = bake(env, dir / "out", "--validate", &code);
  ASSERT_EQ(code, 0) << log;
  EXPECT_NE(log.find("validation"), std::string::npos) << log;
  EXPECT_NE(log.find("total"), std::string::npos) << log;
  for (const char* f : {"specular.ktx2",
                        "irradiance.ktx2",
                        "brdf_lut_reference.ktx2",
                        "brdf_lut_reference_f32.ktx2",
                        "brdf_lut_reference.exr",
                        "brdf_lut_classic.ktx2",
                        "brdf_lut_classic_f32.ktx2",
                        "brdf_lut_classic.exr",
                        "specular_mip0.exr",
                        "specular_mip2.exr",
                        "irradiance.exr",
                        "preview_specular_mip0.png",
                        "preview_irradiance.png",
                        "manifest.json",
                        "sheen.ktx2",
                        "sheen_lut.ktx2",
                        "sheen_lut_f32.ktx2",
                        "sheen_lut.exr",
                        "sheen_mip0.exr",
                        "preview_sheen_mip0.png",
                        "preview_sheen_lut.png"})
    EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
  // No staging folder or temporary files are left behind.
  for (const auto& e : fs::directory_iterator(dir / "out"))
    EXPECT_NE(e.path().filename().string()[0], '.') << e.path();

  // The specular cube: 16, 8, 4 px, RGBA16F, every level the constant L (furnace).
  const Ktx2Texture spec = read_ktx2(dir / "out" / "specular.ktx2");
  EXPECT_EQ(spec.format, Ktx2Format::kRgba16Float);
  EXPECT_EQ(spec.faces, 6u);
  const Cubemap cube = cubemap_from_ktx2(spec);
  ASSERT_EQ(cube.levels(), 3);
  for (int l = 0; l < 3; ++l)
    for (const Image& f : cube.mips[l])
      for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x)
          for (int c = 0; c < 3; ++c) ASSERT_NEAR(f.rgb(x, y)[c] / L[c], 1.0f, 2e-3f);
  // Irradiance = pi L.
  const Cubemap irr = cubemap_from_ktx2(read_ktx2(dir / "out" / "irradiance.ktx2"));
  EXPECT_NEAR(irr.mips[0][2].rgb(1, 1).y / (kPi * L.y), 1.0f, 2e-3f);
  // Both LUT precisions hold the same table.
  const Image lut16 = image_from_ktx2(read_ktx2(dir / "out" / "brdf_lut_reference.ktx2"));
  const Image lut32 = image_from_ktx2(read_ktx2(dir / "out" / "brdf_lut_reference_f32.ktx2"));
  ASSERT_EQ(lut32.width, 16);
  for (std::size_t i = 0; i < lut32.data.size(); ++i)
    EXPECT_NEAR(lut16.data[i], lut32.data[i], 1e-3f);

  std::ifstream mf(dir / "out" / "manifest.json");
  const nlohmann::json m = nlohmann::json::parse(mf);
  EXPECT_EQ(m["specular"]["levels"], 3);
  EXPECT_EQ(m["specular"]["roughness_mapping"], "linear");
  EXPECT_EQ(m["specular"]["samples"], 64);
  EXPECT_NEAR(m["specular"]["level_details"][1]["roughness"].get<double>(), 0.5, 1e-6);
  ASSERT_EQ(m["sh9"]["coefficients"].size(), 9u);
  // SH irradiance: c0 Y00 = pi L.
  EXPECT_NEAR(m["sh9"]["coefficients"][0][1].get<double>() * 0.282095, kPi * L.y, 2e-3);
  EXPECT_NEAR(m["sh9"]["coefficients"][3][1].get<double>(), 0.0, 1e-3);
  EXPECT_TRUE(m["timings_s"].contains("total"));
  EXPECT_TRUE(m["timings_s"].contains("sheen"));
  // The sheen chain: every level the constant L (normalised Charlie prefilter); the manifest
  // lists each level; the LUT's KTX2 reads back.
  const Cubemap sheen = cubemap_from_ktx2(read_ktx2(dir / "out" / "sheen.ktx2"));
  ASSERT_EQ(sheen.levels(), m["sheen"]["levels"].get<int>());
  ASSERT_EQ(m["sheen"]["level_details"].size(), std::size_t(sheen.levels()));
  for (int l = 0; l < sheen.levels(); ++l)
    for (const Image& f : sheen.mips[l])
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(f.rgb(0, 0)[c] / L[c], 1.0f, 2e-3f);
  const Image sheen_lut = image_from_ktx2(read_ktx2(dir / "out" / "sheen_lut_f32.ktx2"));
  EXPECT_EQ(sheen_lut.width, m["sheen_lut"]["size"].get<int>());
  for (int i = 0; i < sheen_lut.width; ++i) {
    EXPECT_GT(sheen_lut.pixel(i, i)[0], 0.0f);
    EXPECT_LE(sheen_lut.pixel(i, i)[0], 1.0f);
  }
  EXPECT_EQ(m["validation"].size(), 2u);
}

TEST(BakeCli, Float32AndOrientation) {
  const fs::path dir = test::scratch_dir();
  // Red in the image's middle column band (which faces -Z), black elsewhere.
  Image img(64, 32, 3);
  for (int y = 8; y < 24; ++y)
    for (int x = 28; x < 36; ++x) img.set_rgb(x, y, {1, 0, 0});
  write_exr(dir / "mid.exr", img, ExrPixelType::kFloat);
  int code = 0;
  std::string log = bake(dir / "mid.exr", dir / "a", "--float32 --no-previews --no-exr", &code);
  ASSERT_EQ(code, 0) << log;
  const Ktx2Texture t = read_ktx2(dir / "a" / "specular.ktx2");
  EXPECT_EQ(t.format, Ktx2Format::kRgba32Float);
  EXPECT_FALSE(fs::exists(dir / "a" / "specular_mip0.exr"));
  const Cubemap cube = cubemap_from_ktx2(t);
  EXPECT_GT(sample_cubemap(cube, {0, 0, -1}).x, 0.5f);   // -Z sees the image centre
  EXPECT_LT(sample_cubemap(cube, {-1, 0, 0}).x, 0.01f);  // -X does not
  // --rotation 90 turns it to -X.
  log = bake(dir / "mid.exr", dir / "b", "--rotation 90 --no-previews --no-exr", &code);
  ASSERT_EQ(code, 0) << log;
  const Cubemap turned = cubemap_from_ktx2(read_ktx2(dir / "b" / "specular.ktx2"));
  EXPECT_GT(sample_cubemap(turned, {-1, 0, 0}).x, 0.5f);
  EXPECT_LT(sample_cubemap(turned, {0, 0, -1}).x, 0.01f);
}

TEST(BakeCli, BadInputFailsCleanlyNamingTheFile) {
  const fs::path dir = test::scratch_dir();
  int code = 0;
  // Missing file.
  std::string log = bake(dir / "nope.exr", dir / "o1", "", &code);
  EXPECT_NE(code, 0);
  EXPECT_NE(log.find("nope.exr"), std::string::npos) << log;
  // Not 2:1.
  const fs::path square = write_env(dir, "square.exr", 32, 32, glm::vec3(1.0f));
  log = bake(square, dir / "o2", "", &code);
  EXPECT_NE(code, 0);
  EXPECT_NE(log.find("square.exr"), std::string::npos) << log;
  EXPECT_NE(log.find("2:1"), std::string::npos) << log;
  EXPECT_TRUE(!fs::exists(dir / "o2") || fs::is_empty(dir / "o2"));
  // Not an image at all.
  { std::ofstream(dir / "junk.exr") << "this is not an EXR"; }
  log = bake(dir / "junk.exr", dir / "o3", "", &code);
  EXPECT_NE(code, 0);
  EXPECT_NE(log.find("junk.exr"), std::string::npos) << log;
  // Unwritable output: a regular file where the directory should be.
  const fs::path env = write_env(dir, "ok.exr", 64, 32, glm::vec3(1.0f));
  { std::ofstream(dir / "blocker") << "x"; }
  log = bake(env, dir / "blocker", "", &code);
  EXPECT_NE(code, 0);
  EXPECT_NE(log.find("blocker"), std::string::npos) << log;
  // Bad sizes.
  code = test::run_command(test::cli_path().string() + " bake " + env.string() + " -o " +
                               (dir / "o4").string() + " --size 100",
                           &log);
  EXPECT_NE(code, 0);
  EXPECT_NE(log.find("power of two"), std::string::npos) << log;
}

TEST(BakeCli, BadSizesAndCountsNameTheirFlag) {
  const fs::path dir = test::scratch_dir();
  const fs::path env = write_env(dir, "ok.exr", 64, 32, glm::vec3(1.0f));
  struct Case {
    const char* flags;
    const char* expected;
  };
  for (const Case& c : {
           Case{"--size 100", "--size: must be a power of two in 1..4096, got 100"},
           Case{"--size 16 --min-size 32",
                "--min-size: must be a power of two in 1..16 (the face size), got 32"},
           Case{"--samples 0", "--samples: must be in 1..1048576, got 0"},
           Case{"--irradiance-size 2000", "--irradiance-size: must be in 1..1024, got 2000"},
           Case{"--lut-size 0", "--lut-size: must be in 1..4096, got 0"},
       }) {
    std::string log;
    const int code = test::run_command(test::cli_path().string() + " bake " + env.string() +
                                           " -o " + (dir / "out").string() + " " + c.flags,
                                       &log);
    EXPECT_NE(code, 0) << c.flags;
    EXPECT_NE(log.find(c.expected), std::string::npos) << c.flags << ": " << log;
    // The CLI speaks in flags; the library's field names stay out of its messages.
    EXPECT_EQ(log.find("BakeOptions"), std::string::npos) << log;
    // Checked before anything is written.
    EXPECT_FALSE(fs::exists(dir / "out")) << c.flags;
  }
}

TEST(BakeCli, NonFinitePixelsAreClampedAndCounted) {
  const fs::path dir = test::scratch_dir();
  Image img(64, 32, 3, 1.0f);
  img.pixel(3, 3)[0] = std::numeric_limits<float>::quiet_NaN();
  img.pixel(4, 3)[1] = std::numeric_limits<float>::infinity();
  img.pixel(5, 3)[2] = -5.0f;
  write_exr(dir / "bad.exr", img, ExrPixelType::kFloat);
  int code = 0;
  const std::string log = bake(dir / "bad.exr", dir / "out", "--no-previews", &code);
  ASSERT_EQ(code, 0) << log;
  EXPECT_NE(log.find("bad.exr"), std::string::npos) << log;
  EXPECT_NE(log.find("1 negative"), std::string::npos) << log;
  const Cubemap cube = cubemap_from_ktx2(read_ktx2(dir / "out" / "specular.ktx2"));
  for (const auto& level : cube.mips)
    for (const Image& f : level)
      for (float v : f.data) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
}

}  // namespace
}  // namespace pbrkit
