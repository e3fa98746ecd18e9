// The checks every command applies to its options, end to end: a number that is not finite
// is an error naming its option, for every floating-point option of every command (found
// in each command's --help, so an option added later is covered without editing this
// test); and `pbrkit render` refuses each renderer's own options with the other renderer
// (every option of the two --help groups, each alone), writing nothing.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

int run(const std::string& args, std::string* output) {
  return test::run_command("env -u DISPLAY " + test::cli_path().string() + " " + args, output);
}

// The long option names of `pbrkit <command> --help` whose line matches `filter` (within the
// group headed `group`, or in the whole text when `group` is empty).
std::vector<std::string> help_options(const std::string& command, const std::string& group,
                                      const std::string& filter) {
  std::string help;
  EXPECT_EQ(run(command + " --help", &help), 0) << help;
  std::vector<std::string> names;
  std::istringstream in(help);
  std::string line;
  bool in_group = group.empty();
  while (std::getline(in, line)) {
    if (!group.empty() && line.rfind(group, 0) == 0) {
      in_group = true;
      continue;
    }
    if (!group.empty() && in_group && !line.empty() && line[0] != ' ') in_group = false;
    if (!in_group) continue;
    // "  -o,--output TEXT ..." or "  --spp UINT:..." : the first "--" word.
    const std::size_t start = line.find("--");
    if (line.rfind("  ", 0) != 0 || start == std::string::npos || start > 6) continue;
    const std::size_t end = line.find_first_of(" ,=", start);
    if (line.find(filter) == std::string::npos) continue;
    names.push_back(line.substr(start, end - start));
  }
  return names;
}

TEST(OptionChecks, EveryFloatOptionOfEveryCommandRefusesNonFiniteNumbers) {
  int checked = 0;
  for (const char* command :
       {"brdf", "scene", "info", "bake", "render", "merge", "denoise", "compare", "view"}) {
    for (const std::string& name : help_options(command, "", "FLOAT")) {
      for (const char* value : {"nan", "inf", "-inf", "1e999", "1e39"}) {
        std::string log;
        const int code = run(std::string(command) + " " + name + " " + value, &log);
        EXPECT_NE(code, 0) << command << " " << name << " " << value << ": " << log;
        EXPECT_NE(log.find(name), std::string::npos)
            << command << " " << name << " " << value << ": " << log;
      }
      // NaN passes every range check (each comparison is false): the message is ours.
      std::string log;
      run(std::string(command) + " " + name + " nan", &log);
      EXPECT_NE(log.find("'nan' is not a finite number"), std::string::npos)
          << command << " " << name << ": " << log;
      ++checked;
    }
  }
  // render alone has --env-rotation, --env-intensity, --exposure, --time,
  // --noise-threshold, --checkpoint-interval: the --help parse found the options.
  std::printf("%d floating-point options refuse non-finite numbers\n", checked);
  EXPECT_GE(checked, 6);
}

TEST(OptionChecks, BackgroundColourAndBlurMustBeFinite) {
  for (const char* value : {"color:nan,0,0", "color:0,inf,0", "blur:nan", "blur:inf"}) {
    std::string log;
    EXPECT_EQ(run(std::string("render furnace --renderer gl --background ") + value, &log), 1)
        << log;
    EXPECT_NE(log.find("--background"), std::string::npos) << log;
    EXPECT_NE(log.find("is not a finite number"), std::string::npos) << log;
  }
}

// A valid value for each renderer-specific option (flags take none); every option of the
// two groups must be listed, so a new one cannot skip the check.
const std::map<std::string, std::string> kValidValues = {
    {"--spp", "4"},
    {"--time", "1"},
    {"--noise-threshold", "0.1"},
    {"--adaptive", "denoised"},
    {"--min-spp", "2"},
    {"--max-bounces", "4"},
    {"--seed", "3"},
    {"--threads", "1"},
    {"--sample-range", "0:4"},
    {"--checkpoint", "ck.exr"},
    {"--checkpoint-interval", "5"},
    {"--resume", ""},  // an existing file: set below
    {"--aov", "albedo"},
    {"--denoise", ""},
    {"--denoiser", "classic"},
    {"--denoiser-weights", ""},  // a file: set below
    {"--filter", "box"},
    {"--light-sampler", "power"},
    {"--guiding", "on"},
    {"--guiding-bsdf-share", "0.5"},
    {"--irradiance", "cube"},
    {"--msaa", "2"},
    {"--background", "color:1,0,0"},
    {"--fresnel", "sg"},
    {"--bake-size", "16"},
    {"--bake-samples", "8"},
    {"--no-ibl", ""},
    {"--no-lights", ""},
    {"--no-glass-shadows", ""},
    {"--opaque-shadows", ""},
    {"--no-glass-reflections", ""},
    {"--channel", "normal"},
};

