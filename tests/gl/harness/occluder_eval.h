#pragma once
// Evaluates occluder_form_factors.glsl's form factors on the GPU for a batch of cases,
// through a compute shader (tests/gl/occluders_test.cpp). Needs a current GL 4.5 context.
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit::gl {

struct FormFactorCase {
  glm::vec3 x{0.0f}, n{0.0f, 0.0f, 1.0f};  ///< the surface point and its unit normal
  bool sphere = true;
  glm::vec3 center{0.0f};
  float radius = 1.0f;  ///< a sphere's
  /// A parallelepiped's half-axes (occluders.h turns them into the faces the shader takes).
  glm::vec3 axes[3] = {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)};
};

/// sphere_form_factor or box_form_factor for every case.
std::vector<float> form_factors_glsl(const std::vector<FormFactorCase>& cases);

}  // namespace pbrkit::gl
