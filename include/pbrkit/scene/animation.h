#pragma once
// glTF 2.0 animations (section 3.11, "Animations") as data, and the evaluation of one
// sampler at a time: keyframes, their interpolation, and the clamping outside the keys.
// What a pose does with the values (node transforms, morph weights, skins) is
// scene/pose.h's.
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace pbrkit {

/// A sampler's interpolation (glTF 2.0, Appendix C "Animation Sampler Interpolation Modes").
enum class Interpolation { kStep, kLinear, kCubicSpline };

/// What a channel animates.
/// What a channel animates: a node's transform or morph weights (glTF 2.0), or another
/// property named by a JSON pointer (KHR_animation_pointer).
enum class AnimatedProperty { kTranslation, kRotation, kScale, kWeights, kPointer };

/// Keyframes: `times` (seconds, strictly increasing) and per key `width` floats (3 for a
/// translation or scale, 4 for a rotation quaternion (x, y, z, w), the morph target count
/// for weights); a cubic spline stores three such groups per key, in the specification's
/// order: in-tangent, value, out-tangent.
struct AnimationSampler {
  Interpolation interpolation = Interpolation::kLinear;
  std::vector<float> times;
  std::vector<float> values;
  int width = 0;
};

/// One animated property of one node, driven by `sampler` (an index into its animation's
/// samplers).
struct AnimationChannel {
  int sampler = -1;
  int node = -1;  ///< -1 for a pointer
  AnimatedProperty property = AnimatedProperty::kTranslation;
  int pointer = -1;  ///< kPointer: the index in SceneMotion::pointers (scene/pose.h)
};

struct Animation {
  std::string name;
  std::vector<AnimationSampler> samplers;
  std::vector<AnimationChannel> channels;
  /// The first and last keyframe time over every sampler (0 and 0 without keys).
  float start() const;
  float end() const;
};

/// The sampler's value at time `t` (seconds) into `out[0, width)`. Times before the first
/// key or after the last clamp to it. Rotations (`rotation`: the values are quaternions)
/// interpolate LINEAR by spherical linear interpolation along the shorter arc, and come
/// out normalised for every mode (glTF 2.0, Appendix C).
void sample_animation(const AnimationSampler& sampler, float t, bool rotation, float* out);

/// Spherical linear interpolation from `a` to `b` at `u` in [0, 1] along the shorter arc
/// (`b` negated when a.b < 0), normalised; linear interpolation where the two are so
/// close that the sine's division would lose precision.
glm::quat slerp_shortest(glm::quat a, glm::quat b, float u);

}  // namespace pbrkit
