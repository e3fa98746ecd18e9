// Issue 12's truth table: how far the OpenGL renderer's screen-space refraction
// (transmission.glsl) is from the path tracer's transmission (core/transmission.h, the
// medium stack in pt/) on the built-in `glass` and `liquid` scenes, lit by the built-in
// environment. Each object's pixels are those where it is the first surface seen (a GL
// pass drawing every instance unlit in its own id colour), eroded by one pixel so that
// silhouettes, where a pixel mixes objects differently in the two renderers, do not count.
// The relative error of each object's mean radiance is printed as a table
// (docs/SPLIT_SUM_ERRORS.md, "Glass and liquids", records it) and the transmissive
// objects' errors are held to the bounds measured for that scene. With
// PBRKIT_TRUTH_TABLE_DIR set, the two renders are written there as EXR for the page's
// heatmaps (`pbrkit compare --heatmap`).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"

namespace pbrkit::gl {
namespace {

constexpr int kWidth = 480, kHeight = 270;

// Per pixel, the instance seen first (-1: none), from a GL frame of the scene where every
// instance is unlit in the colour (i + 1) / 1024 (read back exactly from the float target).
std::vector<int> instance_ids(const Scene& scene, const Camera& camera) {
  Scene ids = scene;
  ids.materials.clear();
  for (std::size_t i = 0; i < ids.instances.size(); ++i) {
    Material m;
    m.unlit = true;
    m.base_color_factor = glm::vec4(float(i + 1) / 1024.0f, 0.0f, 0.0f, 1.0f);
    ids.materials.push_back(m);
    Mesh mesh = ids.meshes[std::size_t(ids.instances[i].mesh)];
    mesh.material = int(i);
    ids.meshes.push_back(std::move(mesh));
    ids.instances[i].mesh = int(ids.meshes.size()) - 1;
  }
  RenderSettings settings;
  settings.msaa = 1;
  settings.ibl = false;
  settings.lights = false;
  settings.background.mode = Background::Mode::kColor;
  settings.background.color = glm::vec3(0.0f);
  const Image image = render_headless(ids, camera, kWidth, kHeight, nullptr, nullptr, settings);
  std::vector<int> id(std::size_t(kWidth) * kHeight, -1);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      id[std::size_t(y) * kWidth + std::size_t(x)] =
          int(std::lround(image.rgb(x, y).r * 1024.0f)) - 1;
  // Erode: a pixel counts only if its 8 neighbours see the same instance.
  std::vector<int> eroded(id.size(), -1);
  for (int y = 1; y + 1 < kHeight; ++y)
    for (int x = 1; x + 1 < kWidth; ++x) {
      const int c = id[std::size_t(y) * kWidth + std::size_t(x)];
      bool same = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          same = same && id[std::size_t(y + dy) * kWidth + std::size_t(x + dx)] == c;
      if (same) eroded[std::size_t(y) * kWidth + std::size_t(x)] = c;
    }
  return eroded;
}

struct TruthCase {
  const char* scene;
  double mean_bound;   ///< bound on the mean |error| over the scene's transmissive objects
  double worst_bound;  ///< bound on the largest |error| among them
};

class GlassTruthTable : public ::testing::TestWithParam<TruthCase> {};

TEST_P(GlassTruthTable, ScreenSpaceRefractionWithinMeasuredBound) {
  testing::context();
  const TruthCase& tc = GetParam();
  const Scene scene = builtin_scene(tc.scene);
  const Camera camera = select_camera(scene, std::nullopt, float(kWidth) / kHeight);
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  const IblMaps maps = ibl_maps_from_bake(bake_environment(env, realtime_bake_options()), env);
  RenderSettings gl_settings;
  gl_settings.msaa = 1;
  const Image gl = render_headless(scene, camera, kWidth, kHeight, &env, &maps, gl_settings);
  for (float f : gl.data) ASSERT_TRUE(std::isfinite(f));

  PathTracerSettings pt;
  pt.width = kWidth;
  pt.height = kHeight;
  pt.spp = 64;
  pt.noise_threshold = 0.0f;
  pt.max_bounces = 24;  // glass: two interfaces per object, total internal reflection
  pt.filter = PixelFilter::kBox;
  const Image truth = render_path(scene, &env, camera, pt).color;
  if (const char* dir = std::getenv("PBRKIT_TRUTH_TABLE_DIR")) {
    write_exr(std::filesystem::path(dir) / (std::string(tc.scene) + "_gl.exr"), gl);
    write_exr(std::filesystem::path(dir) / (std::string(tc.scene) + "_pt.exr"), truth);
  }

  const std::vector<int> ids = instance_ids(scene, camera);
  std::vector<double> sum_gl(scene.instances.size()), sum_pt(scene.instances.size());
  std::vector<int> pixels(scene.instances.size());
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const int i = ids[std::size_t(y) * kWidth + std::size_t(x)];
      if (i < 0 || std::size_t(i) >= scene.instances.size()) continue;
      const glm::vec3 a = gl.rgb(x, y), b = truth.rgb(x, y);
      sum_gl[std::size_t(i)] += a.r + a.g + a.b;
      sum_pt[std::size_t(i)] += b.r + b.g + b.b;
      ++pixels[std::size_t(i)];
    }
  std::printf(
      "%s: relative error of each object's mean radiance, GL vs path tracer (%u spp, %d "
      "bounces), %dx%d\n",
      tc.scene, pt.spp, pt.max_bounces, kWidth, kHeight);
  double worst = 0.0, sum = 0.0;
  int counted = 0;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Mesh& mesh = scene.meshes[std::size_t(scene.instances[i].mesh)];
    const Material& m = scene.material_of(mesh);
    const bool transmissive = m.transmission.has_value() || m.diffuse_transmission.has_value();
    const int n = pixels[i];
    if (n < 100 || !(sum_pt[i] > 0.0)) {
      std::printf("  %-20s %-18s (too few pixels: %d)\n", mesh.name.c_str(), m.name.c_str(), n);
      continue;
    }
    const double e = (sum_gl[i] - sum_pt[i]) / sum_pt[i];
    std::printf("  %-20s %-18s %+7.3f  (%d px)%s\n", mesh.name.c_str(), m.name.c_str(), e, n,
                transmissive ? "" : "  opaque, for comparison");
    if (!transmissive) continue;
    worst = std::max(worst, std::abs(e));
    sum += std::abs(e);
    ++counted;
  }
  ASSERT_GT(counted, 0);
  std::printf("  transmissive objects: mean |error| %.4f, largest %.4f\n", sum / counted, worst);
  EXPECT_LT(sum / counted, tc.mean_bound);
  EXPECT_LT(worst, tc.worst_bound);
}

// Bounds: measured on the 2-core Debian 12 machine with llvmpipe (docs/SPLIT_SUM_ERRORS.md,
// "Glass and liquids": mean |error| / largest, seeds 0 and 1 of the path tracer: its noise
// at 64 spp moves an object's error by at most 0.009), plus about 10% for the bake and
// another driver's rounding. They are large because screen-space refraction is a coarse
// model (the page says where and why: one refraction, the frame read at the exit point, no
// shadows or interreflections in what it reads); they pin it so that a regression shows,
// e.g. glass behind glass read from the opaque frame alone puts the filled tumbler at +0.86.
INSTANTIATE_TEST_SUITE_P(Scenes, GlassTruthTable,
                         ::testing::Values(TruthCase{"glass", 0.40, 0.85},    // 0.357 / 0.778
                                           TruthCase{"liquid", 0.21, 0.31}),  // 0.171 / 0.267
                         [](const auto& info) { return std::string(info.param.scene); });

}  // namespace
}  // namespace pbrkit::gl
