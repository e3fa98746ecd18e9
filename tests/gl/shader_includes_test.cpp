// The embedded shaders' #include graph (shaders.h) is acyclic: expand_shader() includes each
// file once, so a cycle would not fail to compile but would make a file's text depend on
// which of the cycle's files a program starts from.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "pbrkit/gl/shaders.h"

namespace pbrkit::gl {
namespace {

// The files `name` names in its `#include "..."` lines, in order.
std::vector<std::string> includes_of(std::string_view name) {
  std::vector<std::string> files;
  const std::string_view text = shader_source(name);
  constexpr std::string_view kInclude = "#include \"";
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    if (line.substr(0, kInclude.size()) == kInclude) {
      const std::size_t close = line.find('"', kInclude.size());
      if (close != std::string_view::npos)
        files.emplace_back(line.substr(kInclude.size(), close - kInclude.size()));
    }
    pos = end + 1;
  }
  return files;
}

enum class Mark { kOnPath, kDone };

// Depth-first search; the cycle's files, first to last, where `name` reaches one.
bool find_cycle(const std::string& name, std::map<std::string, Mark>& marks,
                std::vector<std::string>& path) {
  marks[name] = Mark::kOnPath;
  path.push_back(name);
  for (const std::string& next : includes_of(name)) {
    const auto it = marks.find(next);
    if (it != marks.end() && it->second == Mark::kOnPath) {
      path.push_back(next);
      return true;
    }
    if (it == marks.end() && find_cycle(next, marks, path)) return true;
  }
  marks[name] = Mark::kDone;
  path.pop_back();
  return false;
}

TEST(GlShaderIncludes, TheIncludeGraphHasNoCycle) {
  std::map<std::string, Mark> marks;
  for (const std::string& name : shader_names()) {
    std::vector<std::string> path;
    if (marks.count(name)) continue;
    ASSERT_FALSE(find_cycle(name, marks, path)) << [&] {
      std::string s;
      for (const std::string& p : path) s += p + " -> ";
      return s;
    }();
  }
  EXPECT_GT(marks.size(), 10u);  // every embedded shader was visited
}

// The search above finds a cycle where there is one (a check that cannot fail proves
// nothing): brdf.glsl's includes reach math.glsl, and a path that already holds math.glsl
// sees the edge back to it as a cycle.
TEST(GlShaderIncludes, TheSearchSeesAnEdgeBackOntoThePath) {
  std::map<std::string, Mark> marks{{"math.glsl", Mark::kOnPath}};
  std::vector<std::string> path{"math.glsl"};
  EXPECT_TRUE(find_cycle("brdf.glsl", marks, path));
  EXPECT_EQ(path.back(), "math.glsl");
}

}  // namespace
}  // namespace pbrkit::gl
