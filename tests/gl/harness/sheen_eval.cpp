#include "gl/harness/sheen_eval.h"

#include <epoxy/gl.h>

#include "gl/harness/compute_eval.h"
#include "pbrkit/gl/energy_texture.h"
#include "pbrkit/gl/program.h"

namespace pbrkit::gl {

std::vector<glm::vec4> sheen_sh_glsl(const std::vector<SheenLobeCase>& cases, const SH9& sh) {
  if (cases.empty()) return {};
  const Program program = detail::test_program("sheen_test.glsl");
  // std430 layout of sheen_test.glsl's SheenLobeCase: two vec4.
  std::vector<glm::vec4> input;
  input.reserve(cases.size() * 2);
  for (const SheenLobeCase& c : cases) {
    input.emplace_back(c.n, c.roughness);
    input.emplace_back(c.v, 0.0f);
  }
  const GLuint sheen_lut = create_sheen_lut_texture();
  program.use();
  program.set("uCount", int(cases.size()));
  glProgramUniform3fv(program.id(), program.location("uSH"), 9, &sh[0].x);
  glBindTextureUnit(0, sheen_lut);
  std::vector<glm::vec4> output = detail::dispatch_cases(input, cases.size());
  glDeleteTextures(1, &sheen_lut);
  return output;
}

}  // namespace pbrkit::gl
