#include "pbrkit/util/data_dir.h"

#include <dlfcn.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

bool holds_data(const std::filesystem::path& dir) {
  std::error_code ec;
  return std::filesystem::is_regular_file(dir / "env" / "city.exr", ec);
}

// The file (executable or shared library) this function was linked into: dladdr maps a
// code address to the object that holds it, so a static library linked into a program
// finds the program's directory.
std::filesystem::path this_binary() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<const void*>(&this_binary), &info) == 0 || !info.dli_fname)
    return {};
  std::error_code ec;
  auto path = std::filesystem::canonical(info.dli_fname, ec);
  return ec ? std::filesystem::path(info.dli_fname) : path;
}

}  // namespace

std::filesystem::path data_dir() {
  std::vector<std::filesystem::path> tried;
  if (const char* env = std::getenv("PBRKIT_DATA_DIR"); env && *env) {
    // An explicit setting is the user's choice: no silent fallback when it is wrong.
    if (holds_data(env)) return env;
    fail("PBRKIT_DATA_DIR={}: no env/city.exr there (unset it to use the installed data)", env);
  }
  if (const auto binary = this_binary(); !binary.empty()) {
    const auto dir = binary.parent_path().parent_path() / "share" / "pbrkit";
    if (holds_data(dir)) return dir;
    tried.push_back(dir);
  }
  const std::filesystem::path installed = PBRKIT_INSTALL_DATA_DIR;
  if (holds_data(installed)) return installed;
  tried.push_back(installed);
  std::string list;
  for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t.string();
  fail("pbrkit's data (env/city.exr) not found in {}; set PBRKIT_DATA_DIR to its directory", list);
}

}  // namespace pbrkit
