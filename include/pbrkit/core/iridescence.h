#pragma once
// STUB (replaced by branch iridescence).
#include <glm/glm.hpp>
namespace pbrkit {
inline glm::vec3 iridescence_fresnel(float cos_theta, float, float, glm::vec3 base_F0) {
  const float m = 1.0f - cos_theta;
  return base_F0 + (1.0f - base_F0) * (m * m * m * m * m);
}
}  // namespace pbrkit
