#include "pbrkit/denoise/denoiser_choice.h"

#include "pbrkit/denoise/denoiser.h"
#include "pbrkit/denoise/inputs.h"
#include "pbrkit/denoise/learned/input_transform.h"
#include "pbrkit/denoise/learned_denoiser.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {
// kpcn-blend-v2 runs the classic denoiser first, which takes most of the time (about 9x
// the network at 512x512, BENCHMARKS.md): its share of the progress.
constexpr double kClassicShare = 0.9;
}  // namespace

const char* denoiser_name(DenoiserKind kind) {
  return kind == DenoiserKind::kLearned ? "learned" : "classic";
}

LoadedDenoiser load_denoiser(const DenoiserChoice& choice) {
  LoadedDenoiser loaded{choice, nullptr};
  if (choice.kind == DenoiserKind::kLearned) {
    LearnedDenoiserOptions options;
    options.weights = choice.weights;
    options.threads = choice.threads;
    loaded.learned = std::make_shared<const LearnedDenoiser>(options);
  }
  return loaded;
}

DenoiseRun denoise_render(const DenoiseInput& input, const DenoiserChoice& choice,
                          const ProgressCallback& progress) {
  return denoise_render(input, load_denoiser(choice), progress);
}

DenoiseRun denoise_render(const DenoiseInput& input, const LoadedDenoiser& loaded,
                          const ProgressCallback& progress) {
  DenoiseRun run;
  if (loaded.choice.kind == DenoiserKind::kClassic) {
    DenoiseStats stats;
    run.image = denoise(input, {}, progress, &stats);
    run.interrupted = stats.interrupted;
    run.seconds = stats.seconds;
    return run;
  }
  if (!loaded.learned) fail("the learned denoiser was not loaded (load_denoiser)");
  const LearnedDenoiser& denoiser = *loaded.learned;
  validate_denoise_input(input);
  LearnedDenoiseStats stats;
  const Image color = mean_of_halves(input.color);
  Image classic;
  if (denoiser.blends_classic()) {
    // The classic denoiser first; the network then blends its output with its own.
    DenoiseStats classic_stats;
    const ProgressCallback classic_progress =
        progress ? ProgressCallback([&](double f, const std::string& what) {
          return progress(kClassicShare * f, what.empty() ? "classic" : "classic: " + what);
        })
                 : ProgressCallback{};
    classic = denoise(input, {}, classic_progress, &classic_stats);
    run.seconds += classic_stats.seconds;
    if (classic_stats.interrupted) {
      run.image = std::move(classic);  // what the classic denoiser returns when stopped
      run.interrupted = true;
      return run;
    }
  }
  const ProgressCallback network_progress =
      progress && denoiser.blends_classic()
          ? ProgressCallback([&](double f, const std::string& what) {
              return progress(kClassicShare + (1.0 - kClassicShare) * f, what);
            })
          : progress;
  run.image = denoiser.denoise(color, mean_of_halves(input.albedo), mean_of_halves(input.normal),
                               classic, network_progress, &stats);
  run.interrupted = stats.interrupted;
  run.seconds += stats.seconds;
  // Stopped within the network after the classic denoiser finished: its image, not the raw.
  if (run.interrupted && !classic.empty()) run.image = std::move(classic);
  // As the classic denoiser does (DenoiseOptions::keep_direct_environment): a pixel whose
  // every sample saw the environment directly (depth 0 in both halves) is a lookup of the
  // environment, noise-free but for the pixel filter's sampling of its detail; the
  // network's kernels would average the scene into it (worst 32x32 blocks 20 to 180 raw
  // standard errors off on the shared models under studio and sunset, BENCHMARKS.md).
  if (!run.interrupted)
    for (std::size_t i = 0; i < color.pixel_count(); ++i)
      if (input.depth[0].data[i] == 0.0f && input.depth[1].data[i] == 0.0f)
        for (std::size_t c = 0; c < 3; ++c)
          run.image.data[i * 3 + c] = learned::sanitize_color(color.data[i * 3 + c]);
  return run;
}

}  // namespace pbrkit
