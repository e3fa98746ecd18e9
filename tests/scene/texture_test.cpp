// Texture filtering against hand-computed values: uv origin top-left, texel centres at
// (i + 0.5) / size, wrap modes, box-filtered mips, and KHR_texture_transform's example.
#include <gtest/gtest.h>

#include "pbrkit/scene/scene.h"

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
  Texture t;
  t.mips = make_mip_chain(img);
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
  ASSERT_EQ(t.mips.size(), 3u);  // 4x2, 2x1, 1x1
  EXPECT_EQ(t.mips[1].width, 2);
  EXPECT_EQ(t.mips[1].height, 1);
  EXPECT_EQ(t.mips[2].width, 1);
  EXPECT_EQ(t.mips[2].height, 1);
  // Level 1 texel 0 averages x in {0,1}, y in {0,1}: b = (0 + 1 + 10 + 11) / 4.
  EXPECT_FLOAT_EQ(t.mips[1].pixel(0, 0)[2], 5.5f);
  // The 1x1 level is the mean of the whole image.
  EXPECT_FLOAT_EQ(t.mips[2].pixel(0, 0)[0], 1.5f);
  EXPECT_FLOAT_EQ(t.mips[2].pixel(0, 0)[1], 0.5f);
  // Trilinear: lod 2 gives the mean everywhere, lod 0.5 blends levels 0 and 1.
  EXPECT_FLOAT_EQ(t.sample({0.9f, 0.1f}, 2.0f).r, 1.5f);
  const float l0 = t.sample({0.125f, 0.25f}, 0.0f).b;
  const float l1 = t.sample({0.125f, 0.25f}, 1.0f).b;  // level 1 alone, wrapping across the seam
  EXPECT_FLOAT_EQ(l1, 0.75f * 5.5f + 0.25f * 25.5f);
  EXPECT_NEAR(t.sample({0.125f, 0.25f}, 0.5f).b, 0.5f * (l0 + l1), 1e-5f);
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
