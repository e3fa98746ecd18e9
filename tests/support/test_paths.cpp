#include "support/test_paths.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <sys/wait.h>
#include <array>
#include <cstdio>

namespace pbrkit::test {

std::filesystem::path test_data(const std::string& name) {
  return std::filesystem::path(PBRKIT_TEST_DATA_DIR) / name;
}

std::filesystem::path shared_asset(const std::string& name) {
  return std::filesystem::path(PBRKIT_ASSETS_DIR) / name;
}

std::filesystem::path cli_path() {
  return PBRKIT_CLI_PATH;
}

std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "test";
  for (char& c : name)
    if (c == '/') c = '_';
  const auto dir = std::filesystem::temp_directory_path() /
                   ("pbrkit-test-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

int run_command(const std::string& command, std::string* output) {
  std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buf;
  std::string out;
  while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe)) out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  if (output) *output = out;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string validate_gltf(const std::filesystem::path& path) {
  const std::filesystem::path tool =
      std::filesystem::path(PBRKIT_TEST_DATA_DIR).parent_path().parent_path() / "tools" /
      "gltf-validator";
  if (!std::filesystem::exists(tool / "node_modules" / "gltf-validator"))
    return "the Khronos glTF-Validator is not installed in " + tool.string() +
           " (scripts/setup installs it with npm)";
  std::string out;
  const int code =
      run_command("node '" + (tool / "validate.js").string() + "' '" + path.string() + "'", &out);
  return code == 0 ? std::string() : out;
}

}  // namespace pbrkit::test
