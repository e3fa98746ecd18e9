// The raster view's debug channels (gl/debug_channels.h) against closed forms: the input
// channels show the material's factors and textures exactly, the shading normal facing
// the camera is (0.5, 0.5, 1); the lobe channels sum to the shaded colour less the
// emission, each lobe is zero where the material has none of it, and a white Lambertian
// sphere's diffuse channel is its irradiance over pi.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gl_image_test_util.h"
#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/util/error.h"
#include "support/test_paths.h"

namespace pbrkit::gl {
namespace {

// Odd: the centre pixel's ray is the camera's axis, which meets the sphere at (0, 0, 1).
constexpr int kSize = 33;

struct Lighting {
  const Environment* env = nullptr;
  const IblMaps* maps = nullptr;
};

// A black background: the surfaces' values alone.
RenderSettings black_background() {
  RenderSettings settings;
  settings.background.mode = Background::Mode::kColor;
  settings.background.color = glm::vec3(0.0f);
  return settings;
}

// Renders `scene` once per channel in one renderer (one upload), no MSAA (a pixel is one
// fragment's value, not a mix of the silhouette's).
std::vector<Image> render_channels(const Scene& scene, const Camera& camera, int width, int height,
                                   const std::vector<DebugChannel>& channels,
                                   Lighting lighting = {},
                                   RenderSettings settings = black_background()) {
  testing::context();
  Renderer renderer;
  renderer.set_scene(scene);
  renderer.set_environment(lighting.env);
  renderer.set_ibl(lighting.maps);
  settings.msaa = 1;
  std::vector<Image> images;
  for (DebugChannel c : channels) {
    settings.debug_channel = c;
    renderer.render(camera, width, height, settings);
    images.push_back(renderer.read_back());
  }
  return images;
}

Scene sphere_scene(const Material& m) {
  Scene scene = builtin_scene("furnace");  // a unit sphere at the origin, camera at +Z 4
  scene.materials.at(0) = m;
  return scene;
}

// The pixels whose ray meets the unit sphere at n.v >= 0.3 (away from the silhouette,
// where a pixel's fragment may come from a facet the analytic sphere does not have).
std::vector<std::pair<int, int>> sphere_pixels(const Camera& camera) {
  std::vector<std::pair<int, int>> pixels;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const auto mu = testing::sphere_hit_cosine(testing::pixel_ray(camera, x, y, kSize, kSize),
                                                 glm::vec3(0.0f), 1.0f);
      if (mu && *mu >= 0.3f) pixels.emplace_back(x, y);
    }
  return pixels;
}

TEST(GlDebugChannels, NamesRoundTripAndUnknownNamesAreErrors) {
  for (const std::string& name : debug_channel_names())
    EXPECT_EQ(debug_channel_name(parse_debug_channel(name)), name);
  EXPECT_EQ(parse_debug_channel("base-color"), DebugChannel::kBaseColor);
  EXPECT_THROW(parse_debug_channel("albedo"), Error);
  EXPECT_TRUE(is_lobe_channel(DebugChannel::kSheen));
  EXPECT_FALSE(is_lobe_channel(DebugChannel::kEmissive));
}

TEST(GlDebugChannels, InputChannelsShowTheMaterialFactors) {
  Material m;
  m.base_color_factor = glm::vec4(0.2f, 0.5f, 0.8f, 1.0f);
  m.metallic_factor = 0.3f;
  m.roughness_factor = 0.6f;
  m.emissive_factor = glm::vec3(0.1f, 0.2f, 0.3f);
  m.emissive_strength = 2.0f;
  const Scene scene = sphere_scene(m);
  const Camera camera = select_camera(scene, std::nullopt, 1.0f);
  const auto images =
      render_channels(scene, camera, kSize, kSize,
                      {DebugChannel::kBaseColor, DebugChannel::kMetallic, DebugChannel::kRoughness,
                       DebugChannel::kNormal, DebugChannel::kOcclusion, DebugChannel::kEmissive});
  // Factors pass through the shader untouched (no lighting, exposure or tone map): exact up
  // to float32 rounding.
  constexpr float kExact = 1e-6f;
  const std::array<glm::vec3, 6> want = {
      glm::vec3(0.2f, 0.5f, 0.8f), glm::vec3(0.3f), glm::vec3(0.6f),
      glm::vec3(0.5f, 0.5f, 1.0f), glm::vec3(1.0f), glm::vec3(0.2f, 0.4f, 0.6f)};
  const auto pixels = sphere_pixels(camera);
  ASSERT_GT(pixels.size(), 200u);
  for (std::size_t c = 0; c < images.size(); ++c) {
    if (c == 3) continue;  // the normal varies over the sphere
    for (auto [x, y] : pixels)
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(images[c].rgb(x, y)[k], want[c][k], kExact) << "channel " << c;
  }
  // The normal at the centre: the UV sphere has a vertex at (0, 0, 1) (its seam faces +Z),
  // whose interpolated normal is exact; the pixel centre lies within float rounding of it.
  const glm::vec3 n = images[3].rgb(kSize / 2, kSize / 2);
  EXPECT_NEAR(n.x, 0.5f, 1e-3f);
  EXPECT_NEAR(n.y, 0.5f, 1e-3f);
  EXPECT_NEAR(n.z, 1.0f, 1e-3f);
  // Elsewhere n * 0.5 + 0.5 is the sphere's normal at the pixel's hit, to the tessellation's
  // error: the interpolated normal of 64 x 32 facets is within 2 degrees of the sphere's.
  for (auto [x, y] : pixels) {
    const Ray ray = testing::pixel_ray(camera, x, y, kSize, kSize);
    const glm::vec3 oc = ray.origin;
    const float b = glm::dot(oc, ray.direction);
    const float t = -b - std::sqrt(b * b - glm::dot(oc, oc) + 1.0f);
    const glm::vec3 normal = glm::normalize(ray.origin + t * ray.direction);
    const glm::vec3 got = images[3].rgb(x, y) * 2.0f - 1.0f;
    ASSERT_GT(glm::dot(glm::normalize(got), normal), std::cos(glm::radians(2.0f))) << x << "," << y;
  }
}

TEST(GlDebugChannels, InputChannelsFollowTheTextures) {
  // BoxTextured's base colour texture (8-bit sRGB), and a linear copy of it as the
  // metallic-roughness and occlusion maps, on a quad that puts texel (x, y) under pixel
  // (x, y) (make_quad's uv (0, 0) is its corner at (-1, 1)).
  const Scene box = load_scene(test::shared_asset("models/BoxTextured/BoxTextured.glb").string());
  ASSERT_FALSE(box.textures.empty());
  const Texture& srgb = box.textures[0];
  ASSERT_TRUE(srgb.srgb);
  Texture linear = srgb;
  linear.srgb = false;
  const int w = srgb.width(), h = srgb.height();
  ASSERT_GE(w, 16);
  ASSERT_GE(h, 16);

  Scene scene;
  scene.source = "test:debug_channel_textures";
  scene.textures = {srgb, linear};
  Material m;
  m.base_color_factor = glm::vec4(1.0f, 0.5f, 0.25f, 1.0f);
  m.base_color_texture.texture = 0;
  m.metallic_factor = 0.8f;
  m.roughness_factor = 0.5f;
  m.metallic_roughness_texture.texture = 1;
  m.occlusion_texture.texture = 1;
  m.occlusion_strength = 0.5f;
  m.emissive_factor = glm::vec3(0.5f, 1.0f, 0.25f);
  m.emissive_texture.texture = 0;
  scene.materials.push_back(m);
  add_mesh_instance(scene, make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), 0);
  Camera camera;
  camera.type = Camera::Type::kOrthographic;
  camera.xmag = camera.ymag = 1.0f;
  camera.camera_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 5.0f));
  const auto images =
      render_channels(scene, camera, w, h,
                      {DebugChannel::kBaseColor, DebugChannel::kMetallic, DebugChannel::kRoughness,
                       DebugChannel::kOcclusion, DebugChannel::kEmissive});
  // GL's sRGB decode was measured up to 1.2e-3 off on llvmpipe (textures_test.cpp); linear
  // 8-bit texels are exact. A texel from the wrong place or the wrong channel is off by
  // one 8-bit step at least across the logo's edges.
  constexpr float kSrgb = 2e-3f, kLinear = 1e-5f;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec4 c = srgb.texel(0, x, y), l = linear.texel(0, x, y);
      const glm::vec3 base = glm::vec3(c) * glm::vec3(1.0f, 0.5f, 0.25f);
      const glm::vec3 emissive = glm::vec3(c) * glm::vec3(0.5f, 1.0f, 0.25f);
      for (int k = 0; k < 3; ++k) {
        ASSERT_NEAR(images[0].rgb(x, y)[k], base[k], kSrgb) << x << "," << y;
        ASSERT_NEAR(images[1].rgb(x, y)[k], 0.8f * l.b, kLinear) << x << "," << y;
        ASSERT_NEAR(images[2].rgb(x, y)[k], 0.5f * l.g, kLinear) << x << "," << y;
        ASSERT_NEAR(images[3].rgb(x, y)[k], 1.0f + 0.5f * (l.r - 1.0f), kLinear) << x << "," << y;
        ASSERT_NEAR(images[4].rgb(x, y)[k], emissive[k], kSrgb) << x << "," << y;
      }
    }
}

