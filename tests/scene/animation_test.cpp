// Keyframe interpolation against closed forms written here from glTF 2.0 Appendix C.
#include "pbrkit/scene/animation.h"

#include <cmath>

#include <gtest/gtest.h>

namespace pbrkit {
namespace {

constexpr float kPi = 3.14159265358979f;

AnimationSampler sampler(Interpolation mode, std::vector<float> times, std::vector<float> values,
                         int width) {
  AnimationSampler s;
  s.interpolation = mode;
  s.times = std::move(times);
  s.values = std::move(values);
  s.width = width;
  return s;
}

// A quaternion (x, y, z, w) of `angle` about z.
std::vector<float> about_z(float angle) {
  return {0.0f, 0.0f, std::sin(angle / 2), std::cos(angle / 2)};
}

TEST(Slerp, HalfwayBetweenTwoRotationsAboutOneAxisIsTheHalfAngle) {
  const glm::quat a(1, 0, 0, 0);
  const glm::quat b(std::cos(kPi / 4), 0, 0, std::sin(kPi / 4));  // 90 degrees about z
  for (const float u : {0.0f, 0.25f, 0.5f, 0.9f, 1.0f}) {
    const glm::quat q = slerp_shortest(a, b, u);
    // Slerp moves at constant angular speed: u of the way is u * 90 degrees.
    EXPECT_NEAR(q.w, std::cos(u * kPi / 4), 1e-6f) << u;
    EXPECT_NEAR(q.z, std::sin(u * kPi / 4), 1e-6f) << u;
    EXPECT_NEAR(q.x, 0.0f, 1e-7f);
  }
}

TEST(Slerp, TakesTheShorterArc) {
  // b and -b are one rotation of 90 degrees; from a the short way is 45 at u = 0.5 either way.
  const glm::quat a(1, 0, 0, 0);
  const glm::quat b(std::cos(kPi / 4), 0, 0, std::sin(kPi / 4));
  const glm::quat q = slerp_shortest(a, -b, 0.5f);
  const float sign = q.w < 0 ? -1.0f : 1.0f;
  EXPECT_NEAR(sign * q.w, std::cos(kPi / 8), 1e-6f);
  EXPECT_NEAR(sign * q.z, std::sin(kPi / 8), 1e-6f);
}

TEST(AnimationSampler, LinearRotationIsSlerpAndComesOutNormalised) {
  std::vector<float> v = about_z(0.0f);
  const std::vector<float> v1 = about_z(2.0f);  // 114.6 degrees
  v.insert(v.end(), v1.begin(), v1.end());
  const AnimationSampler s = sampler(Interpolation::kLinear, {1.0f, 3.0f}, v, 4);
  float q[4];
  sample_animation(s, 1.5f, true, q);  // u = 0.25: a quarter of the angle
  EXPECT_NEAR(q[2], std::sin(0.25f), 1e-6f);
  EXPECT_NEAR(q[3], std::cos(0.25f), 1e-6f);
  EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0f, 1e-6f);
}

TEST(AnimationSampler, LinearStepAndClampOnVectors) {
  const AnimationSampler lin =
      sampler(Interpolation::kLinear, {0.0f, 2.0f, 3.0f}, {0, 0, 0, 4, -2, 8, 5, 0, 8}, 3);
  float v[3];
  sample_animation(lin, 0.5f, false, v);  // a quarter of the way from key 0 to key 1
  EXPECT_FLOAT_EQ(v[0], 1.0f);
  EXPECT_FLOAT_EQ(v[1], -0.5f);
  EXPECT_FLOAT_EQ(v[2], 2.0f);
  sample_animation(lin, 2.5f, false, v);
  EXPECT_FLOAT_EQ(v[0], 4.5f);
  EXPECT_FLOAT_EQ(v[1], -1.0f);
  // Outside the keys: the first and last values.
  sample_animation(lin, -7.0f, false, v);
  EXPECT_FLOAT_EQ(v[0], 0.0f);
  sample_animation(lin, 30.0f, false, v);
  EXPECT_FLOAT_EQ(v[0], 5.0f);
  EXPECT_FLOAT_EQ(v[2], 8.0f);

  const AnimationSampler step =
      sampler(Interpolation::kStep, {0.0f, 2.0f, 3.0f}, {0, 0, 0, 4, -2, 8, 5, 0, 8}, 3);
  sample_animation(step, 1.999f, false, v);
  EXPECT_FLOAT_EQ(v[0], 0.0f);
  sample_animation(step, 2.0f, false, v);  // at a key: that key's value
  EXPECT_FLOAT_EQ(v[0], 4.0f);
  sample_animation(step, 2.9f, false, v);
  EXPECT_FLOAT_EQ(v[1], -2.0f);
}

TEST(AnimationSampler, CubicSplineIsTheHermiteCurveWithTangentsScaledByTheInterval) {
  // One scalar, keys at t = 1 and t = 3 (td = 2): (in, value, out) per key.
  const float v0 = 1.0f, b0 = 0.5f, a1 = -3.0f, v1 = 2.0f;
  const AnimationSampler s =
      sampler(Interpolation::kCubicSpline, {1.0f, 3.0f}, {9.0f, v0, b0, a1, v1, 7.0f}, 1);
  float v;
  sample_animation(s, 1.0f, false, &v);  // at the keys: their values, not their tangents
  EXPECT_FLOAT_EQ(v, v0);
  sample_animation(s, 3.0f, false, &v);
  EXPECT_FLOAT_EQ(v, v1);
  for (const float u : {0.1f, 0.5f, 0.8f}) {
    const float td = 2.0f;
    // Appendix C: p = (2u^3-3u^2+1) v0 + td (u^3-2u^2+u) b0 + (-2u^3+3u^2) v1 + td (u^3-u^2) a1.
    const float expected = (2 * u * u * u - 3 * u * u + 1) * v0 +
                           td * (u * u * u - 2 * u * u + u) * b0 +
                           (-2 * u * u * u + 3 * u * u) * v1 + td * (u * u * u - u * u) * a1;
    sample_animation(s, 1.0f + u * td, false, &v);
    EXPECT_NEAR(v, expected, 1e-5f) << u;
  }
  // u = 0.5 by hand: 0.5 v0 + 2 (0.125) b0 + 0.5 v1 + 2 (-0.125) a1 = 0.5 + 0.125 + 1 + 0.75.
  sample_animation(s, 2.0f, false, &v);
  EXPECT_NEAR(v, 2.375f, 1e-6f);
}

TEST(AnimationSampler, CubicSplineRotationIsNormalisedAfterward) {
  // Two keys, 0 and 90 degrees about z, zero tangents: the Hermite blend of the two
  // quaternions at u = 0.5 is their mean, whose normalisation is the 45-degree rotation.
  std::vector<float> v = {0, 0, 0, 0};
  const std::vector<float> q0 = about_z(0.0f), q1 = about_z(kPi / 2);
  v.insert(v.end(), q0.begin(), q0.end());
  v.insert(v.end(), {0, 0, 0, 0, 0, 0, 0, 0});
  v.insert(v.end(), q1.begin(), q1.end());
  v.insert(v.end(), {0, 0, 0, 0});
  const AnimationSampler s = sampler(Interpolation::kCubicSpline, {0.0f, 1.0f}, v, 4);
  float q[4];
  sample_animation(s, 0.5f, true, q);
  EXPECT_NEAR(q[2], std::sin(kPi / 8), 1e-6f);
  EXPECT_NEAR(q[3], std::cos(kPi / 8), 1e-6f);
}

TEST(Animation, StartAndEndSpanEverySampler) {
  Animation a;
  a.samplers.push_back(sampler(Interpolation::kLinear, {0.5f, 2.0f}, {0, 0}, 1));
  a.samplers.push_back(sampler(Interpolation::kLinear, {0.25f, 1.0f}, {0, 0}, 1));
  EXPECT_FLOAT_EQ(a.start(), 0.25f);
  EXPECT_FLOAT_EQ(a.end(), 2.0f);
}

}  // namespace
}  // namespace pbrkit
