// The OpenGL renderer's option values on the command line (apps/pbrkit/gl_options.cpp):
// a malformed --background is refused with an error that names the flag, by both commands
// that take it, before any OpenGL context or window is asked for (so `pbrkit view` reports
// it even on a machine without an X display).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "support/test_paths.h"

namespace {

// Runs `pbrkit <arguments>`; expects it to fail and returns what it printed.
std::string failing_run(const std::string& arguments) {
  std::string output;
  // DISPLAY unset: were the viewer to open its window before parsing, it would fail with
  // GLFW's message instead of the option's.
  const int status = pbrkit::test::run_command(
      "env -u DISPLAY " + pbrkit::test::cli_path().string() + " " + arguments, &output);
  EXPECT_EQ(status, 1) << output;
  return output;
}

TEST(GlCliOptions, RenderRefusesAMalformedBackground) {
  // Nothing is rendered: the output directory stays empty.
  const std::filesystem::path out = pbrkit::test::scratch_dir();
  const auto render = [&](const std::string& background) {
    return failing_run("render furnace --renderer gl --background " + background + " -o " +
                       (out / "x.png").string());
  };
  EXPECT_NE(render("color:1,2").find("--background: expected color:<r>,<g>,<b>, got 'color:1,2'"),
            std::string::npos);
  EXPECT_NE(render("blur:x").find("--background: 'x' is not a number (in 'blur:x')"),
            std::string::npos);
  EXPECT_NE(
      render("sky").find("--background: expected env, blur:<mip> or color:<r>,<g>,<b>, got 'sky'"),
      std::string::npos);
  EXPECT_TRUE(std::filesystem::is_empty(out));
}

TEST(GlCliOptions, ViewRefusesAMalformedBackgroundBeforeOpeningAWindow) {
  EXPECT_NE(failing_run("view furnace --background blur:-1")
                .find("--background: the blur mip must be >= 0, got 'blur:-1'"),
            std::string::npos);
}

}  // namespace
