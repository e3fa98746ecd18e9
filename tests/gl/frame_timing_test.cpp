// The renderer's GPU frame times (GL_TIMESTAMP queries, double-buffered): positive, larger
// for a frame of known larger cost, and latest_gpu_time_ms() never waiting for the frame
// just submitted.
#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::gl {
namespace {

// The viewer's frame time never waits for the frame just submitted: latest_gpu_time_ms()
// is the last frame's time once it is done, else the frame before's; 0 before any frame.
TEST(GlFrameTiming, LatestGpuTimeIsAFinishedFramesTime) {
  testing::context();
  Renderer renderer;
  EXPECT_EQ(renderer.latest_gpu_time_ms(), 0.0);
  renderer.set_scene(builtin_scene("furnace"));
  const Camera camera = select_camera(builtin_scene("furnace"), std::nullopt, 1.0f);
  RenderSettings settings;
  settings.msaa = 1;
  renderer.render(camera, 64, 64, settings);
  glFinish();
  const double first = renderer.gpu_time_ms();
  EXPECT_GT(first, 0.0);                            // a frame that drew something took time
  EXPECT_EQ(renderer.latest_gpu_time_ms(), first);  // done: its own time
  renderer.render(camera, 64, 64, settings);
  const double latest = renderer.latest_gpu_time_ms();
  const double second = renderer.gpu_time_ms();
  EXPECT_GT(second, 0.0);
  EXPECT_TRUE(latest == first || latest == second) << latest << " " << first << " " << second;
}

// `layers` blended quads, each covering the whole view of a camera at the origin looking
// down -Z: blending writes no depth, so every layer shades every pixel and the frame's
// fragment work is proportional to `layers`.
Scene overlapping_layers(int layers) {
  Scene scene;
  Material glass;
  glass.alpha_mode = AlphaMode::kBlend;
  glass.base_color_factor = glm::vec4(0.8f, 0.6f, 0.4f, 0.5f);
  glass.metallic_factor = 0.0f;
  glass.roughness_factor = 0.5f;
  scene.materials.push_back(glass);
  for (int i = 0; i < layers; ++i) {
    const float z = -1.0f - 0.01f * float(i);
    add_mesh_instance(scene, make_quad({-2.0f, -2.0f, z}, {4.0f, 0.0f, 0.0f}, {0.0f, 4.0f, 0.0f}),
                      0);
  }
  Light sun;
  sun.type = Light::Type::kDirectional;
  sun.direction = glm::vec3(0.0f, 0.0f, -1.0f);
  scene.lights.push_back(sun);
  return scene;
}

TEST(GlFrameTiming, GpuTimeGrowsWithTheFramesWork) {
  // Two frames of the same size, one with 4x the fragment work of the other (8 full-frame
  // layers against 2): the heavy one must time at least 1.5x the light one (4x less the
  // fixed cost of a frame; measured 3.0-3.5x on llvmpipe, 2 cores). Each time is the minimum
  // over 5 interleaved frames: on a shared machine preemption only ever adds time.
  //
  // The frame size: llvmpipe bins a frame into 64 x 64 tiles and records a timestamp in
  // every tile, reporting the latest, so a begin/end pair spans about the last tile's work
  // rather than the whole frame (measured: one layer at 256 x 256, 16 tiles, 0.23-0.26 ms
  // against 0.17 ms at 64 x 64, not 16x). A 64 x 64 frame is one tile there; on a GPU such
  // a frame is all fixed cost, so it draws 1024 x 1024.
  testing::context();
  const int size = is_software_renderer(current_renderer()) ? 64 : 1024;
  const Camera camera;  // at the origin, looking down -Z
  RenderSettings settings;
  settings.msaa = 1;
  Renderer light, heavy;
  light.set_scene(overlapping_layers(2));
  heavy.set_scene(overlapping_layers(8));
  double light_ms = std::numeric_limits<double>::infinity(), heavy_ms = light_ms;
  for (int frame = 0; frame < 6; ++frame) {
    light.render(camera, size, size, settings);
    const double l = light.gpu_time_ms();
    heavy.render(camera, size, size, settings);
    const double h = heavy.gpu_time_ms();
    if (frame == 0) continue;  // the first frame compiles the programs
    light_ms = std::min(light_ms, l);
    heavy_ms = std::min(heavy_ms, h);
  }
  std::printf("GPU time of 2 layers %.3f ms, 8 layers %.3f ms (%s, %d x %d)\n", light_ms, heavy_ms,
              current_renderer().c_str(), size, size);
  EXPECT_GT(light_ms, 0.0);
  EXPECT_GT(heavy_ms, 1.5 * light_ms)
      << "light " << light_ms << " ms, heavy " << heavy_ms << " ms on " << current_renderer();
}

}  // namespace
}  // namespace pbrkit::gl
