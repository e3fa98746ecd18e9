#include "gl/harness/brdf_eval.h"

#include <epoxy/gl.h>

#include "gl/harness/compute_eval.h"
#include "pbrkit/gl/energy_texture.h"
#include "pbrkit/gl/program.h"

namespace pbrkit::gl {

void append_brdf_case(const BrdfCase& c, std::vector<glm::vec4>& out) {
  out.emplace_back(c.wo, 0.0f);
  out.emplace_back(c.wi, 0.0f);
  out.emplace_back(c.base_color, c.metallic);
  out.emplace_back(c.roughness, c.ior, c.specular, c.anisotropy);
  out.emplace_back(c.specular_color, c.iridescence);
  out.emplace_back(c.iridescence_ior, c.iridescence_thickness, 0.0f, 0.0f);
}

std::vector<glm::vec3> eval_brdf_glsl(const std::vector<BrdfCase>& cases,
                                      const BrdfOptions& options, FresnelMode fresnel) {
  if (cases.empty()) return {};
  const Program program = detail::test_program("brdf_test.glsl");
  std::vector<glm::vec4> input;
  input.reserve(cases.size() * 6);
  for (const BrdfCase& c : cases) append_brdf_case(c, input);
  const GeometryModel geometry = direct_geometry(options.model);
  const GLuint energy = create_energy_texture(geometry);
  const GLuint aniso_energy = create_anisotropic_energy_texture();
  program.use();
  program.set("uCount", int(cases.size()));
  program.set("uGeometry", int(geometry));
  program.set("uMultiscatter", options.multiscatter ? 1 : 0);
  program.set("uFresnel", fresnel == FresnelMode::kSchlick ? 0 : 1);
  glBindTextureUnit(0, energy);
  glBindTextureUnit(1, aniso_energy);
  const std::vector<glm::vec4> output = detail::dispatch_cases(input, cases.size());
  const GLuint textures[2] = {energy, aniso_energy};
  glDeleteTextures(2, textures);
  std::vector<glm::vec3> result;
  result.reserve(output.size());
  for (const glm::vec4& v : output) result.emplace_back(v);
  return result;
}

}  // namespace pbrkit::gl
