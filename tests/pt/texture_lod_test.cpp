// Ray-cone texture level of detail (Akenine-Moller et al., "Improved Shader and Texture Level
// of Detail Using Ray Cones", JCGT 2021): a fine checker receding to the horizon is filtered
// to its mean at a few samples per pixel, and a texture seen at one texel per pixel is read
// at level 0. Unlit materials show the looked-up colour itself, so the only noise is the
// pixel filter's.
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit {
namespace {

PathTracerSettings settings(int size, std::uint32_t spp, bool lod) {
  PathTracerSettings s;
  s.width = s.height = size;
  s.spp = spp;
  s.noise_threshold = 0.0f;
  s.checkpoint_interval = 0.0;
  s.threads = 2;
  s.texture_lod = lod;
  return s;
}

// An unlit material showing texture 0.
int add_unlit_textured(Scene& scene) {
  Material m;
  m.unlit = true;
  m.base_color_texture.texture = 0;
  scene.materials.push_back(m);
  return int(scene.materials.size()) - 1;
}

// The ground plane y = 0, 400 x 400 around the origin, its uv repeating `repeats` times,
// under a 256 x 256 8-bit sRGB checker of single texels (bytes 0 and 255: linear 0 and 1,
// mean 0.5).
constexpr float kPlaneHalf = 200.0f;
constexpr float kRepeats = 200.0f;
constexpr int kCheckerSize = 256;

Scene checker_plane() {
  Scene scene;
  scene.source = "test:checker_plane";
  std::vector<std::uint8_t> bytes(std::size_t(kCheckerSize) * kCheckerSize);
  for (int y = 0; y < kCheckerSize; ++y)
    for (int x = 0; x < kCheckerSize; ++x)
      bytes[std::size_t(y * kCheckerSize + x)] = (x + y) % 2 == 0 ? 0 : 255;
  scene.textures.push_back(
      Texture::from_unorm8(kCheckerSize, kCheckerSize, 1, std::move(bytes), true));
  Mesh plane = make_quad({-kPlaneHalf, 0.0f, kPlaneHalf}, {2.0f * kPlaneHalf, 0.0f, 0.0f},
                         {0.0f, 0.0f, -2.0f * kPlaneHalf});
  for (glm::vec2& uv : plane.texcoords0) uv *= kRepeats;
  add_mesh_instance(scene, std::move(plane), add_unlit_textured(scene));
  return scene;
}

// A pinhole 1 unit above the plane, looking along -Z pitched 0.15 rad down (yfov 0.6): the
// nearest ground it sees is 2.3 units away, where a pixel of a 48-pixel image spans about
// 4 texels across and 9 along the view; the horizon is in the upper half.
Camera grazing_camera() {
  Camera c;
  c.yfov = 0.6f;
  c.camera_to_world = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f)),
                                  -0.15f, glm::vec3(1.0f, 0.0f, 0.0f));
  return c;
}

// Pixels whose whole filter support (the tent's 1 pixel around the centre, and a margin)
// sees the plane within 60 units, well inside its edges (directly, or with `mirror`, after
// the mirror y = 2 above it): their pixel integral is the checker's mean, 0.5.
std::vector<std::size_t> far_field_pixels(const Camera& camera, int size, bool mirror = false) {
  std::vector<std::size_t> pixels;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      bool inside = true;
      for (float dy : {-1.5f, 1.5f})
        for (float dx : {-1.5f, 1.5f}) {
          const glm::vec2 ndc((x + 0.5f + dx) / float(size) * 2.0f - 1.0f,
                              1.0f - (y + 0.5f + dy) / float(size) * 2.0f);
          const Ray r = generate_ray(camera, 1.0f, ndc);
          const float t = mirror ? (r.direction.y > 0.0f ? 3.0f / r.direction.y : -1.0f)
                                 : (r.direction.y < 0.0f ? -r.origin.y / r.direction.y : -1.0f);
          inside = inside && t > 0.0f && t < 60.0f;
        }
      if (inside) pixels.push_back(std::size_t(y * size + x));
    }
  return pixels;
}

double red(const Image& image, std::size_t i) {
  return double(image.data[i * std::size_t(image.channels)]);
}

// Mean |pixel - centre| over `pixels` (red channel; the checker is grey).
double mean_deviation(const Image& image, const std::vector<std::size_t>& pixels,
                      double centre = 0.5) {
  double sum = 0.0;
  for (std::size_t i : pixels) sum += std::abs(red(image, i) - centre);
  return sum / double(pixels.size());
}

