// ProgressiveRender, the viewer's path view: snapshots arrive while the render runs, a new
// job (the camera moved) restarts the accumulation, and a finished job's image is exactly
// render_path's for its settings, its film with it.
#include <chrono>
#include <memory>
#include <thread>

#include <gtest/gtest.h>

#include "pbrkit/pt/progressive_render.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"

namespace pbrkit {
namespace {

ProgressiveSnapshot wait_for(const ProgressiveRender& r, std::uint64_t job, double spp,
                             bool complete) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  std::uint64_t seen = 0;
  ProgressiveSnapshot last;
  while (std::chrono::steady_clock::now() < deadline) {
    if (auto s = r.latest(seen)) {
      seen = s->serial;
      last = std::move(*s);
      if (last.job == job && last.spp >= spp && (!complete || last.complete)) return last;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ADD_FAILURE() << "no snapshot of job " << job << " with " << spp << " spp in time";
  return last;
}

TEST(ProgressiveRender, RestartsOnANewViewAndEndsAtTheRenderOfThatView) {
  auto scene = std::make_shared<const Scene>(builtin_scene("cornell"));
  const Camera front = select_view(*scene, std::nullopt, 48, 36).camera;
  Camera moved = front;
  moved.camera_to_world[3] += glm::vec4(0.3f, 0.1f, -0.5f, 0.0f);

  ProgressiveJob job;
  job.scene = scene;
  job.camera = front;
  job.settings.width = 48;
  job.settings.height = 36;
  job.settings.spp = 1 << 14;  // far more than the test waits for
  job.settings.min_spp = 1;
  job.settings.noise_threshold = 0.0f;
  job.settings.threads = 2;
  job.settings.checkpoint_interval = 0.01;
  ProgressiveRender r;
  const std::uint64_t first = r.start(job);
  const ProgressiveSnapshot before = wait_for(r, first, 8.0, false);
  EXPECT_GE(before.spp, 8.0);

  job.camera = moved;
  job.settings.spp = 16;
  const std::uint64_t second = r.start(job);
  EXPECT_GT(second, first);
  // The first snapshot of the new view is the preview or a low sample count, never the
  // old view's.
  std::uint64_t seen = 0;
  std::optional<ProgressiveSnapshot> next;
  for (int i = 0; i < 20000 && !next; ++i) {
    next = r.latest(seen);
    if (!next) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ(next->job, second);
  EXPECT_LT(next->spp, before.spp);
  const ProgressiveSnapshot done = wait_for(r, second, 16.0, true);

  PathTracerSettings s = job.settings;
  s.checkpoint_interval = 0.0;
  const PathTracerResult fresh = render_path(*scene, nullptr, moved, s);
  EXPECT_EQ(done.color.data, fresh.color.data);
  // The final snapshot carries its film (what the viewer's denoise reads), the same one;
  // the running ones do not (a copy per checkpoint would cost the window its frames).
  EXPECT_FALSE(before.film);
  ASSERT_TRUE(done.film);
  EXPECT_EQ(done.film->color().data, fresh.color.data);
  // And not the first view's image: the restart used the new camera.
  s.spp = 16;
  EXPECT_NE(done.color.data, render_path(*scene, nullptr, front, s).color.data);
}

}  // namespace
}  // namespace pbrkit
