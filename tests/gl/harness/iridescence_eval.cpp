#include "gl/harness/iridescence_eval.h"

#include "gl/harness/compute_eval.h"
#include "pbrkit/gl/program.h"

namespace pbrkit::gl {

std::vector<glm::vec3> iridescence_fresnel_glsl(const std::vector<IridescenceCase>& cases) {
  if (cases.empty()) return {};
  const Program program = detail::test_program("iridescence_test.glsl");
  // std430 layout of iridescence_test.glsl's IridescenceCase: two vec4.
  std::vector<glm::vec4> input;
  input.reserve(cases.size() * 2);
  for (const IridescenceCase& c : cases) {
    input.emplace_back(c.cos_theta, c.film_ior, c.thickness_nm, 0.0f);
    input.emplace_back(c.base_F0, 0.0f);
  }
  program.use();
  program.set("uCount", int(cases.size()));
  const std::vector<glm::vec4> output = detail::dispatch_cases(input, cases.size());
  std::vector<glm::vec3> result;
  result.reserve(output.size());
  for (const glm::vec4& v : output) result.emplace_back(v);
  return result;
}

}  // namespace pbrkit::gl
