// The path view's denoiser (viewer/path_view.h): it denoises a finished render once, with
// the project's denoiser, and again only when the accumulation has reached another final
// image; running snapshots (no film) are never denoised.
#include <chrono>
#include <memory>
#include <thread>

#include <gtest/gtest.h>

#include "pbrkit/denoise/denoiser.h"
#include "pbrkit/denoise/denoiser_choice.h"
#include "pbrkit/denoise/inputs.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "viewer/path_view.h"

namespace pbrkit {
namespace {

// A complete snapshot numbered `serial` of a small cornell render.
ProgressiveSnapshot finished(std::uint64_t serial) {
  const Scene scene = builtin_scene("cornell");
  PathTracerSettings s;
  s.width = 24;
  s.height = 18;
  s.spp = 8;
  s.min_spp = 1;
  s.noise_threshold = 0.0f;
  s.threads = 2;
  const Camera camera = select_view(scene, std::nullopt, s.width, s.height).camera;
  PathTracerResult r = render_path(scene, nullptr, camera, s);
  ProgressiveSnapshot snap;
  snap.color = r.color;
  snap.complete = true;
  snap.serial = serial;
  snap.film = std::make_shared<const Film>(std::move(r.film));
  return snap;
}

void wait(PathDenoiser& d) {
  for (int i = 0; i < 2000 && !d.poll(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

TEST(PathDenoiser, DenoisesEachFinalImageOnce) {
  PathDenoiser d;
  DenoiserChoice learned;
  learned.kind = DenoiserKind::kLearned;
  ProgressiveSnapshot running = finished(1);
  running.complete = false;
  running.film.reset();
  d.request(running, learned);
  EXPECT_FALSE(d.busy());  // nothing to denoise before the target

  const ProgressiveSnapshot snap = finished(2);
  d.request(snap, learned);
  EXPECT_TRUE(d.busy());
  wait(d);
  ASSERT_NE(d.result(2), nullptr);
  EXPECT_FALSE(d.error());
  // The chosen denoiser on the film's half buffers, bit for bit (it is deterministic).
  EXPECT_EQ(d.result(2)->data, denoise_render(denoise_input(*snap.film), learned).image.data);
  EXPECT_EQ(d.result(1), nullptr);

  d.request(snap, learned);  // the same image again: nothing recomputed
  EXPECT_FALSE(d.busy());
  ProgressiveSnapshot next = snap;
  next.serial = 3;  // the accumulation advanced to another final image
  DenoiserChoice classic;
  classic.kind = DenoiserKind::kClassic;
  d.request(next, classic);
  EXPECT_TRUE(d.busy());
  wait(d);
  ASSERT_NE(d.result(3), nullptr);
  EXPECT_EQ(d.result(2), nullptr);  // only the newest is kept
  // The classic denoiser when it is chosen (the two differ on a noisy film).
  EXPECT_EQ(d.result(3)->data, denoise(denoise_input(*snap.film)).data);
  EXPECT_NE(d.result(3)->data, denoise_render(denoise_input(*snap.film), learned).image.data);
}

TEST(PathDenoiser, KeepsTheLoadedWeightsForEveryImage) {
  // The weights are read once: the network given by use() (as `pbrkit view --denoise`
  // loads it before the window opens) denoises every image of its choice, and is kept.
  DenoiserChoice learned;
  learned.kind = DenoiserKind::kLearned;
  const LoadedDenoiser loaded = load_denoiser(learned);
  PathDenoiser d;
  d.use(loaded);
  for (std::uint64_t serial : {2u, 3u}) {
    ProgressiveSnapshot snap = finished(2);
    snap.serial = serial;
    d.request(snap, learned);
    wait(d);
    ASSERT_NE(d.result(serial), nullptr);
    EXPECT_EQ(d.result(serial)->data, denoise_render(denoise_input(*snap.film), loaded).image.data);
  }
  EXPECT_EQ(loaded.learned.use_count(), 2);  // this test's and the view's: not read again
}

}  // namespace
}  // namespace pbrkit
