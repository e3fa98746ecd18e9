// `pbrkit view` under a virtual X server (xvfb-run), as CI runs it: start the viewer, render
// a few frames, take a screenshot, quit; the screenshot must show the lit furnace sphere in
// the middle (grey-white, shaded) on the chosen solid background colour (red), i.e. the
// renderer drew into the window's context and the display transform ran. And the
// viewer's defaults (MSAA by rasteriser, the IBL bake of the headless renderer).
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/viewer/viewer.h"
#include "support/test_paths.h"

namespace {

bool have_xvfb_run() {
  return std::system("command -v xvfb-run > /dev/null 2>&1") == 0;
}

TEST(Viewer, RendersFramesAndScreenshotUnderXvfb) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("pbrkit_view_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::filesystem::path png = dir / "shot.png";
  const std::string command = std::string("xvfb-run -a -s '-screen 0 1280x720x24' ") +
                              pbrkit::test::cli_path().string() +
                              " view furnace --width 160 --height 120 --frames 3 --msaa 1"
                              " --background color:1,0,0 --tonemap none --screenshot " +
                              png.string() + " > " + (dir / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "log.txt");
  ASSERT_TRUE(std::filesystem::exists(png));
  ASSERT_TRUE(std::filesystem::exists(dir / "shot.exr"));

  const pbrkit::Image image = pbrkit::read_image(png);  // decoded to linear
  ASSERT_EQ(image.width, 160);
  ASSERT_EQ(image.height, 120);
  // Background: the solid colour, exactly (tone mapper none).
  const glm::vec3 corner = image.rgb(2, 2);
  EXPECT_NEAR(corner.r, 1.0f, 0.01f);
  EXPECT_NEAR(corner.g, 0.0f, 0.01f);
  // Centre: the white sphere lit by the city environment, a neutral-ish grey that is
  // neither the background nor black (the diffuse white sphere under city.exr is about
  // 0.5 in linear radiance at the centre, see the headless tests).
  const glm::vec3 centre = image.rgb(80, 60);
  EXPECT_GT(centre.g, 0.3f);
  EXPECT_LT(centre.g, 0.8f);
  EXPECT_LT(std::abs(centre.r - centre.g), 0.15f);
  // And it is shaded: the top of the sphere (facing the bright sky) is brighter than the
  // bottom.
  EXPECT_GT(image.rgb(80, 25).g, image.rgb(80, 95).g);
  std::filesystem::remove_all(dir);
}

// The viewer's interactive defaults: no MSAA on software rasterisers (4x MSAA costs about
// 2.5x the frame on llvmpipe), 4x on GPUs; and the IBL bake of `pbrkit render --renderer
// gl`, so the viewer shows what a headless render writes.
TEST(Viewer, InteractiveDefaults) {
  EXPECT_EQ(pbrkit::gl::interactive_msaa("llvmpipe (LLVM 15.0.6, 256 bits)"), 1);
  EXPECT_EQ(pbrkit::gl::interactive_msaa("softpipe"), 1);
  EXPECT_EQ(pbrkit::gl::interactive_msaa("Google SwiftShader"), 1);
  EXPECT_EQ(pbrkit::gl::interactive_msaa("NVIDIA H100 80GB HBM3/PCIe/SSE2"), 4);
  EXPECT_EQ(pbrkit::gl::interactive_msaa("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.6)"),
            4);
  const pbrkit::ViewerOptions options;
  EXPECT_EQ(options.msaa, 0);  // 0: chosen from the context
  const pbrkit::BakeOptions bake = pbrkit::gl::realtime_bake_options();
  EXPECT_EQ(options.bake_size, bake.face_size);
  EXPECT_EQ(options.bake_samples, bake.samples);
}

}  // namespace
