// The GL renderer samples textures kept at their source's precision as the path tracer's
// lookups decode them: 8-bit colour uploaded as GL_SRGB8_ALPHA8 (decoded by GL), grey
// expanded to RGB, 16-bit data as GL_RGBA16. An unlit quad seen at one texel per pixel
// shows each texel, so every pixel is compared with the texel's CPU decode.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::gl {
namespace {

constexpr int kSize = 16;

// The largest |GL pixel - texel(0, x, y)| over the image, channel by channel (RGB).
float largest_difference(const Texture& texture) {
  testing::context();
  Scene scene;
  scene.source = "test:texture_upload";
  scene.textures.push_back(texture);
  Material m;
  m.unlit = true;
  m.base_color_texture.texture = 0;
  scene.materials.push_back(m);
  // make_quad's uv (0, 0) is the corner at (-1, 1): texel (x, y) lies under pixel (x, y).
  add_mesh_instance(scene, make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), 0);
  Camera camera;
  camera.type = Camera::Type::kOrthographic;
  camera.xmag = camera.ymag = 1.0f;
  camera.camera_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 5.0f));
  RenderSettings settings;
  settings.msaa = 1;
  settings.background.mode = Background::Mode::kColor;
  settings.background.color = glm::vec3(0.0f);
  const Image image = render_headless(scene, camera, kSize, kSize, nullptr, nullptr, settings);
  float largest = 0.0f;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec3 want(texture.texel(0, x, y));
      const glm::vec3 got = image.rgb(x, y);
      for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(got[c] - want[c]));
    }
  return largest;
}

std::vector<std::uint8_t> random_bytes(std::size_t n) {
  std::mt19937 rng(11);
  std::vector<std::uint8_t> bytes(n);
  for (std::uint8_t& b : bytes) b = std::uint8_t(rng() & 0xff);
  return bytes;
}

// GL may decode sRGB approximately (llvmpipe's decode was measured up to 1.2e-3 off near 1,
// a seventh of the 8-bit step there); a texel read from the wrong place, not decoded (0.5
// instead of 0.21 at mid-grey) or left unexpanded (green and blue 0) is off by far more.
constexpr float kTolerance = 2e-3f;

TEST(GlTextures, EightBitSrgbRgbIsDecodedAsTheLookupsDecodeIt) {
  const std::size_t n = std::size_t(kSize) * kSize;
  EXPECT_LT(largest_difference(Texture::from_unorm8(kSize, kSize, 3, random_bytes(n * 3), true)),
            kTolerance);
}

TEST(GlTextures, EightBitGreyAlphaExpandsToRgb) {
  const std::size_t n = std::size_t(kSize) * kSize;
  EXPECT_LT(largest_difference(Texture::from_unorm8(kSize, kSize, 2, random_bytes(n * 2), true)),
            kTolerance);
}

TEST(GlTextures, SixteenBitDataKeepsItsValues) {
  const std::size_t n = std::size_t(kSize) * kSize;
  std::vector<std::uint16_t> samples(n * 4);
  std::mt19937 rng(5);
  for (std::uint16_t& s : samples) s = std::uint16_t(rng() & 0xffff);
  EXPECT_LT(largest_difference(Texture::from_unorm16(kSize, kSize, 4, samples, false)), kTolerance);
}

}  // namespace
}  // namespace pbrkit::gl
