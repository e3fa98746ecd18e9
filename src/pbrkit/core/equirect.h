#pragma once
// The project's one orientation convention for equirectangular (lat-long) environment
// maps. The baker, the path tracer and the OpenGL renderer (GLSL mirrors these lines in
// shaders/equirect.glsl) all use exactly these functions.
//
//   * +Y is up. Row 0 (v = 0) is the zenith (+Y), the bottom row (v = 1) the nadir.
//   * The image centre (u = 0.5, v = 0.5) faces -Z: the direction a default glTF camera
//     looks, so an unrotated default view shows the middle of the panorama.
//   * u grows to the right as seen from inside the sphere: u = 0.75 faces +X,
//     u = 0.25 faces -X, u = 0 and u = 1 face +Z (the seam is behind the default camera).
//     In formulas: u = 0.5 + atan2(d.x, -d.z) / (2 pi),  v = acos(d.y) / pi.
//   * `rotation_deg` turns the environment about +Y, counter-clockwise seen from above
//     (right-handed): with rotation 90, what was at -Z (image centre) is now at -X.
#include <cmath>

#include <glm/glm.hpp>

#include "pbrkit/core/math.h"

namespace pbrkit {

/// Direction (unit) -> (u, v) in [0,1]^2 of the unrotated map.
inline glm::vec2 equirect_uv(glm::vec3 d) {
  const float u = 0.5f + std::atan2(d.x, -d.z) * (0.5f * kInvPi);
  const float v = std::acos(glm::clamp(d.y, -1.0f, 1.0f)) * kInvPi;
  return {u - std::floor(u), v};
}

/// (u, v) -> unit direction; the inverse of equirect_uv.
inline glm::vec3 equirect_direction(glm::vec2 uv) {
  const float phi = (uv.x - 0.5f) * 2.0f * kPi;  // angle from -Z towards +X
  const float theta = uv.y * kPi;                // angle from +Y
  const float s = std::sin(theta);
  return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

/// Rotates a world direction into the environment map's frame for a map rotated by
/// `rotation_deg` about +Y (see the convention above): lookup(d) = map(R(-rotation) d).
inline glm::vec3 world_to_env(glm::vec3 d, float rotation_deg) {
  const float a = -rotation_deg * (kPi / 180.0f);
  const float c = std::cos(a), s = std::sin(a);
  return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}
/// Inverse of world_to_env.
inline glm::vec3 env_to_world(glm::vec3 d, float rotation_deg) {
  return world_to_env(d, -rotation_deg);
}

}  // namespace pbrkit
