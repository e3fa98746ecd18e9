// Every command that writes an image names its two files by one rule
// (image/output_paths.h): -o a.exr or b.png, in any case, writes the EXR and the PNG, the
// other beside it with the same stem, and says so; any other name is an error that names
// it, before any work, and writes nothing. What was written is checked by the files' own
// signatures. The viewer's --screenshot follows the same rule:
// tests/viewer/viewer_screenshot_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <ostream>
#include <string>

#include "support/image_files.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

int pbrkit_cli(const std::string& args, std::string* log) {
  return test::run_command(test::cli_path().string() + " " + args, log);
}

// A command that writes an image, without its -o; `inputs` is a directory it may read,
// which make_inputs() fills.
struct Command {
  const char* name;
  std::string (*args)(const fs::path& inputs);
};

// gtest's name for a parameter in ctest's list.
void PrintTo(const Command& command, std::ostream* os) {
  *os << command.name;
}

const std::string kPath = "render furnace --renderer path --spp 2 --width 16 --height 16 ";

const Command kCommands[] = {
    {"render_path", [](const fs::path&) { return kPath; }},
    {"render_gl",
     [](const fs::path&) {
       return std::string(
           "render furnace --renderer gl --msaa 1 --bake-size 16 --width 16 "
           "--height 16 ");
     }},
    {"merge",
     [](const fs::path& in) {
       return "merge " + (in / "part0.exr").string() + " " + (in / "part1.exr").string() + " ";
     }},
    {"denoise", [](const fs::path& in) { return "denoise " + (in / "aovs.exr").string() + " "; }},
};

// What merge and denoise read: two accumulation parts of a render, and a render with the
// denoiser's layers.
void make_inputs(const fs::path& in) {
  std::string log;
  for (const char* range : {"0:1", "1:2"})
    ASSERT_EQ(pbrkit_cli(kPath + "--sample-range " + range + " -o " +
                             (in / (std::string("part") + range[0] + ".exr")).string(),
                         &log),
              0)
        << log;
  ASSERT_EQ(pbrkit_cli(kPath + "--aov denoise -o " + (in / "aovs.exr").string(), &log), 0) << log;
}

class OutputNames : public ::testing::TestWithParam<Command> {};

TEST_P(OutputNames, EitherExtensionWritesBothFilesAndSaysWhich) {
  const fs::path dir = test::scratch_dir();
  ASSERT_NO_FATAL_FAILURE(make_inputs(dir / "in"));
  for (const char* name : {"a.exr", "b.png", "c.EXR"}) {
    const fs::path out = dir / "sub" / name;
    std::string log;
    ASSERT_EQ(pbrkit_cli(GetParam().args(dir / "in") + "-o " + out.string(), &log), 0) << log;
    const fs::path stem = out.parent_path() / out.stem();
    const fs::path exr = out.extension() == ".png" ? fs::path(stem.string() + ".exr") : out;
    const fs::path png = out.extension() == ".png" ? out : fs::path(stem.string() + ".png");
    EXPECT_TRUE(test::is_exr_file(exr)) << exr;
    EXPECT_TRUE(test::is_png_file(png)) << png;
    EXPECT_NE(log.find(png.string() + " and " + exr.string()), std::string::npos) << log;
  }
}

TEST_P(OutputNames, OtherNamesAreAClearErrorAndWriteNothing) {
  const fs::path dir = test::scratch_dir();
  ASSERT_NO_FATAL_FAILURE(make_inputs(dir / "in"));
  fs::create_directories(dir / "out");
  for (const char* name : {"x.jpg", "x", "x.png.tmp"}) {
    const fs::path out = dir / "out" / name;
    std::string log;
    EXPECT_EQ(pbrkit_cli(GetParam().args(dir / "in") + "-o " + out.string(), &log), 1) << log;
    EXPECT_NE(log.find("-o " + out.string()), std::string::npos) << log;
    EXPECT_NE(log.find(".png or .exr"), std::string::npos) << log;
  }
  EXPECT_TRUE(fs::is_empty(dir / "out"));
}

INSTANTIATE_TEST_SUITE_P(Commands, OutputNames, ::testing::ValuesIn(kCommands),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace pbrkit
