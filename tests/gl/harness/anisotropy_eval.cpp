#include "gl/harness/anisotropy_eval.h"

#include <epoxy/gl.h>

#include "gl/harness/compute_eval.h"
#include "pbrkit/gl/energy_texture.h"
#include "pbrkit/gl/program.h"

namespace pbrkit::gl {

std::vector<glm::vec4> eval_anisotropy_glsl(const std::vector<AnisotropyCase>& cases,
                                            AnisotropyFunction function,
                                            const std::array<glm::vec3, 6>& face_colors,
                                            glm::vec2 rotation) {
  if (cases.empty()) return {};
  const Program program = detail::test_program("anisotropy_ibl_test.glsl");
  // std430 layout of anisotropy_ibl_test.glsl's AnisotropyCase: five vec4.
  std::vector<glm::vec4> input;
  input.reserve(cases.size() * 5);
  for (const AnisotropyCase& c : cases) {
    input.emplace_back(c.wo, float(c.tap));
    input.emplace_back(c.alpha_x, c.alpha_y, 0.0f, 0.0f);
    for (int k = 0; k < 3; ++k) input.emplace_back(c.frame[k], 0.0f);
  }
  // A one-level cube of 1x1 faces, nearest filtering: each lookup returns its face's colour.
  GLuint cube = 0;
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &cube);
  glTextureStorage2D(cube, 1, GL_RGBA32F, 1, 1);
  for (int face = 0; face < 6; ++face) {
    const glm::vec4 texel(face_colors[std::size_t(face)], 1.0f);
    glTextureSubImage3D(cube, 0, 0, 0, face, 1, 1, 1, GL_RGBA, GL_FLOAT, &texel);
  }
  glTextureParameteri(cube, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(cube, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  program.use();
  program.set("uCount", int(cases.size()));
  program.set("uFunction", int(function));
  program.set("uRotation", rotation);
  const GLuint albedo = create_anisotropic_albedo_texture();
  glBindTextureUnit(0, cube);
  glBindTextureUnit(1, albedo);
  std::vector<glm::vec4> output = detail::dispatch_cases(input, cases.size());
  glDeleteTextures(1, &cube);
  glDeleteTextures(1, &albedo);
  return output;
}

}  // namespace pbrkit::gl
