#pragma once
// Evaluates the GLSL sheen IBL's lookups (shaders/sheen.glsl: sheen_sh_radiance, sheen_E) on
// the GPU for a batch of inputs, through a compute shader: the shader unit test that shows
// the OpenGL renderer's sheen IBL is the C++ ibl/sheen_sh.h reading the same SheenTable
// (core/sheen.h). Needs a current GL 4.5 context.
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/ibl/spherical_harmonics.h"

namespace pbrkit::gl {

/// One call: n and v unit, sheen roughness.
struct SheenLobeCase {
  glm::vec3 n{0.0f, 0.0f, 1.0f};
  glm::vec3 v{0.0f, 0.0f, 1.0f};
  float roughness = 0.5f;
};

/// (sheen_sh_radiance(sh, n, v, roughness), sheen_E(n.v, roughness)) of sheen.glsl for every
/// case, with one environment's irradiance SH.
std::vector<glm::vec4> sheen_sh_glsl(const std::vector<SheenLobeCase>& cases, const SH9& sh);

}  // namespace pbrkit::gl
