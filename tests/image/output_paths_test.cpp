// The one rule for the names of image outputs (image/output_paths.h): a .png or .exr name,
// in any case, is that file and the other goes beside it with the same stem; any other
// name is an error that says where the name came from and what it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "pbrkit/image/output_paths.h"
#include "pbrkit/util/error.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

TEST(ImageOutputPaths, EitherExtensionNamesBothFilesWithOneStem) {
  struct Case {
    const char* name;
    const char* png;
    const char* exr;
  };
  const Case cases[] = {
      {"x.png", "x.png", "x.exr"},
      {"out/x.exr", "out/x.png", "out/x.exr"},
      {"shot.exr", "shot.png", "shot.exr"},  // the two files differ whichever is named
      {"d/x.EXR", "d/x.png", "d/x.EXR"},
      {"d/x.Png", "d/x.Png", "d/x.exr"},
      {"a.b.png", "a.b.png", "a.b.exr"},  // only the last extension is the format's
      {"dir.exr/x.png", "dir.exr/x.png", "dir.exr/x.exr"},
  };
  for (const Case& c : cases) {
    const ImageOutputPaths out = image_output_paths(c.name, "-o");
    EXPECT_EQ(out.png, c.png) << c.name;
    EXPECT_EQ(out.exr, c.exr) << c.name;
  }
}

TEST(ImageOutputPaths, OtherNamesAreAnErrorNamingWhereTheNameCameFrom) {
  for (const char* name : {"x.jpg", "x", "x.png.tmp", ".exr", "out.png/", "x.hdr"}) {
    try {
      image_output_paths(name, "--screenshot");
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(std::string("--screenshot ") + name), std::string::npos) << message;
      EXPECT_NE(message.find(".png or .exr"), std::string::npos) << message;
    }
  }
}

TEST(ImageOutputPaths, CreatesTheOutputsDirectory) {
  const fs::path dir = test::scratch_dir();
  create_output_directory(image_output_paths((dir / "a" / "b" / "x.exr").string(), "-o"));
  EXPECT_TRUE(fs::is_directory(dir / "a" / "b"));
  EXPECT_NO_THROW(create_output_directory(image_output_paths("x.png", "-o")));
}

}  // namespace
}  // namespace pbrkit
