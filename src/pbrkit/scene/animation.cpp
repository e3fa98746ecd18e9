// Keyframe interpolation, glTF 2.0 Appendix C ("Animation Sampler Interpolation Modes").
#include "pbrkit/scene/animation.h"

#include <algorithm>
#include <cmath>

namespace pbrkit {

float Animation::start() const {
  float s = 0.0f;
  bool any = false;
  for (const AnimationSampler& sampler : samplers)
    if (!sampler.times.empty()) {
      s = any ? std::min(s, sampler.times.front()) : sampler.times.front();
      any = true;
    }
  return s;
}

float Animation::end() const {
  float e = 0.0f;
  bool any = false;
  for (const AnimationSampler& sampler : samplers)
    if (!sampler.times.empty()) {
      e = any ? std::max(e, sampler.times.back()) : sampler.times.back();
      any = true;
    }
  return e;
}

glm::quat slerp_shortest(glm::quat a, glm::quat b, float u) {
  float d = glm::dot(a, b);
  if (d < 0.0f) {  // q and -q are the same rotation: take the shorter arc
    b = -b;
    d = -d;
  }
  glm::quat q;
  if (d > 0.9995f) {
    // sin(theta) -> 0: the arc is a line to float precision (Appendix C's slerp divides by it).
    q = a * (1.0f - u) + b * u;
  } else {
    const float theta = std::acos(std::min(d, 1.0f));
    const float s = std::sin(theta);
    q = a * (std::sin((1.0f - u) * theta) / s) + b * (std::sin(u * theta) / s);
  }
  const float len = glm::length(q);
  return len > 0.0f ? q / len : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
}

namespace {

glm::quat quat_at(const float* v) {
  return glm::quat(v[3], v[0], v[1], v[2]);
}  // (x,y,z,w)

void store_normalised(glm::quat q, float* out) {
  const float len = glm::length(q);
  if (len > 0.0f && std::isfinite(len))
    q = q / len;
  else
    q = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  out[0] = q.x;
  out[1] = q.y;
  out[2] = q.z;
  out[3] = q.w;
}

}  // namespace

void sample_animation(const AnimationSampler& sampler, float t, bool rotation, float* out) {
  const std::size_t w = std::size_t(sampler.width);
  const std::size_t keys = sampler.times.size();
  if (keys == 0 || w == 0) return;
  const bool cubic = sampler.interpolation == Interpolation::kCubicSpline;
  // A key's value: the middle of the cubic spline's (in-tangent, value, out-tangent) triple.
  const std::size_t stride = cubic ? 3 * w : w;
  const std::size_t value_offset = cubic ? w : 0;
  auto value = [&](std::size_t k) { return sampler.values.data() + k * stride + value_offset; };
  auto copy_key = [&](std::size_t k) {
    const float* v = value(k);
    if (rotation)
      store_normalised(quat_at(v), out);
    else
      std::copy(v, v + w, out);
  };
  // Outside the keys: clamp (glTF 2.0 section 3.11: "the animated property ... is
  // clamped" to the first or last keyframe's value).
  if (!(t > sampler.times.front()) || keys == 1) return copy_key(0);
  if (t >= sampler.times.back()) return copy_key(keys - 1);
  // The interval [t_k, t_k+1) holding t.
  const std::size_t k =
      std::size_t(std::upper_bound(sampler.times.begin(), sampler.times.end(), t) -
                  sampler.times.begin()) -
      1;
  const float t0 = sampler.times[k], t1 = sampler.times[k + 1];
  const float td = t1 - t0;
  const float u = td > 0.0f ? std::clamp((t - t0) / td, 0.0f, 1.0f) : 0.0f;
  switch (sampler.interpolation) {
    case Interpolation::kStep:
      return copy_key(k);
    case Interpolation::kLinear:
      if (rotation)
        return store_normalised(slerp_shortest(quat_at(value(k)), quat_at(value(k + 1)), u), out);
      for (std::size_t c = 0; c < w; ++c) out[c] = value(k)[c] * (1.0f - u) + value(k + 1)[c] * u;
      return;
    case Interpolation::kCubicSpline: {
      // Appendix C, "Cubic Spline Interpolation": the Hermite basis with the tangents
      // scaled by the interval td: p(u) = (2u^3 - 3u^2 + 1) v_k + td (u^3 - 2u^2 + u) b_k
      // + (-2u^3 + 3u^2) v_k+1 + td (u^3 - u^2) a_k+1, b the out- and a the in-tangents.
      const float u2 = u * u, u3 = u2 * u;
      const float h00 = 2 * u3 - 3 * u2 + 1, h10 = td * (u3 - 2 * u2 + u);
      const float h01 = -2 * u3 + 3 * u2, h11 = td * (u3 - u2);
      const float* v0 = value(k);
      const float* b0 = sampler.values.data() + k * stride + 2 * w;
      const float* v1 = value(k + 1);
      const float* a1 = sampler.values.data() + (k + 1) * stride;
      float r[16];
      float* dst = rotation ? r : out;
      for (std::size_t c = 0; c < w; ++c)
        dst[c] = h00 * v0[c] + h10 * b0[c] + h01 * v1[c] + h11 * a1[c];
      if (rotation) store_normalised(quat_at(r), out);  // "MUST be normalized" after
      return;
    }
  }
}

}  // namespace pbrkit
