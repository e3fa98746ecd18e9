#pragma once
// Small math shared by every module: constants, an orthonormal frame, and helpers whose
// names mirror the formulas they are used in. Vectors are glm's (they read like GLSL,
// which keeps the C++ and shader versions of the model side by side).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace pbrkit {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;

template <typename T>
constexpr T sqr(T x) {
  return x * x;
}
/// The largest channel (KHR_materials_specular's and _sheen's max3).
inline float max3(glm::vec3 v) {
  return std::max(v.x, std::max(v.y, v.z));
}

inline float safe_sqrt(float x) {
  return std::sqrt(std::max(x, 0.0f));
}
inline float saturate(float x) {
  return std::clamp(x, 0.0f, 1.0f);
}

/// Reflects v about n (both pointing away from the surface): 2 (v.n) n - v.
inline glm::vec3 reflect_about(glm::vec3 v, glm::vec3 n) {
  return 2.0f * glm::dot(v, n) * n - v;
}

/// Orthonormal frame with `n` as its z axis. Built with the branchless method of
/// Duff et al. 2017, "Building an Orthonormal Basis, Revisited" (JCGT 6(1)).
struct Frame {
  glm::vec3 t, b, n;

  Frame() : t(1, 0, 0), b(0, 1, 0), n(0, 0, 1) {}
  explicit Frame(glm::vec3 normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float bb = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x);
    b = glm::vec3(bb, sign + n.y * n.y * a, -n.y);
  }
  Frame(glm::vec3 tangent, glm::vec3 bitangent, glm::vec3 normal)
      : t(tangent), b(bitangent), n(normal) {}

  glm::vec3 to_local(glm::vec3 v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
  glm::vec3 to_world(glm::vec3 v) const { return v.x * t + v.y * b + v.z * n; }
};

}  // namespace pbrkit
