// `pbrkit view` under a virtual X server (xvfb-run), as CI runs it: start the viewer, render
// a few frames, take a screenshot, quit; the screenshot must show the lit furnace sphere in
// the middle (grey-white, shaded) on the chosen solid background colour (red), i.e. the
// renderer drew into the window's context and the display transform ran. The projection
// and the first view's framing follow the window's aspect. The image is the headless
// renderer's (same IBL bake). And the MSAA default by rasteriser.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/scene/load.h"
#include "support/test_paths.h"
#include "viewer/viewer.h"

namespace {

bool have_xvfb_run() {
  return std::system("command -v xvfb-run > /dev/null 2>&1") == 0;
}

// Runs `pbrkit view <scene>` in a `width` x `height` window for a few frames on a red
// background, without tone mapping; the screenshot (empty if the viewer failed), written
// with its log into `dir`.
pbrkit::Image view(const std::string& scene, int width, int height,
                   const std::filesystem::path& dir) {
  const std::filesystem::path png = dir / "shot.png";
  const std::string command = std::string("xvfb-run -a -s '-screen 0 1280x720x24' ") +
                              pbrkit::test::cli_path().string() + " view " + scene + " --width " +
                              std::to_string(width) + " --height " + std::to_string(height) +
                              " --frames 3 --msaa 1"
                              " --background color:1,0,0 --tonemap none --screenshot " +
                              png.string() + " > " + (dir / "log.txt").string() + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "log.txt");
  EXPECT_TRUE(std::filesystem::exists(dir / "shot.exr"));
  if (!std::filesystem::exists(png)) return {};
  return pbrkit::read_image(png);  // decoded to linear
}

// The bounding box of the furnace sphere's pixels: those with green (the red background
// has none).
struct Extent {
  int x0, x1, y0, y1;
  int across() const { return x1 - x0 + 1; }
  int down() const { return y1 - y0 + 1; }
};
Extent sphere_extent(const pbrkit::Image& image) {
  Extent e{image.width, -1, image.height, -1};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.rgb(x, y).g > 0.05f) {
        e.x0 = std::min(e.x0, x), e.x1 = std::max(e.x1, x);
        e.y0 = std::min(e.y0, y), e.y1 = std::max(e.y1, y);
      }
  return e;
}

TEST(Viewer, RendersFramesAndScreenshotUnderXvfb) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed";
  const std::filesystem::path dir = pbrkit::test::scratch_dir();
  const pbrkit::Image image = view("furnace", 160, 120, dir);
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

// The window's aspect decides the projection, a glTF camera's aspectRatio does not: the
// furnace sphere seen through its scene's camera, given aspectRatio 1, in a 2:1 and a 1:2
// window. A sphere straight ahead projects to a circle, so in the wide window it must be as
// wide as it is high (to a pixel or two: the silhouette is tessellated); with the camera's
// aspect it would be stretched to twice its height. The vertical field of view is the
// camera's in both windows, so the sphere spans the same share of the window's height (and
// overflows the tall window sideways).
TEST(Viewer, ProjectsWithTheWindowsAspect) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed";
  pbrkit::Scene scene = pbrkit::builtin_scene("furnace");
  ASSERT_EQ(scene.cameras.size(), 1u);
  scene.cameras[0].aspect_ratio = 1.0f;
  const std::filesystem::path dir = pbrkit::test::scratch_dir();
  const std::filesystem::path glb = dir / "square_camera.glb";
  pbrkit::write_glb(scene, glb);

  const pbrkit::Image wide = view(glb.string(), 240, 120, dir);
  const pbrkit::Image tall = view(glb.string(), 120, 240, dir);
  ASSERT_EQ(wide.width, 240);
  ASSERT_EQ(tall.height, 240);
  const Extent w = sphere_extent(wide), t = sphere_extent(tall);
  ASSERT_GT(w.down(), 20) << "no sphere";
  EXPECT_NEAR(w.across(), w.down(), 2);
  EXPECT_NEAR(0.5 * (w.x0 + w.x1), 119.5, 1.5);
  EXPECT_NEAR(double(t.down()) / 240.0, double(w.down()) / 120.0, 2.5 / 120.0);
  EXPECT_NEAR(0.5 * (t.y0 + t.y1), 119.5, 1.5);
  std::filesystem::remove_all(dir);
}

// Without a glTF camera the first view is the automatic framing for the window's aspect:
// in a tall window the narrower field of view is the horizontal one, and the whole sphere
// must fit across it, round and centred.
TEST(Viewer, FramesTheSceneForTheWindowsAspect) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed";
  pbrkit::Scene scene = pbrkit::builtin_scene("furnace");
  scene.cameras.clear();
  const std::filesystem::path dir = pbrkit::test::scratch_dir();
  const std::filesystem::path glb = dir / "no_camera.glb";
  pbrkit::write_glb(scene, glb);

  const pbrkit::Image tall = view(glb.string(), 120, 240, dir);
  ASSERT_EQ(tall.width, 120);
  const Extent e = sphere_extent(tall);
  // At least a third of the width: framed, not a speck.
  ASSERT_GT(e.across(), 40) << "no sphere";
  EXPECT_NEAR(e.across(), e.down(), 2);
  EXPECT_GT(e.x0, 0);
  EXPECT_LT(e.x1, 119);
  EXPECT_NEAR(0.5 * (e.x0 + e.x1), 59.5, 1.5);
  EXPECT_NEAR(0.5 * (e.y0 + e.y1), 119.5, 1.5);
  std::filesystem::remove_all(dir);
}

