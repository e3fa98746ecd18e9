// `pbrkit render` end to end: the image's aspect (a sphere at the centre of a wide image is
// round), the options' effects, merge's refusal of a non-accumulation file. What -o writes
// is tested with every other image-writing command in output_names_test.cpp.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "pbrkit/image/image_io.h"
#include "pbrkit/pt/film.h"
#include "pbrkit/util/error.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

std::string render(const std::string& args, int* code) {
  std::string output;
  *code = test::run_command(test::cli_path().string() + " render " + args, &output);
  return output;
}

// Width and height in pixels of the connected region of pixels for which `inside` holds
// that contains the image's centre (4-connected flood fill).
glm::ivec2 centre_extent(int w, int h, const std::function<bool(int, int)>& inside) {
  std::vector<char> seen(std::size_t(w) * h, 0);
  std::vector<glm::ivec2> stack{{w / 2, h / 2}};
  glm::ivec2 lo(w, h), hi(-1, -1);
  while (!stack.empty()) {
    const glm::ivec2 p = stack.back();
    stack.pop_back();
    if (p.x < 0 || p.y < 0 || p.x >= w || p.y >= h) continue;
    char& s = seen[std::size_t(p.y) * w + p.x];
    if (s || !inside(p.x, p.y)) continue;
    s = 1;
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    for (const glm::ivec2 d :
         {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)})
      stack.push_back(p + d);
  }
  return glm::max(hi - lo + 1, glm::ivec2(0));
}

// The built-in spheres' camera was authored for a square image (aspectRatio 1). Rendered
// 2:1, the centre sphere must stay round: a stretched projection makes it twice as wide as
// tall. The sphere is told from the background by the depth AOV (path tracer: 0 where no
// sample hit; 16 samples a pixel widen it by at most a pixel on every side alike) and by
// a background colour no lit pixel has (GL, one sample at each pixel centre).
TEST(RenderAspect, CentreSphereOfAWideImageIsRoundInBothRenderers) {
  const fs::path dir = test::scratch_dir();
  const int w = 480, h = 240;
  const std::string size = " --width " + std::to_string(w) + " --height " + std::to_string(h);
  int code = 0;
  std::string log = render(
      "spheres --renderer path --spp 16 --noise-threshold 0 --filter box "
      "--max-bounces 1 --aov depth" +
          size + " -o " + (dir / "path.exr").string(),
      &code);
  ASSERT_EQ(code, 0) << log;
  Image depth;
  for (auto& [name, image] : read_exr_layers(dir / "path.exr"))
    if (name.find("depth") != std::string::npos) depth = image;
  ASSERT_EQ(depth.width, w);
  const glm::ivec2 path =
      centre_extent(w, h, [&](int x, int y) { return depth.pixel(x, y)[0] > 0.0f; });
  EXPECT_GT(path.y, 20);
  EXPECT_LE(std::abs(path.x - path.y), 1) << "width " << path.x << " height " << path.y;

  log = render("spheres --renderer gl --msaa 1 --no-ibl --background color:1,0,0" + size + " -o " +
                   (dir / "gl.exr").string(),
               &code);
  ASSERT_EQ(code, 0) << log;
  const Image gl = read_image(dir / "gl.exr");
  ASSERT_EQ(gl.width, w);
  const glm::ivec2 raster =
      centre_extent(w, h, [&](int x, int y) { return gl.rgb(x, y) != glm::vec3(1, 0, 0); });
  EXPECT_GT(raster.y, 20);
  EXPECT_LE(std::abs(raster.x - raster.y), 1) << "width " << raster.x << " height " << raster.y;
  // Both renderers see the same sphere.
  EXPECT_LE(std::abs(raster.y - path.y), 2);
}

