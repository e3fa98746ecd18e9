#pragma once
// Robust spawn points for secondary rays: Wachter & Binder, "A Fast and Robust Method for
// Avoiding Self-Intersection", Ray Tracing Gems (2019), chapter 6. The hit point is
// computed from barycentrics (not o + t d) and then moved off the surface along the
// geometric normal by a few ulps of its own magnitude (an integer offset in the float's
// bit pattern), or by a tiny absolute offset near the origin where ulps are too small.
// Unlike a fixed epsilon this works at any scene scale and for grazing rays.
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace pbrkit {

/// `p` moved off the surface to the side `n` points to (n: geometric normal, unit).
inline glm::vec3 offset_ray_origin(glm::vec3 p, glm::vec3 n) {
  constexpr float kOrigin = 1.0f / 32.0f;
  constexpr float kFloatScale = 1.0f / 65536.0f;
  constexpr float kIntScale = 256.0f;
  glm::vec3 out;
  for (int i = 0; i < 3; ++i) {
    const auto of_i = static_cast<std::int32_t>(kIntScale * n[i]);
    const auto bits = std::bit_cast<std::int32_t>(p[i]);
    const float p_i = std::bit_cast<float>(bits + (p[i] < 0.0f ? -of_i : of_i));
    out[i] = std::fabs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : p_i;
  }
  return out;
}

}  // namespace pbrkit
