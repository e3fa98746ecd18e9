#include "pbrkit/gl/testing/transmission_eval.h"

#include "pbrkit/gl/program.h"
#include "pbrkit/gl/testing/compute_eval.h"

namespace pbrkit::gl {

std::vector<glm::vec4> eval_transmission_glsl(const std::vector<TransmissionCase>& cases,
                                              TransmissionFunction function,
                                              const glm::mat4& view_projection) {
  if (cases.empty()) return {};
  const Program program = detail::test_program("transmission_test.glsl");
  // std430 layout of transmission_test.glsl's TransmissionCase: eight vec4.
  std::vector<glm::vec4> input;
  input.reserve(cases.size() * 8);
  for (const TransmissionCase& c : cases) {
    input.emplace_back(c.n, c.ior);
    input.emplace_back(c.v, c.thickness);
    input.emplace_back(c.model_scale, c.dispersion);
    input.emplace_back(c.attenuation_color, c.attenuation_distance);
    input.emplace_back(c.roughness, c.width, c.distance, 0.0f);
    input.emplace_back(c.base_color, c.metallic);
    input.emplace_back(c.back_point, 0.0f);
    input.emplace_back(c.back_normal, 0.0f);
  }
  program.use();
  program.set("uCount", int(cases.size()));
  program.set("uFunction", int(function));
  program.set("uViewProjection", view_projection);
  return detail::dispatch_cases(input, cases.size());
}

}  // namespace pbrkit::gl