// Multiple-scattering compensation is on by default for `reference` and off for `classic`;
// --multiscatter / --no-multiscatter override either. The GL renderer is
// deterministic, so "the same setting" is bit-identical and a different one is not: the
// rough metals of `spheres` gain up to 2x with compensation.
TEST(RenderCli, CompensationDefaultsFollowTheModel) {
  const fs::path dir = test::scratch_dir();
  auto render_gl = [&](const std::string& flags, const std::string& name) {
    int code = 0;
    const std::string log = render("spheres --renderer gl --msaa 1 --width 96 --height 96 " +
                                       flags + " -o " + (dir / (name + ".exr")).string(),
                                   &code);
    EXPECT_EQ(code, 0) << log;
    return read_image(dir / (name + ".exr"));
  };
  const Image ref_default = render_gl("", "ref_default");
  const Image ref_on = render_gl("--multiscatter", "ref_on");
  const Image ref_off = render_gl("--no-multiscatter", "ref_off");
  const Image classic_default = render_gl("--model classic", "classic_default");
  const Image classic_off = render_gl("--model classic --no-multiscatter", "classic_off");
  const Image classic_on = render_gl("--model classic --multiscatter", "classic_on");
  EXPECT_EQ(ref_default.data, ref_on.data);
  EXPECT_NE(ref_default.data, ref_off.data);
  EXPECT_EQ(classic_default.data, classic_off.data);
  EXPECT_NE(classic_default.data, classic_on.data);
}

// A built-in scene rendered by the GL renderer (96x64, no MSAA) with `flags`, as `name`.exr
// in `dir`.
Image render_small_gl(const fs::path& dir, const std::string& scene, const std::string& flags,
                      const std::string& name) {
  int code = 0;
  const std::string log = render(scene + " --renderer gl --msaa 1 --width 96 --height 64 " + flags +
                                     " -o " + (dir / (name + ".exr")).string(),
                                 &code);
  EXPECT_EQ(code, 0) << log;
  return read_image(dir / (name + ".exr"));
}

// The built-in `glass` rendered by the GL renderer as is and with `flag`, and the check that
// `spheres`, where nothing transmits, renders the same either way.
struct GlassOnOff {
  Image on, off;
};
GlassOnOff glass_with_and_without(const std::string& flag) {
  const fs::path dir = test::scratch_dir();
  EXPECT_EQ(render_small_gl(dir, "spheres", "", "spheres_on").data,
            render_small_gl(dir, "spheres", flag, "spheres_off").data)
      << flag;
  return {render_small_gl(dir, "glass", "", "glass_on"),
          render_small_gl(dir, "glass", flag, "glass_off")};
}

// Transmissive objects shadow the environment light by default; --no-glass-shadows turns it
// off, and only makes the image brighter (the shadows only take light away), and the
// spheres scene (nothing transmits) is the same either way.
TEST(RenderCli, GlassShadowsAreOnByDefaultAndNoGlassShadowsTurnsThemOff) {
  const auto [on, off] = glass_with_and_without("--no-glass-shadows");
  ASSERT_EQ(on.data.size(), off.data.size());
  double sum_on = 0.0, sum_off = 0.0;
  for (std::size_t i = 0; i < on.data.size(); ++i) {
    sum_on += on.data[i];
    sum_off += off.data[i];
    EXPECT_LE(on.data[i], off.data[i] * (1.0f + 1e-5f) + 1e-6f) << i;
  }
  EXPECT_LT(sum_on, 0.99 * sum_off);
}

// Thick glass reflects the frame on the screen by default; --no-glass-reflections makes it
// reflect the environment alone. Only the thick glass objects' pixels change (the five
// objects of `glass` cover under a tenth of its frame), and a scene without them renders the
// same either way.
TEST(RenderCli, GlassReflectionsAreOnByDefaultAndNoGlassReflectionsTurnsThemOff) {
  const auto [on, off] = glass_with_and_without("--no-glass-reflections");
  ASSERT_EQ(on.data.size(), off.data.size());
  const std::size_t pixels = std::size_t(on.width) * std::size_t(on.height);
  std::size_t changed = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    bool differs = false;
    for (std::size_t c = 0; c < std::size_t(on.channels); ++c)
      differs |=
          on.data[p * std::size_t(on.channels) + c] != off.data[p * std::size_t(on.channels) + c];
    changed += differs;
  }
  EXPECT_GT(changed, 0u);
  EXPECT_LT(changed, pixels / 10);
}

