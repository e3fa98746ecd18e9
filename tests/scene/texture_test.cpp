// Texture filtering against hand-computed values: uv origin top-left, texel centres at
// (i + 0.5) / size, wrap modes, box-filtered mips, and KHR_texture_transform's example.
#include <gtest/gtest.h>

#include <cmath>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/scene.h"
#include "pbrkit/util/error.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

// 4 x 2 texture whose texel (x, y) holds (x, y, 10 * x + y, 1).
Texture ramp(WrapMode wrap = WrapMode::kRepeat) {
  Image img(4, 2, 4);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      float* p = img.pixel(x, y);
      p[0] = float(x);
      p[1] = float(y);
      p[2] = float(10 * x + y);
      p[3] = 1.0f;
    }
  Texture t = Texture::from_linear(img, false);
  t.sampler.wrap_s = t.sampler.wrap_t = wrap;
  return t;
}

TEST(Texture, TexelCentresReturnTheTexel) {
  const Texture t = ramp();
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const glm::vec4 v = t.sample({(x + 0.5f) / 4.0f, (y + 0.5f) / 2.0f});
      EXPECT_FLOAT_EQ(v.b, float(10 * x + y));
    }
  // Top-left origin: v = 0.25 is the first (top) row.
  EXPECT_FLOAT_EQ(t.sample({0.125f, 0.25f}).g, 0.0f);
}

TEST(Texture, BilinearBetweenTexels) {
  const Texture t = ramp(WrapMode::kClampToEdge);
  // Halfway between texel columns 1 and 2 on the top row.
  EXPECT_FLOAT_EQ(t.sample({0.5f, 0.25f}).r, 1.5f);
  // A quarter of the way from row 0 to row 1.
  EXPECT_NEAR(t.sample({0.375f, 0.25f + 0.125f}).g, 0.25f, 1e-6f);
}

TEST(Texture, WrapModes) {
  const Texture repeat = ramp(WrapMode::kRepeat);
  const Texture clamp = ramp(WrapMode::kClampToEdge);
  const Texture mirror = ramp(WrapMode::kMirroredRepeat);
  // u = 1.125 is texel 0 again when repeating, the last texel when clamped, and texel 3
  // (mirrored) when mirrored.
  EXPECT_FLOAT_EQ(repeat.sample({1.125f, 0.25f}).r, 0.0f);
  EXPECT_FLOAT_EQ(clamp.sample({1.125f, 0.25f}).r, 3.0f);
  EXPECT_FLOAT_EQ(mirror.sample({1.125f, 0.25f}).r, 3.0f);
  EXPECT_FLOAT_EQ(mirror.sample({1.375f, 0.25f}).r, 2.0f);
  EXPECT_FLOAT_EQ(repeat.sample({-0.875f, 0.25f}).r, 0.0f);
  // Bilinear across the repeat seam mixes the last and first texels.
  EXPECT_FLOAT_EQ(repeat.sample({0.0f, 0.25f}).r, 1.5f);
  // Nearest filtering.
  Texture nearest = ramp();
  nearest.sampler.mag = FilterMode::kNearest;
  EXPECT_FLOAT_EQ(nearest.sample({0.49f, 0.25f}).r, 1.0f);
  // Non-finite coordinates never crash or produce NaN.
  const glm::vec4 v = repeat.sample({std::nanf(""), 1e30f});
  EXPECT_TRUE(std::isfinite(v.r) && std::isfinite(v.g));
}

TEST(Texture, MipChainIsABoxFilterDownToOnePixel) {
  const Texture t = ramp();
  ASSERT_EQ(t.levels.size(), 3u);  // 4x2, 2x1, 1x1
  EXPECT_EQ(t.levels[1].width, 2);
  EXPECT_EQ(t.levels[1].height, 1);
  EXPECT_EQ(t.levels[2].width, 1);
  EXPECT_EQ(t.levels[2].height, 1);
  // Level 1 texel 0 averages x in {0,1}, y in {0,1}: b = (0 + 1 + 10 + 11) / 4.
  EXPECT_FLOAT_EQ(t.texel(1, 0, 0).b, 5.5f);
  // The 1x1 level is the mean of the whole image.
  EXPECT_FLOAT_EQ(t.texel(2, 0, 0).r, 1.5f);
  EXPECT_FLOAT_EQ(t.texel(2, 0, 0).g, 0.5f);
  // Trilinear: lod 2 gives the mean everywhere, lod 0.5 blends levels 0 and 1.
  EXPECT_FLOAT_EQ(t.sample({0.9f, 0.1f}, 2.0f).r, 1.5f);
  const float l0 = t.sample({0.125f, 0.25f}, 0.0f).b;
  const float l1 = t.sample({0.125f, 0.25f}, 1.0f).b;  // level 1 alone, wrapping across the seam
  EXPECT_FLOAT_EQ(l1, 0.75f * 5.5f + 0.25f * 25.5f);
  EXPECT_NEAR(t.sample({0.125f, 0.25f}, 0.5f).b, 0.5f * (l0 + l1), 1e-5f);
}

