// The viewer's truth views under a virtual X server, as CI runs them (`pbrkit view
// --mode ... --exit --screenshot`): the path view is `pbrkit render`'s image of the same
// scene, camera, size, seed and samples; the split view is the raster screenshot left of
// the divider and that image right of it; the difference view is the per-pixel relative
// luminance error of the one against the other, recomputed here from the two screenshots.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "pbrkit/image/image_io.h"
#include "support/test_paths.h"

namespace {

using pbrkit::Image;

bool have_xvfb_run() {
  return std::system("command -v xvfb-run > /dev/null 2>&1") == 0;
}

// `pbrkit view <scene> --mode <mode> ... --exit`: the screenshot's linear EXR.
Image view(const std::string& scene, const std::string& mode, const std::string& args,
           const std::filesystem::path& dir) {
  const std::filesystem::path png = dir / (mode + ".png");
  const std::string command = "xvfb-run -a -s '-screen 0 640x480x24' " +
                              pbrkit::test::cli_path().string() + " view " + scene + " --mode " +
                              mode + " --msaa 1 --exit " + args + " --screenshot " + png.string() +
                              " > " + (dir / (mode + ".log")).string() + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << "see " << (dir / (mode + ".log"));
  if (!std::filesystem::exists(dir / (mode + ".exr"))) return {};
  return pbrkit::read_image(dir / (mode + ".exr"));
}

Image render_path(const std::string& scene, const std::string& args,
                  const std::filesystem::path& dir) {
  const std::string command = pbrkit::test::cli_path().string() + " render " + scene +
                              " --noise-threshold 0 --float " + args + " -o " +
                              (dir / "render.png").string() + " > " +
                              (dir / "render.log").string() + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "render.log");
  return pbrkit::read_image(dir / "render.exr");
}

float luminance(const Image& im, int x, int y) {
  const glm::vec3 c = im.rgb(x, y);
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

TEST(ViewerTruth, PathViewIsTheRenderOfTheSameSamples) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed";
  const auto dir = pbrkit::test::scratch_dir();
  const Image shown = view("cornell", "path", "--spp 12 --seed 5 --width 96 --height 72", dir);
  const Image rendered = render_path("cornell", "--spp 12 --seed 5 --width 96 --height 72", dir);
  ASSERT_EQ(shown.width, 96);
  ASSERT_EQ(shown.height, 72);
  ASSERT_EQ(shown.data.size(), rendered.data.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < shown.data.size(); ++i) differ += shown.data[i] != rendered.data[i];
  EXPECT_EQ(differ, 0u) << "of " << shown.data.size() << " values";
  // Another seed differs: the comparison above can fail.
  const Image other = render_path("cornell", "--spp 12 --seed 6 --width 96 --height 72", dir);
  EXPECT_NE(other.data, shown.data);
}

// With --guiding on (the panel's toggle) the path view is `render --guiding on`'s image:
// a guided render's bits do not depend on the thread count, and differ from unguided ones
// (the sunlit interior, at a size where some regions learn that their guide pays).
TEST(ViewerTruth, GuidedPathViewIsTheGuidedRender) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed";
  const auto dir = pbrkit::test::scratch_dir();
  const std::string args = "--spp 63 --seed 5 --width 96 --height 72";
  const Image shown = view("interior", "path", args + " --guiding on", dir);
  const Image guided = render_path("interior", args + " --guiding on", dir);
  ASSERT_EQ(shown.data.size(), guided.data.size());
  EXPECT_EQ(shown.data, guided.data);
  const Image unguided = render_path("interior", args, dir);
  EXPECT_NE(unguided.data, shown.data);
}

TEST(ViewerTruth, SplitIsRasterLeftAndPathRightAndDifferenceIsTheirError) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed";
  const auto dir = pbrkit::test::scratch_dir();
  const std::string size = "--spp 8 --width 120 --height 90";
  const Image raster = view("spheres", "raster", size, dir);
  const Image split = view("spheres", "split", size + " --split 0.4", dir);
  const Image error = view("spheres", "difference", size, dir);
  const Image path = render_path("spheres", size, dir);
  ASSERT_EQ(raster.width, 120);
  ASSERT_EQ(split.width, 120);
  ASSERT_EQ(error.width, 120);
  ASSERT_EQ(error.channels, 1);
  const int column = 48;  // 0.4 of 120
  std::size_t left_differ = 0, right_differ = 0, raster_path_differ = 0;
  double sum = 0.0, worst = 0.0;
  for (int y = 0; y < 90; ++y)
    for (int x = 0; x < 120; ++x) {
      const glm::vec3 s = split.rgb(x, y);
      if (x < column)
        left_differ += s != raster.rgb(x, y);
      else
        right_differ += s != path.rgb(x, y);
      raster_path_differ += raster.rgb(x, y) != path.rgb(x, y);
      // |Y_raster - Y_path| / (Y_path + 0.01), as pbrkit compare's relative error.
      const float yp = luminance(path, x, y);
      const float e = std::fabs(luminance(raster, x, y) - yp) / (yp + 0.01f);
      sum += e;
      worst = std::max(worst, double(std::fabs(e - error.pixel(x, y)[0])));
    }
  EXPECT_EQ(left_differ, 0u);
  EXPECT_EQ(right_differ, 0u);
  EXPECT_GT(raster_path_differ, 1000u);  // the two halves come from different images
  EXPECT_LT(worst, 1e-5) << "the error view is not the raster image's error against the path";
  EXPECT_GT(sum / (120.0 * 90.0), 0.01);  // a non-trivial error map
}

}  // namespace