// Opaque objects cast no shadow in the environment light unless --opaque-shadows: with it
// `glass`'s floor, whose sky the wall behind it hides, is darker (the wall sends back less
// than the sky it hides under the built-in environment; docs/MODEL.md, "Shadows of opaque
// objects"), and so is the image as a whole.
TEST(RenderCli, OpaqueShadowsAreOffByDefaultAndDarkenTheFloorInFrontOfTheWall) {
  const fs::path dir = test::scratch_dir();
  const Image plain = render_small_gl(dir, "glass", "", "plain");
  const Image shadowed = render_small_gl(dir, "glass", "--opaque-shadows", "shadowed");
  ASSERT_EQ(plain.data.size(), shadowed.data.size());
  // The image's bottom quarter is floor in front of the glass objects.
  double floor_plain = 0.0, floor_shadowed = 0.0, all_plain = 0.0, all_shadowed = 0.0;
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) {
      const glm::vec3 a = plain.rgb(x, y), b = shadowed.rgb(x, y);
      all_plain += a.r + a.g + a.b;
      all_shadowed += b.r + b.g + b.b;
      if (4 * y >= 3 * plain.height) {
        floor_plain += a.r + a.g + a.b;
        floor_shadowed += b.r + b.g + b.b;
      }
    }
  EXPECT_LT(floor_shadowed, 0.97 * floor_plain);
  EXPECT_LT(all_shadowed, 0.97 * all_plain);
}

// Without --width/--height the image takes the camera's authored aspect (512 along the
// longer side); with one of them, the other follows the aspect.
TEST(RenderAspect, SizeFollowsTheCamerasAspectRatio) {
  const fs::path dir = test::scratch_dir();
  const std::string scene = test::test_data("gltf/valid/cameras_lights.gltf").string();
  struct Case {
    std::string args;
    int width, height;
  };
  // Camera 0: perspective, aspectRatio 1.5. Camera 1: orthographic, xmag 2, ymag 1.
  const std::array<Case, 4> cases{{{"--camera 0", 512, 341},
                                   {"--camera 0 --width 300", 300, 200},
                                   {"--camera 1 --height 100", 200, 100},
                                   {"--camera 1 --width 64 --height 64", 64, 64}}};
  for (const Case& c : cases) {
    int code = 0;
    const std::string log = render(
        scene + " --spp 1 --max-bounces 1 " + c.args + " -o " + (dir / "x.png").string(), &code);
    ASSERT_EQ(code, 0) << log;
    const Image png = read_image(dir / "x.png");
    EXPECT_EQ(png.width, c.width) << c.args;
    EXPECT_EQ(png.height, c.height) << c.args;
  }
}

}  // namespace
}  // namespace pbrkit

namespace pbrkit {
namespace {

// The library says what is wrong with a file that is not an accumulation EXR; only the
// command line names the flags that write one.
TEST(MergeCli, ANonAccumulationFileNamesTheCommandsThatWriteOne) {
  const fs::path dir = test::scratch_dir();
  int code = 0;
  std::string log =
      render("furnace --spp 1 --width 8 --height 8 -o " + (dir / "a.exr").string(), &code);
  ASSERT_EQ(code, 0) << log;
  ASSERT_EQ(test::run_command(test::cli_path().string() + " merge " + (dir / "a.exr").string() +
                                  " -o " + (dir / "m.png").string(),
                              &log),
            1);
  EXPECT_NE(log.find("not a pbrkit accumulation file"), std::string::npos) << log;
  EXPECT_NE(log.find("--sample-range"), std::string::npos) << log;
  try {
    read_film(dir / "a.exr");
    ADD_FAILURE() << "read_film accepted a plain EXR";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pbrkit
