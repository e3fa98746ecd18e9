#include "gl/harness/bsdf_eval.h"

#include <epoxy/gl.h>

#include "gl/harness/compute_eval.h"
#include "pbrkit/gl/energy_texture.h"
#include "pbrkit/gl/program.h"

namespace pbrkit::gl {

std::vector<glm::vec3> eval_bsdf_glsl(const std::vector<BsdfCase>& cases,
                                      const BrdfOptions& options) {
  if (cases.empty()) return {};
  const Program program = detail::test_program("bsdf_test.glsl");
  // bsdf_test.glsl's BsdfCase: brdf_test.glsl's six vec4, then three for the layers.
  std::vector<glm::vec4> input;
  input.reserve(cases.size() * 9);
  for (const BsdfCase& c : cases) {
    append_brdf_case(c.base, input);
    input.emplace_back(c.coat_weight, c.coat_roughness, c.sheen_roughness, 0.0f);
    input.emplace_back(c.coat_normal, 0.0f);
    input.emplace_back(c.sheen_color, 0.0f);
  }
  const GeometryModel geometry = direct_geometry(options.model);
  const GLuint energy = create_energy_texture(geometry);
  const GLuint coat_energy = create_energy_texture(GeometryModel::kReference);
  const GLuint sheen_lut = create_sheen_lut_texture();
  const GLuint aniso_energy = create_anisotropic_energy_texture();
  program.use();
  program.set("uCount", int(cases.size()));
  program.set("uGeometry", int(geometry));
  program.set("uMultiscatter", options.multiscatter ? 1 : 0);
  glBindTextureUnit(0, energy);
  glBindTextureUnit(1, coat_energy);
  glBindTextureUnit(2, sheen_lut);
  glBindTextureUnit(3, aniso_energy);
  const std::vector<glm::vec4> output = detail::dispatch_cases(input, cases.size());
  const GLuint textures[4] = {energy, coat_energy, sheen_lut, aniso_energy};
  glDeleteTextures(4, textures);
  std::vector<glm::vec3> result;
  result.reserve(output.size());
  for (const glm::vec4& v : output) result.emplace_back(v);
  return result;
}

}  // namespace pbrkit::gl
