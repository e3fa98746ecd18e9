#include "pbrkit/denoise/denoiser_choice.h"

#include "pbrkit/denoise/learned_denoiser.h"

namespace pbrkit {

const char* denoiser_name(DenoiserKind kind) {
  return kind == DenoiserKind::kLearned ? "learned" : "classic";
}

namespace {

Image mean_of_halves(const Image (&halves)[2]) {
  Image out(halves[0].width, halves[0].height, halves[0].channels);
  for (std::size_t i = 0; i < out.data.size(); ++i)
    out.data[i] = 0.5f * (halves[0].data[i] + halves[1].data[i]);
  return out;
}

}  // namespace

void check_denoiser(const DenoiserChoice& choice) {
  if (choice.kind != DenoiserKind::kLearned) return;
  LearnedDenoiserOptions options;
  options.weights = choice.weights;
  const LearnedDenoiser check(options);
}

DenoiseRun denoise_render(const DenoiseInput& input, const DenoiserChoice& choice,
                          const ProgressCallback& progress) {
  DenoiseRun run;
  if (choice.kind == DenoiserKind::kClassic) {
    DenoiseStats stats;
    run.image = denoise(input, {}, progress, &stats);
    run.interrupted = stats.interrupted;
    run.seconds = stats.seconds;
    return run;
  }
  LearnedDenoiserOptions options;
  options.weights = choice.weights;
  options.threads = choice.threads;
  const LearnedDenoiser denoiser(options);
  validate_denoise_input(input);
  LearnedDenoiseStats stats;
  run.image = denoiser.denoise(mean_of_halves(input.color), mean_of_halves(input.albedo),
                               mean_of_halves(input.normal), progress, &stats);
  run.interrupted = stats.interrupted;
  run.seconds = stats.seconds;
  return run;
}

}  // namespace pbrkit
