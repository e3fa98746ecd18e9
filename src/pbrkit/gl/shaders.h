#pragma once
// The GLSL sources of src/pbrkit/gl/shaders/, embedded into the library at build time
// (embed_shaders.cmake). A line `#include "file.glsl"` in a shader is replaced by that
// file's text (once per file), so the model's functions live in one file (brdf.glsl) that
// every program and the shader unit test share.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pbrkit::gl {

/// The text of an embedded shader file, e.g. "brdf.glsl". Throws pbrkit::Error if absent.
std::string_view shader_source(std::string_view name);

/// The text of `name` with its #include lines expanded (recursively, each file once).
std::string expand_shader(std::string_view name);

/// Names of every embedded shader file.
std::vector<std::string> shader_names();

/// Adds a table of further shader files, (name, text) pairs ending with an empty name, that
/// shader_source() searches after the library's own (a test-support library's shader unit
/// tests, which the installed library does not carry). The table must outlive every lookup.
void add_shader_table(const std::pair<std::string_view, std::string_view>* table);

}  // namespace pbrkit::gl