// The viewer shows what a headless render writes: its screenshot's linear EXR equals
// `pbrkit render --renderer gl`'s of the same scene, size, MSAA, background and tone
// mapper, the render left at its other defaults (the IBL bake its --help promises:
// --bake-size 128, --bake-samples 256). The spheres scene, whose smooth metal shows the
// specular cube's resolution: measured identical to the bit on llvmpipe, and off by an RMSE
// of 4e-3 with --bake-size 64 or 256, 9e-5 with --bake-samples 128, so the bound (a
// millionth, for float rounding) holds the viewer to the render's bake, not a neighbour of it.
// `scene` in the viewer's window and from the headless renderer: the same pixels (RMSE
// below `rmse_bound`).
void expect_viewer_matches_headless(const std::string& scene, double rmse_bound = 1e-6) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed";
  const std::filesystem::path dir = pbrkit::test::scratch_dir();
  ASSERT_EQ(view(scene, 160, 120, dir).width, 160);
  const pbrkit::Image shown = pbrkit::read_image(dir / "shot.exr");
  const std::filesystem::path exr = dir / "render.exr";
  // Software rendering, as the viewer under Xvfb (a GPU's arithmetic would differ).
  const std::string command = "LIBGL_ALWAYS_SOFTWARE=1 " + pbrkit::test::cli_path().string() +
                              " render " + scene +
                              " --renderer gl --width 160 --height 120 --msaa 1"
                              " --background color:1,0,0 --tonemap none --float -o " +
                              exr.string() + " > " + (dir / "render_log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "render_log.txt");
  std::ifstream log(dir / "render_log.txt");
  const std::string log_text((std::istreambuf_iterator<char>(log)), {});
  if (log_text.find("llvmpipe") == std::string::npos)
    GTEST_SKIP() << "the headless render ran on another rasteriser than Xvfb's llvmpipe:\n"
                 << log_text;
  const pbrkit::Image rendered = pbrkit::read_image(exr);
  ASSERT_EQ(shown.width, rendered.width);
  ASSERT_EQ(shown.height, rendered.height);
  double sum_sq = 0.0, worst = 0.0;
  for (int y = 0; y < shown.height; ++y)
    for (int x = 0; x < shown.width; ++x)
      for (int k = 0; k < 3; ++k) {
        const double d = double(shown.rgb(x, y)[k]) - double(rendered.rgb(x, y)[k]);
        sum_sq += d * d;
        worst = std::max(worst, std::abs(d));
      }
  const double rmse = std::sqrt(sum_sq / (3.0 * shown.width * shown.height));
  std::printf("%s: RMSE %.3g, largest difference %.3g\n", scene.c_str(), rmse, worst);
  EXPECT_LT(rmse, rmse_bound) << "largest difference " << worst;
  std::filesystem::remove_all(dir);
}

TEST(Viewer, ShowsWhatTheHeadlessRenderWrites) {
  expect_viewer_matches_headless("spheres");
}

// The transmission pass (the frame captured, its mip chain, glass behind glass) runs in the
// window's context as it does headless. `glass` has a glTF camera, which the viewer shows
// exactly until the user moves it (the orbit made from it would give the matrix back only
// within float rounding, moving edge pixels and refracted reads: RMSE 2.7e-3 that way).
TEST(Viewer, ShowsGlassAsTheHeadlessRenderDoes) {
  expect_viewer_matches_headless("glass");
}

// The viewer's interactive defaults: no MSAA on software rasterisers (4x MSAA costs about
// 2.5x the frame on llvmpipe), 4x on GPUs. (Its IBL bake is the headless render's, checked
// by the images above: comparing ViewerOptions' bake fields with realtime_bake_options(),
// which they are initialised from, could not fail.)
TEST(Viewer, InteractiveDefaults) {
  EXPECT_EQ(pbrkit::gl::interactive_msaa("llvmpipe (LLVM 15.0.6, 256 bits)"), 1);
  EXPECT_EQ(pbrkit::gl::interactive_msaa("softpipe"), 1);
  EXPECT_EQ(pbrkit::gl::interactive_msaa("Google SwiftShader"), 1);
  EXPECT_EQ(pbrkit::gl::interactive_msaa("NVIDIA H100 80GB HBM3/PCIe/SSE2"), 4);
  EXPECT_EQ(pbrkit::gl::interactive_msaa("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.6)"),
            4);
  const pbrkit::ViewerOptions options;
  EXPECT_EQ(options.msaa, 0);  // 0: chosen from the context
}

}  // namespace
