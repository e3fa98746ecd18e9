#include "pbrkit/gl/shaders.h"

#include <mutex>
#include <set>
#include <utility>

#include "pbrkit/util/error.h"

namespace pbrkit::gl {
namespace detail {
extern const std::pair<std::string_view, std::string_view> kShaders[];
}  // namespace detail

namespace {

using ShaderTable = const std::pair<std::string_view, std::string_view>*;

// The library's table first, then those add_shader_table() added.
std::mutex& tables_mutex() {
  static std::mutex m;
  return m;
}
std::vector<ShaderTable>& tables() {
  static std::vector<ShaderTable> t{detail::kShaders};
  return t;
}

}  // namespace

void add_shader_table(const std::pair<std::string_view, std::string_view>* table) {
  const std::lock_guard lock(tables_mutex());
  tables().push_back(table);
}

std::string_view shader_source(std::string_view name) {
  const std::lock_guard lock(tables_mutex());
  for (ShaderTable table : tables())
    for (const auto* s = table; !s->first.empty(); ++s)
      if (s->first == name) return s->second;
  fail("GL shader '{}' is not embedded in this build", name);
}

std::vector<std::string> shader_names() {
  const std::lock_guard lock(tables_mutex());
  std::vector<std::string> names;
  for (ShaderTable table : tables())
    for (const auto* s = table; !s->first.empty(); ++s) names.emplace_back(s->first);
  return names;
}

namespace {

void expand_into(std::string_view name, std::string& out, std::set<std::string>& seen) {
  if (!seen.insert(std::string(name)).second) return;
  const std::string_view text = shader_source(name);
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    constexpr std::string_view kInclude = "#include \"";
    if (line.substr(0, kInclude.size()) == kInclude) {
      const std::size_t close = line.find('"', kInclude.size());
      if (close == std::string_view::npos) fail("GL shader '{}': malformed #include", name);
      expand_into(line.substr(kInclude.size(), close - kInclude.size()), out, seen);
    } else {
      out.append(line);
      out.push_back('\n');
    }
    pos = end + 1;
  }
}

}  // namespace

std::string expand_shader(std::string_view name) {
  std::string out;
  std::set<std::string> seen;
  expand_into(name, out, seen);
  return out;
}

}  // namespace pbrkit::gl
