// The viewer's animations: the playback clock (viewer/playback.h: looping wraps, without a
// loop it stops at the end, the speed scales wall-clock time), the state's poses
// (load_scene_into with --animation, apply_pose while playing and paused, on a headless
// context), and `pbrkit view --animation --animation-time` under Xvfb: the screenshot
// shows the pose, moved by the pixels worked out by hand.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/image/image_io.h"
#include "scene/gltf_builder.h"
#include "support/test_paths.h"
#include "viewer/playback.h"
#include "viewer/viewer_state.h"

namespace pbrkit {
namespace {

using viewer::advance;
using viewer::Playback;

Playback playing(float start, float end, float time, bool loop, float speed = 1.0f) {
  Playback p;
  viewer::choose_animation(p, 0, start, end);
  p.time = time;
  p.loop = loop;
  p.speed = speed;
  p.playing = true;
  return p;
}

TEST(Playback, LoopingWrapsIntoTheAnimationsRange) {
  Playback p = playing(1.0f, 3.0f, 2.5f, true);
  EXPECT_TRUE(advance(p, 0.25));
  EXPECT_FLOAT_EQ(p.time, 2.75f);
  // 2.75 + 1 = 3.75: past the end by 0.75, so 0.75 after the start.
  EXPECT_TRUE(advance(p, 1.0));
  EXPECT_FLOAT_EQ(p.time, 1.75f);
  EXPECT_TRUE(p.playing);
  // Several lengths in one step (a slow frame at a high speed) still land in range:
  // 1.75 + 4 * 2.1 = 10.15, 9.15 after the start, 1.15 past four lengths of 2.
  p.speed = 4.0f;
  EXPECT_TRUE(advance(p, 2.1));
  EXPECT_NEAR(p.time, 2.15f, 1e-5f);
  // Backwards it wraps from the start to the end: 2.15 - 1.5 = 0.65, 0.35 before the
  // start, so 0.35 before the end.
  p.speed = -1.0f;
  EXPECT_TRUE(advance(p, 1.5));
  EXPECT_NEAR(p.time, 2.65f, 1e-5f);
}

TEST(Playback, WithoutLoopItStopsAtTheEndAndPlayStartsOver) {
  Playback p = playing(0.0f, 2.0f, 1.5f, false);
  EXPECT_TRUE(advance(p, 1.0));
  EXPECT_FLOAT_EQ(p.time, 2.0f);
  EXPECT_FALSE(p.playing);
  EXPECT_FALSE(advance(p, 1.0));  // stopped: no change
  EXPECT_FLOAT_EQ(p.time, 2.0f);
  viewer::play(p);
  EXPECT_TRUE(p.playing);
  EXPECT_FLOAT_EQ(p.time, 0.0f);
  // Backwards it stops at the start.
  p.speed = -2.0f;
  p.time = 0.5f;
  EXPECT_TRUE(advance(p, 1.0));
  EXPECT_FLOAT_EQ(p.time, 0.0f);
  EXPECT_FALSE(p.playing);
}

TEST(Playback, SpeedScalesTheWallClock) {
  Playback p = playing(0.0f, 10.0f, 1.0f, true, 0.5f);
  advance(p, 1.0);
  EXPECT_FLOAT_EQ(p.time, 1.5f);
  p.speed = 3.0f;
  advance(p, 0.5);
  EXPECT_FLOAT_EQ(p.time, 3.0f);
}

TEST(Playback, PausedRestAndZeroLengthAnimationsStayPut) {
  Playback p = playing(0.0f, 2.0f, 1.0f, true);
  p.playing = false;
  EXPECT_FALSE(advance(p, 1.0));
  EXPECT_FLOAT_EQ(p.time, 1.0f);
  // A one-key animation: looping cannot divide by its length.
  Playback still = playing(0.5f, 0.5f, 0.5f, true);
  EXPECT_FALSE(advance(still, 1.0));
  EXPECT_FLOAT_EQ(still.time, 0.5f);
  // The rest pose neither plays nor advances; choosing another range clamps the time.
  viewer::choose_animation(p, -1, 0.0f, 0.0f);
  viewer::play(p);
  EXPECT_FALSE(p.playing);
  p.time = 5.0f;
  viewer::choose_animation(p, 1, 1.0f, 3.0f);
  EXPECT_FLOAT_EQ(p.time, 3.0f);
}

// A white unlit triangle (-1,-1,0) (1,-1,0) (0,1,0) on node 0, seen by a camera at
// (0, 0, 8) down -z with a 90 degree field of view: 16 units across the view at the
// triangle's depth. Animation "slide" moves node 0 from (0,0,0) at 1 s to (4,2,0) at 3 s.
std::filesystem::path sliding_triangle() {
  test::GltfBuilder b;
  const int mesh = b.mesh({b.primitive({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {0, 1, 2}, 0)});
  b.gltf["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}}},
                          {"doubleSided", true},
                          {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}}};
  b.gltf["extensionsUsed"] = {"KHR_materials_unlit"};
  b.node({{"mesh", mesh}});
  b.gltf["cameras"] = {
      {{"type", "perspective"},
       {"perspective", {{"yfov", 1.5707963}, {"aspectRatio", 1}, {"znear", 0.1}}}}};
  b.node({{"camera", 0}, {"translation", {0, 0, 8}}});
  const std::vector<float> times = {1.0f, 3.0f};
  const int t = b.accessor(times.data(), 8, 5126, "SCALAR", 2);
  b.gltf["accessors"][std::size_t(t)]["min"] = {1.0f};
  b.gltf["accessors"][std::size_t(t)]["max"] = {3.0f};
  const std::vector<glm::vec3> move = {{0, 0, 0}, {4, 2, 0}};
  b.gltf["animations"] = {
      {{"name", "slide"},
       {"samplers", {{{"input", t}, {"output", b.floats(move)}}}},
       {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}};
  return b.write("sliding_triangle.glb");
}

TEST(ViewerAnimation, StatePosesOnLoadAndRestartsThePathViewOnlyWhenPaused) {
  gl::HeadlessContext context;
  gl::Renderer renderer;
  viewer::ViewerState s;
  s.options.scene = sliding_triangle().string();
  s.options.animation = "slide";
  s.options.animation_time = 2.0f;
  viewer::load_scene_into(s, renderer);
  EXPECT_EQ(s.playback.animation, 0);
  EXPECT_FLOAT_EQ(s.playback.start, 1.0f);
  EXPECT_FLOAT_EQ(s.playback.end, 3.0f);
  // At 2 s, half way: + (2, 1, 0).
  Bounds b = s.scene.world_bounds();
  EXPECT_NEAR(b.min.x, 1.0f, 1e-5f);
  EXPECT_NEAR(b.max.y, 2.0f, 1e-5f);

  // Playing: each pose goes to the scene and the path tracer's next copy, but the path
  // view is not restarted.
  s.path_dirty = s.path_scene_dirty = false;
  viewer::set_playing(s, renderer, true);
  EXPECT_FALSE(s.path_dirty);
  ASSERT_TRUE(advance(s.playback, 0.5));
  viewer::apply_pose(s, renderer);
  EXPECT_NEAR(s.scene.world_bounds().min.x, 2.0f, 1e-5f);  // 2.5 s: + (3, 1.5, 0)
  EXPECT_TRUE(s.path_scene_dirty);
  EXPECT_FALSE(s.path_dirty);
  // Paused: it restarts on the pose shown, and a reload keeps animation and time.
  viewer::set_playing(s, renderer, false);
  EXPECT_TRUE(s.path_dirty);
  EXPECT_EQ(s.options.animation, "slide");
  EXPECT_FLOAT_EQ(s.options.animation_time, 2.5f);
  viewer::load_scene_into(s, renderer);
  EXPECT_NEAR(s.scene.world_bounds().min.x, 2.0f, 1e-5f);
  // The rest pose again.
  viewer::set_animation(s, renderer, -1);
  EXPECT_NEAR(s.scene.world_bounds().min.x, -1.0f, 1e-5f);
  EXPECT_TRUE(s.options.animation.empty());
}

bool have_xvfb_run() {
  return std::system("command -v xvfb-run > /dev/null 2>&1") == 0;
}

// The mean position (x, y) of the pixels the white triangle covers in `pbrkit view`'s
// screenshot of the scene with `args`.
glm::vec2 viewed_centroid(const std::string& args, const std::string& name) {
  const std::filesystem::path dir = test::scratch_dir();
  const std::filesystem::path png = dir / (name + ".png");
  const std::string command = "xvfb-run -a -s '-screen 0 640x480x24' " + test::cli_path().string() +
                              " view " + sliding_triangle().string() + " " + args +
                              " --width 64 --height 64 --frames 3 --msaa 1 --no-env"
                              " --tonemap none --screenshot " +
                              png.string() + " > " + (dir / (name + ".log")).string() + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << "see " << (dir / (name + ".log"));
  if (!std::filesystem::exists(dir / (name + ".exr"))) return glm::vec2(-1.0f);
  const Image image = read_image(dir / (name + ".exr"));
  EXPECT_EQ(image.width, 64);
  glm::dvec2 sum(0.0);
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.pixel(x, y)[1] > 0.5f) {
        sum += glm::dvec2(x, y);
        ++count;
      }
  EXPECT_GT(count, 10) << name << ": the triangle is not in the screenshot";
  return count ? glm::vec2(sum / double(count)) : glm::vec2(-1.0f);
}

TEST(ViewerAnimation, ViewStartsPosedByTheCommandLinesAnimation) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed";
  const glm::vec2 rest = viewed_centroid("", "rest");
  const glm::vec2 posed = viewed_centroid("--animation slide --animation-time 2", "slide");
  // 64 pixels over 16 units: 4 a unit, so (2, 1, 0) is 8 pixels right and 4 up.
  EXPECT_NEAR(posed.x - rest.x, 8.0f, 0.25f);
  EXPECT_NEAR(posed.y - rest.y, -4.0f, 0.25f);
}

}  // namespace
}  // namespace pbrkit
