#pragma once
// Runs a shader unit test's compute shader over a batch: `input` (std430 vec4s, binding 0)
// in, one vec4 per case (binding 1) out, 64 invocations per group. Shared by the GLSL
// BRDF and display-transform evaluations (brdf_eval.h, display_eval.h). Needs a current
// GL 4.5 context, and the program in use with its uniforms set.
#include <cstddef>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/gl/program.h"

namespace pbrkit::gl::detail {

/// The compute program of a shader unit test, `file` one of harness/shaders/*_test.glsl:
/// those are embedded in this test-support library, not in libpbrkit, and are added to the
/// shaders that shader_source() finds on first use.
Program test_program(std::string_view file);

std::vector<glm::vec4> dispatch_cases(const std::vector<glm::vec4>& input, std::size_t count);

}  // namespace pbrkit::gl::detail
