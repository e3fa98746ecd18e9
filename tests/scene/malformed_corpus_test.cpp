// The malformed corpus (tests/data/gltf/malformed, written by make_test_files.py): every
// file must fail with a pbrkit::Error naming the file and containing its expected message,
// and the CLI must exit non-zero with that message (no crash, no hang).
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

std::vector<std::pair<std::string, std::string>> corpus() {
  std::ifstream in(test::test_data("gltf/malformed/expected.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [file, message] : j.items()) out.emplace_back(file, message.get<std::string>());
  return out;
}

TEST(MalformedCorpus, HasAtLeast25Files) {
  EXPECT_GE(corpus().size(), 25u);
}

TEST(MalformedCorpus, EveryFileFailsWithItsExpectedError) {
  const LogSink previous = set_log_sink([](LogLevel, const std::string&) {});
  for (const auto& [file, message] : corpus()) {
    const std::string path = test::test_data("gltf/malformed/" + file).string();
    try {
      load_scene(path);
      ADD_FAILURE() << file << " loaded without an error";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos)
          << file << ": the error does not name the file: " << what;
      EXPECT_NE(what.find(message), std::string::npos)
          << file << ": expected '" << message << "' in: " << what;
    }
  }
  set_log_sink(previous);
}

TEST(MalformedCorpus, CliExitsNonZeroWithTheMessage) {
  for (const std::string file : {"truncated.glb", "cyclic_nodes.gltf", "uri_escapes_folder.gltf"}) {
    std::string output;
    const std::string path = test::test_data("gltf/malformed/" + file).string();
    const int status =
        test::run_command(test::cli_path().string() + " info '" + path + "'", &output);
    EXPECT_EQ(status, 1) << output;
    EXPECT_NE(output.find("pbrkit: error: " + path), std::string::npos) << output;
  }
}

}  // namespace
}  // namespace pbrkit