// The lit setting of the lobe tests: an environment brighter above than below (so every
// lobe's split sum sees a different light) and a directional light from the upper left.
struct LobeLighting {
  Environment env = Environment::constant(glm::vec3(1.0f), 16);
  IblMaps maps;
  LobeLighting() {
    for (int y = 0; y < env.map.height; ++y)
      for (int x = 0; x < env.map.width; ++x)
        env.map.set_rgb(x, y,
                        glm::vec3(0.2f, 0.3f, 0.4f) + glm::vec3(1.5f, 1.2f, 1.0f) *
                                                          float(env.map.height - y) /
                                                          float(env.map.height));
    maps = testing::small_ibl_maps(env);
  }
};

void add_light(Scene& scene) {
  Light light;
  light.type = Light::Type::kDirectional;
  light.intensity = 2.0f;
  light.direction = glm::normalize(glm::vec3(0.4f, -0.5f, -1.0f));
  scene.lights.push_back(light);
}

const std::vector<DebugChannel> kLobes = {DebugChannel::kDiffuse, DebugChannel::kSpecular,
                                          DebugChannel::kClearcoat, DebugChannel::kSheen,
                                          DebugChannel::kTransmission};

// `channels` of the sphere of material `m` in the lit setting, the environment behind it
// (what the transmission lobe sees through the sphere), the reference model.
std::vector<Image> render_lit(const Material& m, const LobeLighting& lighting,
                              const std::vector<DebugChannel>& channels) {
  Scene scene = sphere_scene(m);
  add_light(scene);
  const Camera camera = select_camera(scene, std::nullopt, 1.0f);
  RenderSettings settings;
  settings.brdf.model = BrdfModel::kReference;  // its specular weight 0 removes the specular
  return render_channels(scene, camera, kSize, kSize, channels, {&lighting.env, &lighting.maps},
                         settings);
}

