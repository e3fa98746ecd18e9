#pragma once
// Runs a shader unit test's compute shader over a batch: `input` (std430 vec4s, binding 0)
// in, one vec4 per case (binding 1) out, 64 invocations per group. Shared by the GLSL
// BRDF and display-transform evaluations (brdf_eval.h, display_eval.h). Needs a current
// GL 4.5 context, and the program in use with its uniforms set.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit::gl::detail {

std::vector<glm::vec4> dispatch_cases(const std::vector<glm::vec4>& input, std::size_t count);

}  // namespace pbrkit::gl::detail
