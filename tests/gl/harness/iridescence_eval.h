#pragma once
// Evaluates the GLSL thin-film Fresnel (shaders/iridescence.glsl) on the GPU for a batch of
// inputs, through a compute shader: the shader unit test that shows the OpenGL renderer's
// iridescence and the C++ pbrkit::iridescence_fresnel (core/iridescence.h) are one model.
// Needs a current GL 4.5 context.
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit::gl {

/// The arguments of iridescence_fresnel, one call each.
struct IridescenceCase {
  float cos_theta = 1.0f;
  float film_ior = 1.3f;
  float thickness_nm = 400.0f;
  glm::vec3 base_F0{0.04f};
};

/// iridescence_fresnel(...) of iridescence.glsl for every case, read back as RGB.
std::vector<glm::vec3> iridescence_fresnel_glsl(const std::vector<IridescenceCase>& cases);

}  // namespace pbrkit::gl
