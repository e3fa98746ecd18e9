#include "gl/harness/display_eval.h"

#include "gl/harness/compute_eval.h"
#include "pbrkit/gl/program.h"

namespace pbrkit::gl {

std::vector<glm::vec3> display_transform_glsl(const std::vector<glm::vec3>& linear,
                                              float exposure_ev, ToneMapper mapper) {
  if (linear.empty()) return {};
  const Program program = detail::test_program("display_test.glsl");
  std::vector<glm::vec4> input;
  input.reserve(linear.size());
  for (const glm::vec3& c : linear) input.emplace_back(c, 0.0f);
  program.use();
  program.set("uCount", int(linear.size()));
  program.set("uExposureScale", exposure_scale(exposure_ev));
  program.set("uToneMapper", int(mapper));
  const std::vector<glm::vec4> output = detail::dispatch_cases(input, linear.size());
  std::vector<glm::vec3> result;
  result.reserve(output.size());
  for (const glm::vec4& v : output) result.emplace_back(v);
  return result;
}

}  // namespace pbrkit::gl