Material layered_material() {
  Material m;
  m.base_color_factor = glm::vec4(0.8f, 0.3f, 0.2f, 1.0f);
  m.metallic_factor = 0.2f;
  m.roughness_factor = 0.4f;
  m.emissive_factor = glm::vec3(0.05f, 0.1f, 0.02f);
  m.clearcoat = ClearcoatExtension{};
  m.clearcoat->factor = 0.7f;
  m.clearcoat->roughness_factor = 0.2f;
  m.sheen = SheenExtension{};
  m.sheen->color_factor = glm::vec3(0.5f, 0.6f, 0.7f);
  m.sheen->roughness_factor = 0.5f;
  m.transmission = TransmissionExtension{};
  m.transmission->factor = 0.5f;
  return m;
}

TEST(GlDebugChannels, LobesSumToTheShadedColourLessTheEmission) {
  const LobeLighting lighting;
  const Camera camera = select_camera(sphere_scene(Material{}), std::nullopt, 1.0f);
  const auto pixels = sphere_pixels(camera);
  {
    // The full image, each lobe's, the emission's.
    std::vector<DebugChannel> channels = {DebugChannel::kNone};
    channels.insert(channels.end(), kLobes.begin(), kLobes.end());
    channels.push_back(DebugChannel::kEmissive);
    const auto images = render_lit(layered_material(), lighting, channels);
    // Every lobe channel recomputes the shaded colour's terms in a program of its own, and
    // the split ones as a difference of two evaluations: each term agrees with the full
    // image's to a few float32 ulps per operation of its ~100 (2^-23 relative each), so the
    // sum is within 1e-4 of the pixel plus 1e-6 absolute (where a difference cancels). A
    // term missing or counted twice is at least a few per cent of the pixel (each lobe is,
    // below).
    double lobe_share[5] = {};
    for (auto [x, y] : pixels) {
      const glm::vec3 full = images[0].rgb(x, y);
      glm::vec3 sum = images[6].rgb(x, y);
      for (int l = 0; l < 5; ++l) {
        sum += images[std::size_t(1 + l)].rgb(x, y);
        lobe_share[l] += luminance(images[std::size_t(1 + l)].rgb(x, y)) / luminance(full);
      }
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(sum[k], full[k], 1e-4f * full[k] + 1e-6f) << x << "," << y;
    }
    // Each lobe is seen: a lobe channel left black would still sum right if another
    // channel held its terms.
    for (int l = 0; l < 5; ++l)
      EXPECT_GT(lobe_share[l] / double(pixels.size()), 0.02)
          << debug_channel_name(kLobes[std::size_t(l)]);
  }
}

