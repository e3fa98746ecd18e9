// Denoiser-driven adaptive sampling: at the same total sample count it must bring the
// denoised image closer to a reference than uniform sampling, on a scene whose noise is
// uneven; it must be deterministic; and it must refuse what it cannot honour.
#include "pbrkit/denoise/denoiser_driven_sampling.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "pbrkit/denoise/inputs.h"
#include "pbrkit/image/compare.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/pt/film.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

// Relative MSE as the benchmark reports it (pbrkit compare's): mean of (x - ref)^2 /
// (ref^2 + 0.01).
double rel_mse(const Image& x, const Image& ref) {
  return compare_images(x, ref).relative_mse;
}

constexpr int kSize = 48;

PathTracerSettings settings_for(const RenderView& view, std::uint32_t spp, std::uint32_t seed) {
  PathTracerSettings s;
  s.width = view.size.width;
  s.height = view.size.height;
  s.spp = spp;
  s.seed = seed;
  s.noise_threshold = 0.0f;
  s.threads = 2;
  return s;
}

struct Cornell {
  Scene scene = load_scene("cornell");
  Environment env = load_environment_or_default("", 0.0f, 1.0f);
  RenderView view = select_view(scene, std::nullopt, kSize, kSize);
};

TEST(DenoiserDrivenSampling, BeatsUniformSamplingAtTheSameSampleCount) {
  const Cornell c;
  // The reference (another seed) at 1024 spp: its own relMSE is about a 64th of the 16-spp
  // raw image's, small against the differences measured here.
  const Image reference =
      render_path(c.scene, &c.env, c.view.camera, settings_for(c.view, 1024, 99)).color;
  constexpr std::uint32_t kSpp = 16;
  const PathTracerResult uniform =
      render_path(c.scene, &c.env, c.view.camera, settings_for(c.view, kSpp, 1));
  const double uniform_error = rel_mse(denoise(denoise_input(uniform.film)), reference);
  const DenoiserDrivenSamplingResult adaptive =
      render_denoiser_driven(c.scene, &c.env, c.view.camera, settings_for(c.view, kSpp, 1));
  ASSERT_TRUE(adaptive.denoised_ok);
  const double adaptive_error = rel_mse(adaptive.denoised, reference);
  RecordProperty("uniform_rel_mse", std::to_string(uniform_error));
  RecordProperty("adaptive_rel_mse", std::to_string(adaptive_error));
  RecordProperty("passes", adaptive.passes);
  // The same budget: never more samples than the uniform render, and nearly all of them.
  EXPECT_EQ(uniform.stats.samples, adaptive.budget);
  EXPECT_LE(adaptive.render.stats.samples, adaptive.budget);
  EXPECT_GT(double(adaptive.render.stats.samples), 0.95 * double(adaptive.budget));
  EXPECT_GE(adaptive.passes, 3);
  // The counts vary (it adapts) and the film holds no stop flag.
  float lowest = 1e30f, highest = 0.0f;
  for (std::size_t i = 0; i < adaptive.render.film.pixel_count(); ++i) {
    lowest = std::min(lowest, adaptive.render.film.count[i]);
    highest = std::max(highest, adaptive.render.film.count[i]);
    EXPECT_EQ(adaptive.render.film.done[i], 0.0f);
  }
  EXPECT_LT(lowest, float(kSpp));
  EXPECT_GT(highest, float(kSpp));
  // Measured with these seeds: uniform 0.0096, adaptive 0.0087 (0.91x; seeds 2 and 3 gave
  // 0.86x and 0.80x). With the priority inverted it was 0.0135 (1.41x), with a random one
  // 0.0103 (1.07x): the bound fails unless the samples go where the estimate says.
  EXPECT_LT(adaptive_error, 0.95 * uniform_error)
      << "uniform relMSE " << uniform_error << ", adaptive " << adaptive_error;
}

TEST(DenoiserDrivenSampling, SameSeedSameBitsWhateverTheThreads) {
  const Cornell c;
  PathTracerSettings s = settings_for(c.view, 8, 7);
  const DenoiserDrivenSamplingResult a = render_denoiser_driven(c.scene, &c.env, c.view.camera, s);
  s.threads = 1;
  const DenoiserDrivenSamplingResult b = render_denoiser_driven(c.scene, &c.env, c.view.camera, s);
  EXPECT_EQ(a.passes, b.passes);
  EXPECT_EQ(a.render.film.count, b.render.film.count);
  EXPECT_EQ(a.denoised.data, b.denoised.data);
  s.seed = 8;  // and another seed gives another image (the comparison can fail)
  const DenoiserDrivenSamplingResult other =
      render_denoiser_driven(c.scene, &c.env, c.view.camera, s);
  EXPECT_NE(a.denoised.data, other.denoised.data);
}

