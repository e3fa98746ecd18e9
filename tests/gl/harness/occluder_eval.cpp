#include "gl/harness/occluder_eval.h"

#include "gl/harness/compute_eval.h"
#include "pbrkit/gl/occluders.h"
#include "pbrkit/gl/program.h"

namespace pbrkit::gl {

std::vector<float> form_factors_glsl(const std::vector<FormFactorCase>& cases) {
  if (cases.empty()) return {};
  const Program program = detail::test_program("occluders_test.glsl");
  std::vector<glm::vec4> input;
  input.reserve(7 * cases.size());
  for (const FormFactorCase& c : cases) {
    input.emplace_back(c.x, c.sphere ? 1.0f : 0.0f);
    input.emplace_back(c.n, 0.0f);
    input.emplace_back(c.center, c.radius);
    const ParallelepipedFaces faces = parallelepiped_faces(c.axes);
    for (const glm::vec4& f : faces.normals) input.push_back(f);
    input.emplace_back(faces.areas, 0.0f);
  }
  program.use();
  program.set("uCount", int(cases.size()));
  const std::vector<glm::vec4> output = detail::dispatch_cases(input, cases.size());
  std::vector<float> result;
  result.reserve(output.size());
  for (const glm::vec4& v : output) result.push_back(v.x);
  return result;
}

}  // namespace pbrkit::gl
