// The viewer's screenshots are named as every image output is (image/output_paths.h):
// `pbrkit view --screenshot a.exr` or `b.png`, in any case, writes the EXR and the PNG, the
// other beside it, and says so; any other name is refused before a window opens (by the
// command, naming its flag, and by run_viewer itself) and writes nothing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "pbrkit/util/error.h"
#include "support/image_files.h"
#include "support/test_paths.h"
#include "viewer/viewer.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

bool have_xvfb_run() {
  return std::system("command -v xvfb-run > /dev/null 2>&1") == 0;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ViewerScreenshot, EitherExtensionWritesBothFilesAndSaysWhich) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed";
  const fs::path dir = test::scratch_dir();
  for (const char* name : {"a.exr", "b.png", "c.EXR"}) {
    const fs::path out = dir / "sub" / name;
    const fs::path log = dir / (std::string(name) + ".log");
    const std::string command = "xvfb-run -a -s '-screen 0 1280x720x24' " +
                                test::cli_path().string() +
                                " view furnace --width 64 --height 64 --msaa 1 --exit"
                                " --screenshot " +
                                out.string() + " > " + log.string() + " 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << read_text(log);
    const fs::path stem = out.parent_path() / out.stem();
    const fs::path exr = out.extension() == ".png" ? fs::path(stem.string() + ".exr") : out;
    const fs::path png = out.extension() == ".png" ? out : fs::path(stem.string() + ".png");
    EXPECT_TRUE(test::is_exr_file(exr)) << exr;
    EXPECT_TRUE(test::is_png_file(png)) << png;
    EXPECT_NE(read_text(log).find("wrote " + png.string() + " and " + exr.string()),
              std::string::npos)
        << read_text(log);
  }
}

// No X display is needed: the name is refused before the window opens.
TEST(ViewerScreenshot, OtherNamesAreRefusedBeforeAWindowOpens) {
  const fs::path dir = test::scratch_dir();
  fs::create_directories(dir / "out");
  for (const char* name : {"x.jpg", "x", "x.png.tmp"}) {
    const fs::path out = dir / "out" / name;
    std::string log;
    EXPECT_EQ(test::run_command("DISPLAY= " + test::cli_path().string() +
                                    " view furnace --exit --screenshot " + out.string(),
                                &log),
              1)
        << log;
    EXPECT_NE(log.find("--screenshot " + out.string()), std::string::npos) << log;
    EXPECT_NE(log.find(".png or .exr"), std::string::npos) << log;

    ViewerOptions options;
    options.scene = "furnace";
    options.exit_when_done = true;
    options.screenshot = out.string();
    try {
      run_viewer(options);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(out.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(".png or .exr"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::is_empty(dir / "out"));
}

}  // namespace
}  // namespace pbrkit