// IEC 61966-2-1's decode, written out here rather than taken from core/color.h.
double srgb_to_linear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// A 16 x 16 RGBA8 texture whose texel i = 16 y + x holds bytes (i, 255 - i, i / 2, i).
Texture bytes_ramp(bool srgb) {
  std::vector<std::uint8_t> bytes(16 * 16 * 4);
  for (int i = 0; i < 256; ++i) {
    bytes[std::size_t(4 * i)] = std::uint8_t(i);
    bytes[std::size_t(4 * i + 1)] = std::uint8_t(255 - i);
    bytes[std::size_t(4 * i + 2)] = std::uint8_t(i / 2);
    bytes[std::size_t(4 * i + 3)] = std::uint8_t(i);
  }
  Texture t = Texture::from_unorm8(16, 16, 4, std::move(bytes), srgb);
  t.sampler.wrap_s = t.sampler.wrap_t = WrapMode::kClampToEdge;
  return t;
}

TEST(Texture, EightBitSrgbLookupIsTheExactDecodeOfTheByte) {
  const Texture t = bytes_ramp(true);
  EXPECT_EQ(t.format, TexelFormat::kUnorm8);
  for (int i = 0; i < 256; ++i) {
    const glm::vec4 v = t.sample({(i % 16 + 0.5f) / 16.0f, (i / 16 + 0.5f) / 16.0f});
    EXPECT_NEAR(v.r, srgb_to_linear(i / 255.0), 1e-6) << i;
    EXPECT_NEAR(v.g, srgb_to_linear((255 - i) / 255.0), 1e-6) << i;
    EXPECT_NEAR(v.b, srgb_to_linear((i / 2) / 255.0), 1e-6) << i;
    EXPECT_NEAR(v.a, i / 255.0, 1e-6) << i;  // alpha is linear (glTF 2.0 section 3.9.2)
  }
}

TEST(Texture, EightBitDataLookupIsTheUnormValue) {
  const Texture t = bytes_ramp(false);
  for (int i = 0; i < 256; i += 5) {
    const glm::vec4 v = t.texel(0, i % 16, i / 16);
    EXPECT_NEAR(v.r, i / 255.0, 1e-7) << i;
    EXPECT_NEAR(v.g, (255 - i) / 255.0, 1e-7) << i;
  }
}

TEST(Texture, BilinearOfTwoSrgbTexelsIsTheMeanOfTheirDecodedValues) {
  const Texture t = bytes_ramp(true);
  // Halfway between texels 3 and 4 of the top row (bytes 3 and 4, 252 and 251, ...).
  const glm::vec4 v = t.sample({4.0f / 16.0f, 0.5f / 16.0f});
  EXPECT_NEAR(v.r, 0.5 * (srgb_to_linear(3 / 255.0) + srgb_to_linear(4 / 255.0)), 1e-6);
  EXPECT_NEAR(v.g, 0.5 * (srgb_to_linear(252 / 255.0) + srgb_to_linear(251 / 255.0)), 1e-6);
  // Between rows 0 and 1 of column 0: bytes 0 and 16.
  const glm::vec4 w = t.sample({0.5f / 16.0f, 1.0f / 16.0f});
  EXPECT_NEAR(w.r, 0.5 * (srgb_to_linear(0.0) + srgb_to_linear(16 / 255.0)), 1e-6);
}

TEST(Texture, SrgbMipsAverageInLinearSpace) {
  // A 2 x 2 checker of bytes 0 and 255: the linear mean is 0.5 (byte 188 after re-encoding,
  // within 8-bit quantisation), while averaging the encoded bytes would give 127.5, i.e.
  // 0.21 linear.
  std::vector<std::uint8_t> bytes = {0, 255, 255, 0};
  const Texture colour = Texture::from_unorm8(2, 2, 1, bytes, true);
  ASSERT_EQ(colour.levels.size(), 2u);
  EXPECT_NEAR(colour.texel(1, 0, 0).r, 0.5f, 0.004f);  // half an sRGB step at 0.5 is 0.003
  // Data textures average the values themselves: 127.5 rounds to 128.
  const Texture data = Texture::from_unorm8(2, 2, 1, bytes, false);
  EXPECT_NEAR(data.texel(1, 0, 0).r, 128.0f / 255.0f, 1e-6f);
  // Grey expands to RGB with alpha 1.
  EXPECT_EQ(data.texel(0, 1, 0), glm::vec4(1.0f));
}

