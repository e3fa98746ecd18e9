#include "gl/harness/transmission_eval.h"

#include <epoxy/gl.h>

#include "gl/harness/compute_eval.h"
#include "pbrkit/gl/program.h"

namespace pbrkit::gl {

namespace {

std::vector<glm::vec4> eval(const std::vector<TransmissionCase>& cases,
                            TransmissionFunction function, const glm::mat4& view_projection) {
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
  program.set("uInverseViewProjection", glm::inverse(view_projection));
  return detail::dispatch_cases(input, cases.size());
}

}  // namespace

std::vector<glm::vec4> eval_transmission_glsl(const std::vector<TransmissionCase>& cases,
                                              TransmissionFunction function,
                                              const glm::mat4& view_projection) {
  if (cases.empty()) return {};
  return eval(cases, function, view_projection);
}

namespace {

// A single-level float texture of `width` x `height` texels, bilinear (level 0 alone is
// complete with these filters) and clamped to its edges as the renderer's captures are,
// bound to `unit`.
GLuint bind_float_texture(int unit, GLenum internal, GLenum format, int width, int height,
                          const float* data) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, internal, width, height);
  glTextureSubImage2D(texture, 0, 0, 0, width, height, format, GL_FLOAT, data);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTextureUnit(GLuint(unit), texture);
  return texture;
}

void unbind_texture(int unit, GLuint texture) {
  glBindTextureUnit(GLuint(unit), 0);
  glDeleteTextures(1, &texture);
}

}  // namespace

namespace {

std::vector<glm::vec4> eval_with_depth(const std::vector<TransmissionCase>& cases,
                                       TransmissionFunction function, const FrameDepth& depth,
                                       const glm::mat4& view_projection) {
  if (cases.empty()) return {};
  const GLuint texture =
      bind_float_texture(1, GL_R32F, GL_RED, depth.width, depth.height, depth.depth.data());
  std::vector<glm::vec4> out = eval(cases, function, view_projection);
  unbind_texture(1, texture);
  return out;
}

}  // namespace

std::vector<glm::vec4> eval_frame_hit_glsl(const std::vector<TransmissionCase>& cases,
                                           const FrameDepth& depth,
                                           const glm::mat4& view_projection) {
  return eval_with_depth(cases, TransmissionFunction::kFrameHit, depth, view_projection);
}

std::vector<glm::vec4> eval_frame_march_glsl(const std::vector<TransmissionCase>& cases,
                                             const FrameDepth& depth,
                                             const glm::mat4& view_projection) {
  return eval_with_depth(cases, TransmissionFunction::kFrameMarch, depth, view_projection);
}

std::vector<glm::vec4> eval_reflected_frame_glsl(const std::vector<TransmissionCase>& cases,
                                                 const FrameDepth& depth,
                                                 const std::vector<glm::vec4>& colors,
                                                 const glm::mat4& view_projection) {
  if (cases.empty()) return {};
  const GLuint depth_texture =
      bind_float_texture(1, GL_R32F, GL_RED, depth.width, depth.height, depth.depth.data());
  const GLuint color_texture =
      bind_float_texture(2, GL_RGBA32F, GL_RGBA, depth.width, depth.height, &colors.front().x);
  std::vector<glm::vec4> out = eval(cases, TransmissionFunction::kReflectedFrame, view_projection);
  unbind_texture(2, color_texture);
  unbind_texture(1, depth_texture);
  return out;
}

}  // namespace pbrkit::gl
