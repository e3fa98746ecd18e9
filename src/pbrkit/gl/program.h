#pragma once
// A linked GLSL program built from embedded shader files (shaders.h), with uniform
// setters by name. Compile and link errors become pbrkit::Error with the driver's log and
// the file name.
#include <string>
#include <string_view>

#include <glm/glm.hpp>

namespace pbrkit::gl {

class Program {
 public:
  Program() = default;
  /// Vertex + fragment program from two embedded files.
  static Program graphics(std::string_view vertex_file, std::string_view fragment_file,
                          std::string_view defines = {});
  /// Compute program from one embedded file.
  static Program compute(std::string_view compute_file, std::string_view defines = {});

  ~Program();
  Program(Program&& other) noexcept;
  Program& operator=(Program&& other) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  unsigned id() const { return id_; }
  void use() const;

  int location(const char* name) const;
  void set(const char* name, int v) const;
  void set(const char* name, float v) const;
  void set(const char* name, glm::ivec3 v) const;
  void set(const char* name, glm::vec2 v) const;
  void set(const char* name, glm::vec3 v) const;
  void set(const char* name, glm::vec4 v) const;
  void set(const char* name, const glm::mat3& v) const;
  void set(const char* name, const glm::mat4& v) const;

 private:
  unsigned id_ = 0;
};

}  // namespace pbrkit::gl