TEST(DenoiserDrivenSampling, RefusesWhatItCannotHonour) {
  const Cornell c;
  auto expect_refused = [&](const PathTracerSettings& s, const char* word) {
    try {
      render_denoiser_driven(c.scene, &c.env, c.view.camera, s);
      ADD_FAILURE() << "accepted settings with " << word;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  PathTracerSettings s = settings_for(c.view, 8, 0);
  s.sample_end = 4;
  expect_refused(s, "sample range");
  s = settings_for(c.view, 8, 0);
  s.noise_threshold = 0.02f;
  expect_refused(s, "noise_threshold");
  s = settings_for(c.view, 8, 0);
  const Film film(kSize, kSize);  // not made by denoiser-driven sampling: no passes
  s.resume = &film;
  expect_refused(s, "resume");
  Film other_size(kSize + 1, kSize);
  other_size.denoiser_passes = 2;
  s.resume = &other_size;
  expect_refused(s, "resume");
}

// Checkpoints come after whole passes; resuming any of them ends exactly where the
// uninterrupted run ends (film counts, sums and the denoised image, bit for bit), and the
// checkpoint's EXR keeps the passes.
TEST(DenoiserDrivenSampling, ResumingACheckpointEndsWhereTheWholeRunDoes) {
  const Cornell c;
  PathTracerSettings s = settings_for(c.view, 8, 5);
  std::vector<Film> checkpoints;
  s.checkpoint_interval = 0.0;
  s.checkpoint = [&](const Film& f) { checkpoints.push_back(f); };
  const DenoiserDrivenSamplingResult whole =
      render_denoiser_driven(c.scene, &c.env, c.view.camera, s);
  ASSERT_GE(whole.passes, 3);
  ASSERT_EQ(checkpoints.size(), std::size_t(whole.passes));
  for (std::size_t k = 0; k < checkpoints.size(); ++k)
    EXPECT_EQ(checkpoints[k].denoiser_passes, k + 1);
  // Through the file, as `pbrkit render --checkpoint` writes it.
  const std::filesystem::path path = test::scratch_dir() / "driven_checkpoint.exr";
  write_film(path, checkpoints[1]);
  const Film second = read_film(path);
  EXPECT_EQ(second.denoiser_passes, 2u);
  for (const Film* from : {static_cast<const Film*>(&checkpoints[0]), &second}) {
    PathTracerSettings r = settings_for(c.view, 8, 5);
    r.resume = from;
    const DenoiserDrivenSamplingResult resumed =
        render_denoiser_driven(c.scene, &c.env, c.view.camera, r);
    EXPECT_EQ(resumed.passes, whole.passes);
    EXPECT_EQ(resumed.render.film.count, whole.render.film.count);
    EXPECT_EQ(resumed.render.film.sum, whole.render.film.sum);
    EXPECT_EQ(resumed.denoised.data, whole.denoised.data);
  }
  // A film of these passes is not a sample range.
  Film merged = checkpoints[0];
  EXPECT_THROW(merged.merge(checkpoints[0]), Error);
}

// A stop (util/progress.h's rule) returns what was rendered, undenoised and said so.
TEST(DenoiserDrivenSampling, StopReturnsTheRawImageAndSaysSo) {
  const Cornell c;
  PathTracerSettings s = settings_for(c.view, 8, 0);
  int reports = 0;
  const DenoiserDrivenSamplingResult r =
      render_denoiser_driven(c.scene, &c.env, c.view.camera, s, {},
                             [&](double, const std::string&) { return ++reports < 2; });
  EXPECT_FALSE(r.denoised_ok);
  EXPECT_TRUE(r.render.stats.stopped);
  EXPECT_LT(r.render.stats.samples, r.budget);
  EXPECT_EQ(r.denoised.data, r.render.film.color().data);
}

// The error estimate denoise() returns: one channel, finite, >= 0, larger where the input
// is noisier (fewer samples of the same scene), and the image unchanged by asking for it.
TEST(DenoiserDrivenSampling, DenoiserErrorEstimateFallsWithSamples) {
  const Cornell c;
  const Film few = render_path(c.scene, &c.env, c.view.camera, settings_for(c.view, 4, 3)).film;
  const Film many = render_path(c.scene, &c.env, c.view.camera, settings_for(c.view, 64, 3)).film;
  Image error_few, error_many;
  const Image plain = denoise(denoise_input(few));
  const Image with_error = denoise(denoise_input(few), {}, {}, nullptr, &error_few);
  EXPECT_EQ(plain.data, with_error.data);
  denoise(denoise_input(many), {}, {}, nullptr, &error_many);
  ASSERT_EQ(error_few.channels, 1);
  ASSERT_EQ(error_few.width, kSize);
  double mean_few = 0.0, mean_many = 0.0;
  for (std::size_t i = 0; i < error_few.data.size(); ++i) {
    ASSERT_TRUE(std::isfinite(error_few.data[i]) && error_few.data[i] >= 0.0f);
    mean_few += error_few.data[i];
    mean_many += error_many.data[i];
  }
  // 16x the samples: the estimated error must fall (by a large factor when it is mostly
  // variance; at least 4x with the filter's bias left).
  EXPECT_LT(mean_many, mean_few / 4.0) << mean_few << " vs " << mean_many;
}

}  // namespace
}  // namespace pbrkit
