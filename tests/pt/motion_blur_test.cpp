// Motion blur: a sphere moving at constant speed across an orthographic camera's view
// leaves the box convolution of the still sphere (the image averaged over the shutter is
// the still image averaged over the shifts it moves through); and a render whose shutter
// sees no motion is the still render, bit for bit.
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/scene/primitives.h"
#include "pt_test_util.h"

namespace pbrkit {
namespace {

constexpr int kSize = 96;
constexpr float kHalf = 2.0f;  // the camera sees [-2, 2]^2: 24 pixels per unit

// An unlit white sphere of radius 0.6 on black, moved by animation 0 from x = -0.5 at
// t = 0 to x = +0.5 at t = 1 (constant speed: one LINEAR segment); optionally a second
// still sphere above it.
Scene moving_sphere_scene() {
  Scene s;
  s.source = "moving sphere";
  Material white = test::make_material(glm::vec3(1.0f), 0.0f, 1.0f);
  white.unlit = true;  // radiance = base colour: the image is the sphere's coverage
  s.materials.push_back(white);
  Mesh sphere = make_uv_sphere(0.6f, 96, 48);
  sphere.material = 0;
  s.meshes.push_back(std::move(sphere));
  s.instances.push_back({0, glm::mat4(1.0f), 0});
  auto motion = std::make_shared<SceneMotion>();
  motion->nodes.resize(1);
  motion->order = {0};
  motion->placements = {{0, 0, glm::mat4(1.0f)}};
  Animation a;
  a.name = "slide";
  AnimationSampler sampler;
  sampler.interpolation = Interpolation::kLinear;
  sampler.times = {0.0f, 1.0f};
  sampler.values = {-0.5f, 0.0f, 0.0f, 0.5f, 0.0f, 0.0f};
  sampler.width = 3;
  a.samplers.push_back(sampler);
  a.channels.push_back({0, 0, AnimatedProperty::kTranslation});
  motion->animations.push_back(a);
  s.motion = motion;
  return s;
}

PathTracerSettings settings(std::uint32_t spp) {
  PathTracerSettings st;
  st.width = st.height = kSize;
  st.spp = spp;
  st.noise_threshold = 0.0f;
  st.max_bounces = 0;
  st.env_visible = false;
  st.threads = 2;
  return st;
}

TEST(MotionBlur, ConstantSpeedStreakIsTheBoxConvolutionOfTheStillSphere) {
  Scene scene = moving_sphere_scene();
  pose_scene(scene, {0, 0.5f});  // the centre of the shutter: x = 0
  const Camera camera = test::ortho_camera(kHalf);
  const Image still = render_path(scene, nullptr, camera, settings(256)).color;
  PathTracerSettings blur = settings(256);
  blur.shutter = {0, 0.0f, 1.0f, 9};
  const Image blurred = render_path(scene, nullptr, camera, blur).color;

  // The still image moved through [-0.5, 0.5] units = [-12, 12] pixels and averaged: the
  // box convolution, by a fine midpoint rule over the shifts with linear interpolation.
  const float pixels_per_unit = float(kSize) / (2.0f * kHalf);
  const int taps = 96;
  double sum_sq = 0.0, max_diff = 0.0, streak_mid = 0.0;
  int n = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      double expected = 0.0;
      for (int k = 0; k < taps; ++k) {
        const float shift = (-0.5f + (float(k) + 0.5f) / float(taps)) * pixels_per_unit;
        const float sx = float(x) - shift;  // the still pixel that moves onto x
        const int x0 = int(std::floor(sx));
        const float f = sx - float(x0);
        auto at = [&](int xi) { return xi < 0 || xi >= kSize ? 0.0f : still.pixel(xi, y)[0]; };
        expected += (1.0f - f) * at(x0) + f * at(x0 + 1);
      }
      expected /= taps;
      const double d = double(blurred.pixel(x, y)[0]) - expected;
      sum_sq += d * d;
      max_diff = std::max(max_diff, std::abs(d));
      ++n;
      if (y == kSize / 2 && x == kSize / 2 + int(0.6f * pixels_per_unit)) streak_mid = expected;
    }
  // Noise: a pixel's value is a coverage fraction; with 256 samples its standard deviation
  // is at most 0.5 / 16 = 0.031 (and the still image's, averaged over 24 pixels, far
  // less). 5 of those bound any pixel's difference; the RMS must be at noise level.
  EXPECT_LT(max_diff, 5 * 0.5 / 16) << "RMS " << std::sqrt(sum_sq / n);
  EXPECT_LT(std::sqrt(sum_sq / n), 0.5 / 16);
  // The shutter's times are uniform: the streak's weighted centroid is the centre pose's (a
  // bias of 1% of the shutter would move it 0.24 pixels; the noise moves it about 0.01).
  auto centroid_x = [&](const Image& image) {
    double sw = 0.0, sx = 0.0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        sw += image.pixel(x, y)[0];
        sx += double(image.pixel(x, y)[0]) * x;
      }
    return sx / sw;
  };
  EXPECT_NEAR(centroid_x(blurred), centroid_x(still), 0.06);
  // The test can fail: at the still sphere's edge the streak is half covered, not 0 or 1.
  EXPECT_GT(streak_mid, 0.3);
  EXPECT_LT(streak_mid, 0.7);
  // And the blurred render is that half-covered value there (not the still sphere's edge).
  EXPECT_NEAR(blurred.pixel(kSize / 2 + int(0.6f * pixels_per_unit), kSize / 2)[0], streak_mid,
              5 * 0.5 / 16);
}

TEST(MotionBlur, AShutterWithoutMotionIsTheStillRender) {
  Scene scene = moving_sphere_scene();
  pose_scene(scene, {0, 3.0f});  // after the last key: the sphere rests at x = 0.5
  const Camera camera = test::ortho_camera(kHalf);
  const Image still = render_path(scene, nullptr, camera, settings(16)).color;
  PathTracerSettings blur = settings(16);
  blur.shutter = {0, 2.0f, 4.0f, 9};  // clamped: nothing moves
  const Image same = render_path(scene, nullptr, camera, blur).color;
  ASSERT_EQ(still.data.size(), same.data.size());
  for (std::size_t i = 0; i < still.data.size(); ++i) ASSERT_EQ(still.data[i], same.data[i]) << i;
}

}  // namespace
}  // namespace pbrkit