TEST(TextureLod, GrazingCheckerConvergesToItsMeanAtFourSamples) {
  const Scene scene = checker_plane();
  const Camera camera = grazing_camera();
  const int size = 48;
  const std::vector<std::size_t> pixels = far_field_pixels(camera, size);
  ASSERT_GT(pixels.size(), std::size_t(size * size / 4));  // the lower half at least
  const Image filtered = render_path(scene, nullptr, camera, settings(size, 4, true)).color;
  // Every footprint spans several texels: level >= 2, where the checker is 0.5 to 8-bit
  // sRGB quantisation (byte 188: 0.503).
  EXPECT_LT(mean_deviation(filtered, pixels), 0.01);
  // Without filtering each sample is one bilinear point of the checker (0.5 +- 0.17), and
  // four of them leave about +-0.08: the aliased image the level of detail removes.
  const Image aliased = render_path(scene, nullptr, camera, settings(size, 4, false)).color;
  EXPECT_GT(mean_deviation(aliased, pixels), 0.04);
}

TEST(TextureLod, TheConePassesThroughAMirror) {
  // The checker seen in a mirror-smooth metal ceiling y = 2 (its lobe is far narrower than
  // a pixel's cone): the reflected floor is as far away as the direct one and is filtered
  // the same way.
  Scene scene = checker_plane();
  Material mirror;
  mirror.metallic_factor = 1.0f;
  mirror.roughness_factor = 0.0f;
  scene.materials.push_back(mirror);
  add_mesh_instance(scene,
                    make_quad({-kPlaneHalf, 2.0f, kPlaneHalf}, {0.0f, 0.0f, -2.0f * kPlaneHalf},
                              {2.0f * kPlaneHalf, 0.0f, 0.0f}),
                    int(scene.materials.size()) - 1);
  Camera camera = grazing_camera();
  camera.camera_to_world = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f)),
                                       0.15f, glm::vec3(1, 0, 0));
  const int size = 48;
  const std::vector<std::size_t> pixels = far_field_pixels(camera, size, true);
  ASSERT_GT(pixels.size(), std::size_t(size * size / 4));
  const Image filtered = render_path(scene, nullptr, camera, settings(size, 4, true)).color;
  // The mirror's reflectance (about 1) scales the mean; the spread around it is the test.
  double mean = 0.0;
  for (std::size_t i : pixels) mean += red(filtered, i) / double(pixels.size());
  EXPECT_NEAR(mean, 0.5, 0.05);
  EXPECT_LT(mean_deviation(filtered, pixels, mean), 0.01);
  const Image aliased = render_path(scene, nullptr, camera, settings(size, 4, false)).color;
  EXPECT_GT(mean_deviation(aliased, pixels, mean), 0.04);
}

TEST(TextureLod, OneTexelPerPixelReadsLevelZero) {
  // An orthographic view of a 2 x 2 quad, 32 x 32 pixels, under a 32 x 32 texture of random
  // bytes: a pixel is a texel, so the level of detail is 0 and the image is level 0's. Any
  // other level averages neighbouring random texels and moves pixels by about 0.1.
  Scene scene;
  scene.source = "test:one_texel_per_pixel";
  const int size = 32;
  std::mt19937 rng(7);
  std::vector<std::uint8_t> bytes(std::size_t(size) * size * 3);
  for (std::uint8_t& b : bytes) b = std::uint8_t(rng() & 0xff);
  scene.textures.push_back(Texture::from_unorm8(size, size, 3, std::move(bytes), true));
  add_mesh_instance(scene, make_quad({-1.0f, -1.0f, 0.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f}),
                    add_unlit_textured(scene));
  Camera camera;
  camera.type = Camera::Type::kOrthographic;
  camera.xmag = camera.ymag = 1.0f;
  camera.camera_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 5.0f));
  const Image lod = render_path(scene, nullptr, camera, settings(size, 8, true)).color;
  const Image level0 = render_path(scene, nullptr, camera, settings(size, 8, false)).color;
  // The same samples (same seed) through the same texels: equal to float rounding, far
  // inside the pixel noise (the texture's own contrast, about 0.3 per sample).
  double max_diff = 0.0;
  for (std::size_t i = 0; i < lod.data.size(); ++i)
    max_diff = std::max(max_diff, std::abs(double(lod.data[i]) - double(level0.data[i])));
  EXPECT_LT(max_diff, 1e-3);
  // The test can tell: a 16-pixel image has two texels per pixel, level 1, which differs.
  const Image small_lod = render_path(scene, nullptr, camera, settings(16, 8, true)).color;
  const Image small_level0 = render_path(scene, nullptr, camera, settings(16, 8, false)).color;
  double small_diff = 0.0;
  for (std::size_t i = 0; i < small_lod.data.size(); ++i)
    small_diff += std::abs(double(small_lod.data[i]) - double(small_level0.data[i]));
  EXPECT_GT(small_diff / double(small_lod.data.size()), 0.01);
}

}  // namespace
}  // namespace pbrkit