// The largest |channel| over the sphere relative to the full image's luminance there.
float largest_relative(const Image& channel, const Image& full, const Camera& camera) {
  float largest = 0.0f;
  for (auto [x, y] : sphere_pixels(camera)) {
    const glm::vec3 c = channel.rgb(x, y);
    largest = std::max(largest, std::max({std::abs(c.r), std::abs(c.g), std::abs(c.b)}) /
                                    luminance(full.rgb(x, y)));
  }
  return largest;
}

TEST(GlDebugChannels, EachLobeIsIsolated) {
  const LobeLighting lighting;
  const Camera camera = select_camera(sphere_scene(Material{}), std::nullopt, 1.0f);
  // Float32 cancellation in a difference of two evaluations of the same terms (the sum
  // test's bound); a lobe that leaked is a sizeable share.
  constexpr float kZero = 1e-4f;

  // A white Lambertian base without specular under a coat and a sheen: its specular
  // channel, bsdf_eval less the attenuated diffuse, is 0 only if the layers' attenuation
  // given to the diffuse is the one bsdf_eval applies to the base (and the split sum's
  // diffuse is the whole of its base).
  Material lambert;
  lambert.base_color_factor = glm::vec4(1.0f);
  lambert.metallic_factor = 0.0f;
  lambert.specular = SpecularExtension{};
  lambert.specular->factor = 0.0f;
  Material layered = lambert;
  layered.clearcoat = layered_material().clearcoat;
  layered.sheen = layered_material().sheen;
  auto images = render_lit(layered, lighting, {DebugChannel::kNone, DebugChannel::kSpecular});
  EXPECT_LT(largest_relative(images[1], images[0], camera), kZero) << "specular";

  // Over a black base without specular, the coat alone, then the sheen alone, is the whole
  // shaded colour: each channel holds every term of its lobe, the lights' and the
  // environment's.
  Material black = lambert;
  black.base_color_factor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  for (DebugChannel lobe : {DebugChannel::kClearcoat, DebugChannel::kSheen}) {
    Material m = black;
    if (lobe == DebugChannel::kClearcoat) m.clearcoat = layered_material().clearcoat;
    if (lobe == DebugChannel::kSheen) m.sheen = layered_material().sheen;
    images = render_lit(m, lighting, {DebugChannel::kNone, lobe});
    float largest = 0.0f;
    for (auto [x, y] : sphere_pixels(camera)) {
      const glm::vec3 d = images[1].rgb(x, y) - images[0].rgb(x, y);
      largest = std::max(largest, std::max({std::abs(d.r), std::abs(d.g), std::abs(d.b)}) /
                                      luminance(images[0].rgb(x, y)));
    }
    EXPECT_LT(largest, kZero) << debug_channel_name(lobe);
    EXPECT_GT(largest_relative(images[1], images[0], camera), 0.5f) << debug_channel_name(lobe);
  }
}

TEST(GlDebugChannels, DiffuseOfAWhiteLambertianIsItsIrradianceOverPi) {
  // A uniform environment L (its irradiance pi L, exact in the SH's first band) and a
  // directional light E from the camera: at the centre (n = l = v) f = 1/pi gives
  // L + E/pi, with no specular (weight 0) to hide among.
  const Environment env = Environment::constant(glm::vec3(0.5f));
  const IblMaps maps = testing::small_ibl_maps(env);
  Material m;
  m.base_color_factor = glm::vec4(1.0f);
  m.metallic_factor = 0.0f;
  m.specular = SpecularExtension{};
  m.specular->factor = 0.0f;
  Scene scene = sphere_scene(m);
  Light light;
  light.type = Light::Type::kDirectional;
  light.intensity = 2.0f;
  light.direction = glm::vec3(0.0f, 0.0f, -1.0f);
  scene.lights.push_back(light);
  const Camera camera = select_camera(scene, std::nullopt, 1.0f);
  for (bool multiscatter : {false, true}) {
    RenderSettings settings;
    settings.brdf.model = BrdfModel::kReference;
    settings.brdf.multiscatter = multiscatter;
    const auto images = render_channels(scene, camera, kSize, kSize, {DebugChannel::kDiffuse},
                                        {&env, &maps}, settings);
    const glm::vec3 c = images[0].rgb(kSize / 2, kSize / 2);
    const float want = 0.5f + 2.0f / float(M_PI);
    // The bake's SH of a constant map is exact to float rounding; 1e-3 leaves room for the
    // small bake's 16-sample integration of the first band.
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], want, 1e-3f * want) << multiscatter;
  }
}

}  // namespace
}  // namespace pbrkit::gl