TEST(OptionChecks, RenderRefusesTheOtherRenderersOptions) {
  const fs::path dir = test::scratch_dir();
  const fs::path existing = dir / "existing.exr";
  const fs::path out = dir / "out";  // never created: the check comes before any output
  {
    std::string log;
    ASSERT_EQ(run("render furnace --spp 1 --width 4 --height 4 --sample-range 0:1 -o " +
                      existing.string(),
                  &log),
              0)
        << log;
  }
  struct Group {
    const char* heading;  // the --help group
    const char* other;    // the renderer that must refuse its options
    const char* kind;     // what the message calls them
  };
  int checked = 0;
  for (const Group& g :
       {Group{"Path tracer (--renderer path only)", "gl", "path tracer"},
        Group{"OpenGL renderer (--renderer gl only)", "path", "OpenGL renderer"}}) {
    const std::vector<std::string> names = help_options("render", g.heading, "--");
    EXPECT_GE(names.size(), 8u) << g.heading;
    for (const std::string& name : names) {
      const auto it = kValidValues.find(name);
      ASSERT_NE(it, kValidValues.end()) << name << ": add a valid value to kValidValues";
      const std::string value =
          name == "--resume" || name == "--denoiser-weights" ? existing.string() : it->second;
      std::string log;
      const int code =
          run("render furnace --renderer " + std::string(g.other) + " --width 8 --height 8 " +
                  name + " " + value + " -o " + (out / "x.png").string(),
              &log);
      EXPECT_EQ(code, 1) << name << ": " << log;
      EXPECT_NE(log.find("--renderer " + std::string(g.other) + " does not take " + name + ":"),
                std::string::npos)
          << log;
      EXPECT_NE(log.find(g.kind), std::string::npos) << log;
      ++checked;
    }
  }
  EXPECT_GE(checked, 16);
  // The example: both options named, in --help's order.
  std::string log;
  EXPECT_EQ(run("render furnace --renderer gl --denoise --sample-range 0:4 -o " +
                    (out / "x.png").string(),
                &log),
            1);
  EXPECT_NE(log.find("--renderer gl does not take --sample-range, --denoise: path tracer"),
            std::string::npos)
      << log;
  EXPECT_FALSE(fs::exists(out));
  std::printf("%d renderer-specific options refused with the other renderer\n", checked);
}

// The pixel type of an EXR's first channel, from the file's header: the "channels"
// attribute (type "chlist") lists each channel as its name, a null byte and a 4-byte pixel
// type, 1 for HALF and 2 for FLOAT (OpenEXR file layout, "Header Attributes"). -1: not found.
int first_channel_pixel_type(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string header(4096, '\0');
  in.read(header.data(), std::streamsize(header.size()));
  const std::string key("channels\0chlist\0", 16);
  const std::size_t at = header.find(key);
  if (at == std::string::npos) return -1;
  const std::size_t name = at + key.size() + 4;  // after the attribute's size
  const std::size_t type = header.find('\0', name) + 1;
  if (type == 0 || type + 4 > header.size()) return -1;
  return int(std::uint8_t(header[type])) | int(std::uint8_t(header[type + 1])) << 8;
}

TEST(OptionChecks, HalfAndFloatApplyToBothRenderers) {
  const fs::path dir = test::scratch_dir();
  for (const char* renderer : {"path", "gl"})
    for (const char* type : {"", " --half", " --float"}) {
      const std::string fast = std::string(renderer) == "path" ? " --spp 1" : " --msaa 1";
      const fs::path out =
          dir / (std::string(renderer) + std::to_string(std::strlen(type)) + ".exr");
      std::string log;
      ASSERT_EQ(run(std::string("render furnace --renderer ") + renderer + fast +
                        " --width 16 --height 16" + type + " -o " + out.string(),
                    &log),
                0)
          << log;
      // The defaults: half for the path tracer, float for the OpenGL renderer.
      const bool half = std::string(type) == " --half" ||
                        (std::string(type).empty() && std::string(renderer) == "path");
      EXPECT_EQ(first_channel_pixel_type(out), half ? 1 : 2) << renderer << type;
    }
}

}  // namespace
}  // namespace pbrkit
