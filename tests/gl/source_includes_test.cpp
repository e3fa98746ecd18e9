// The OpenGL renderer's C++ files include each other without a loop: a file and its header
// are one part (surface_bindings.h with surface_bindings.cpp), and no part reaches itself
// through the parts it includes. surface_bindings is at the bottom: the other parts read
// their binding points from it, and it includes none of them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "support/test_paths.h"

namespace pbrkit::gl {
namespace {

namespace fs = std::filesystem;

// The parts ("surface_bindings", "renderer", ...) each part's files include, by
// `#include "pbrkit/gl/<part>.h"`, from the public and private folders of the module.
std::map<std::string, std::set<std::string>> part_includes() {
  const fs::path root = pbrkit::test::test_data("x").parent_path().parent_path().parent_path();
  std::map<std::string, std::set<std::string>> graph;
  const std::string prefix = "#include \"pbrkit/gl/";
  for (const fs::path& dir : {root / "src/pbrkit/gl", root / "include/pbrkit/gl"}) {
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
      const fs::path& file = entry.path();
      if (file.extension() != ".h" && file.extension() != ".cpp") continue;
      const std::string part = file.stem().string();
      graph[part];
      std::ifstream in(file);
      for (std::string line; std::getline(in, line);) {
        if (line.rfind(prefix, 0) != 0) continue;
        const std::size_t close = line.find('"', prefix.size());
        if (close == std::string::npos) continue;
        const std::string name = line.substr(prefix.size(), close - prefix.size());
        if (name.find('/') != std::string::npos) continue;  // a subfolder's: not one of the parts
        const std::string included = fs::path(name).stem().string();
        if (included != part) graph[part].insert(included);
      }
    }
  }
  return graph;
}

// Depth-first search; the loop's parts, first to last, where `part` reaches one.
bool find_loop(const std::string& part, const std::map<std::string, std::set<std::string>>& graph,
               std::map<std::string, int>& marks, std::vector<std::string>& path) {
  marks[part] = 1;  // on the path
  path.push_back(part);
  const auto it = graph.find(part);
  if (it != graph.end())
    for (const std::string& next : it->second) {
      const int mark = marks.count(next) ? marks[next] : 0;
      if (mark == 1) {
        path.push_back(next);
        return true;
      }
      if (mark == 0 && find_loop(next, graph, marks, path)) return true;
    }
  marks[part] = 2;  // done
  path.pop_back();
  return false;
}

TEST(GlSourceIncludes, ThePartsIncludeEachOtherWithoutALoop) {
  const auto graph = part_includes();
  ASSERT_GE(graph.size(), 10u);
  std::map<std::string, int> marks;
  for (const auto& [part, includes] : graph) {
    if (marks.count(part)) continue;
    std::vector<std::string> path;
    ASSERT_FALSE(find_loop(part, graph, marks, path)) << [&] {
      std::string loop;
      for (const std::string& p : path) loop += p + " -> ";
      return loop;
    }();
  }
}

TEST(GlSourceIncludes, SurfaceBindingsIsAtTheBottom) {
  const auto graph = part_includes();
  ASSERT_TRUE(graph.count("surface_bindings"));
  EXPECT_TRUE(graph.at("surface_bindings").empty());
}

}  // namespace
}  // namespace pbrkit::gl
