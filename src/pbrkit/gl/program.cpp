#include "pbrkit/gl/program.h"

#include <utility>

#include <epoxy/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include "pbrkit/gl/shaders.h"
#include "pbrkit/util/error.h"

namespace pbrkit::gl {

namespace {

// Inserts `defines` after the #version line (which must stay first).
std::string with_defines(std::string text, std::string_view defines) {
  if (defines.empty()) return text;
  const std::size_t eol = text.find('\n');
  text.insert(eol == std::string::npos ? text.size() : eol + 1, std::string(defines) + "\n");
  return text;
}

GLuint compile(GLenum stage, std::string_view file, std::string_view defines) {
  const std::string text = with_defines(expand_shader(file), defines);
  const GLuint shader = glCreateShader(stage);
  const char* source = text.c_str();
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    fail("GL shader {} failed to compile:\n{}", file, log);
  }
  return shader;
}

GLuint link(std::initializer_list<GLuint> shaders, std::string_view what) {
  const GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) glDeleteShader(s);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    fail("GL program {} failed to link:\n{}", what, log);
  }
  return program;
}

}  // namespace

Program Program::graphics(std::string_view vertex_file, std::string_view fragment_file,
                          std::string_view defines) {
  Program p;
  p.id_ = link({compile(GL_VERTEX_SHADER, vertex_file, defines),
                compile(GL_FRAGMENT_SHADER, fragment_file, defines)},
               fragment_file);
  return p;
}

Program Program::compute(std::string_view compute_file, std::string_view defines) {
  Program p;
  p.id_ = link({compile(GL_COMPUTE_SHADER, compute_file, defines)}, compute_file);
  return p;
}

Program::~Program() {
  if (id_) glDeleteProgram(id_);
}
Program::Program(Program&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
Program& Program::operator=(Program&& other) noexcept {
  if (this != &other) {
    if (id_) glDeleteProgram(id_);
    id_ = std::exchange(other.id_, 0);
  }
  return *this;
}

void Program::use() const {
  glUseProgram(id_);
}
int Program::location(const char* name) const {
  return glGetUniformLocation(id_, name);
}
void Program::set(const char* name, int v) const {
  glProgramUniform1i(id_, location(name), v);
}
void Program::set(const char* name, float v) const {
  glProgramUniform1f(id_, location(name), v);
}
void Program::set(const char* name, glm::ivec3 v) const {
  glProgramUniform3iv(id_, location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, glm::vec2 v) const {
  glProgramUniform2fv(id_, location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, glm::vec3 v) const {
  glProgramUniform3fv(id_, location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, glm::vec4 v) const {
  glProgramUniform4fv(id_, location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::mat3& v) const {
  glProgramUniformMatrix3fv(id_, location(name), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::mat4& v) const {
  glProgramUniformMatrix4fv(id_, location(name), 1, GL_FALSE, glm::value_ptr(v));
}

}  // namespace pbrkit::gl