TEST(Texture, SixteenBitKeepsSixteenBits) {
  const std::vector<std::uint16_t> samples = {0, 1, 32768, 65535};
  const Texture data = Texture::from_unorm16(2, 2, 1, samples, false);
  EXPECT_EQ(data.format, TexelFormat::kUnorm16);
  EXPECT_NEAR(data.texel(0, 1, 0).r, 1.0 / 65535.0, 1e-9);
  EXPECT_NEAR(data.texel(0, 0, 1).r, 32768.0 / 65535.0, 1e-7);
  const Texture colour = Texture::from_unorm16(2, 2, 1, samples, true);
  EXPECT_NEAR(colour.texel(0, 0, 1).r, srgb_to_linear(32768.0 / 65535.0), 1e-6);
  EXPECT_LE(data.bytes(), std::size_t(2 * 4 + 2 + 64));  // 2 bytes a sample, plus two levels
}

TEST(Texture, EightBitRgbCostsAtMostSixBytesPerTexelWithMips) {
  const int size = 256;
  std::vector<std::uint8_t> rgb(std::size_t(size) * size * 3, 128);
  const Texture t = Texture::from_unorm8(size, size, 3, std::move(rgb), true);
  const double per_texel = double(t.bytes()) / (double(size) * size);
  EXPECT_LE(per_texel, 6.0);
  EXPECT_GE(per_texel, 4.0);  // 3 bytes x 4/3: the mips are all there
  EXPECT_EQ(t.levels.size(), 9u);
  std::vector<std::uint8_t> rgba(std::size_t(size) * size * 4, 128);
  const Texture t4 = Texture::from_unorm8(size, size, 4, std::move(rgba), true);
  EXPECT_LE(double(t4.bytes()) / (double(size) * size), 5.34);  // 4 bytes x 4/3
}

TEST(Texture, ImageTooLargeForTheTextureBudgetNamesTheFileAndImage) {
  // textured_quad.gltf's 4 x 4 image needs more than 16 bytes with its mips.
  LoadOptions tight;
  tight.limits.max_total_texture_bytes = 16;
  try {
    load_scene(test::test_data("gltf/valid/textured_quad.gltf").string(), tight);
    FAIL() << "loaded";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("textured_quad.gltf"), std::string::npos) << what;
    EXPECT_NE(what.find("images[0]"), std::string::npos) << what;
    EXPECT_NE(what.find("limit of 16 bytes"), std::string::npos) << what;
  }
}

TEST(TextureTransform, SpecExampleSelectsTheLowerLeftQuadrant) {
  // KHR_texture_transform README: offset [0, 1], rotation pi/2, scale [0.5, 0.5] "utilizes
  // only the lower left quadrant of the source image, rotated clockwise 90 degrees".
  TextureTransform tt;
  tt.offset = {0.0f, 1.0f};
  tt.rotation = 1.57079632679f;
  tt.scale = {0.5f, 0.5f};
  const glm::mat3 m = tt.matrix();
  auto apply = [&](glm::vec2 uv) { return glm::vec2(m * glm::vec3(uv, 1.0f)); };
  const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const glm::vec2 expected[4] = {{0, 1}, {0, 0.5f}, {0.5f, 1}, {0.5f, 0.5f}};
  for (int i = 0; i < 4; ++i) {
    const glm::vec2 p = apply(corners[i]);
    EXPECT_NEAR(p.x, expected[i].x, 1e-6f) << i;
    EXPECT_NEAR(p.y, expected[i].y, 1e-6f) << i;
  }
  // The second example (offset [0, 1], scale [1, -1]) flips T.
  TextureTransform flip;
  flip.offset = {0.0f, 1.0f};
  flip.scale = {1.0f, -1.0f};
  const glm::vec2 q = glm::vec2(flip.matrix() * glm::vec3(0.25f, 0.2f, 1.0f));
  EXPECT_NEAR(q.x, 0.25f, 1e-6f);
  EXPECT_NEAR(q.y, 0.8f, 1e-6f);
}

}  // namespace
}  // namespace pbrkit
