#include "gl/harness/compute_eval.h"

#include <epoxy/gl.h>

#include <mutex>
#include <string_view>
#include <utility>

#include "pbrkit/gl/shaders.h"

namespace pbrkit::gl {

namespace detail {

// harness/shaders/*_test.glsl (embed_shaders.cmake, as the library's own shaders).
extern const std::pair<std::string_view, std::string_view> kTestShaders[];

Program test_program(std::string_view file) {
  static std::once_flag added;
  std::call_once(added, [] { add_shader_table(kTestShaders); });
  return Program::compute(file);
}

std::vector<glm::vec4> dispatch_cases(const std::vector<glm::vec4>& input, std::size_t count) {
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  glNamedBufferStorage(buffers[0], GLsizeiptr(input.size() * sizeof(glm::vec4)), input.data(), 0);
  glNamedBufferStorage(buffers[1], GLsizeiptr(count * sizeof(glm::vec4)), nullptr, GL_MAP_READ_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<glm::vec4> output(count);
  glGetNamedBufferSubData(buffers[1], 0, GLsizeiptr(output.size() * sizeof(glm::vec4)),
                          output.data());
  glDeleteBuffers(2, buffers);
  return output;
}

}  // namespace detail

}  // namespace pbrkit::gl
