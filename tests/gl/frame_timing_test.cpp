// The renderer's GPU frame times (GL_TIMESTAMP queries, double-buffered).
#include <optional>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"

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
  EXPECT_EQ(renderer.latest_gpu_time_ms(), first);  // done: its own time
  renderer.render(camera, 64, 64, settings);
  const double latest = renderer.latest_gpu_time_ms();
  const double second = renderer.gpu_time_ms();
  EXPECT_TRUE(latest == first || latest == second) << latest << " " << first << " " << second;
}

}  // namespace
}  // namespace pbrkit::gl
