#pragma once
// Evaluates the GLSL sheen lookups (shaders/sheen.glsl: sheen_E, sheen_lobe_direction) on the
// GPU for a batch of inputs, through a compute shader: the shader unit test that shows the
// OpenGL renderer's sheen IBL reads the C++ SheenTable (core/sheen.h) as the C++ does. Needs a
// current GL 4.5 context.
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit::gl {

/// One call: n and v unit, sheen roughness.
struct SheenLobeCase {
  glm::vec3 n{0.0f, 0.0f, 1.0f};
  glm::vec3 v{0.0f, 0.0f, 1.0f};
  float roughness = 0.5f;
};

/// (sheen_lobe_direction(n, v, roughness), sheen_E(n.v, roughness)) of sheen.glsl for every
/// case.
std::vector<glm::vec4> sheen_lobe_glsl(const std::vector<SheenLobeCase>& cases);

}  // namespace pbrkit::gl
