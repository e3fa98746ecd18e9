#include "denoising.h"

#include <algorithm>

#include "pbrkit/util/error.h"
#include "pbrkit/util/progress.h"

namespace pbrkit::cli {

DenoiserChoice DenoiserFlags::choice() const {
  DenoiserChoice c;
  c.kind = denoiser == "classic" ? DenoiserKind::kClassic : DenoiserKind::kLearned;
  c.weights = weights;
  return c;
}

LoadedDenoiser DenoiserFlags::load() const {
  return load_denoiser(choice());
}

void add_denoiser_options(CLI::App& cmd, DenoiserFlags* flags, const std::string& group) {
  cmd.add_option("--denoiser", flags->denoiser,
                 "which denoiser: classic (the feature-guided filter, docs/DENOISER.md) or "
                 "learned (a network trained on pbrkit's renders, docs/LEARNED_DENOISER.md; "
                 "reads a weights file)")
      ->check(CLI::IsMember({"learned", "classic"}))
      ->capture_default_str()
      ->group(group);
  cmd.add_option("--denoiser-weights", flags->weights,
                 "the learned denoiser's weights file (default: the one pbrkit ships, "
                 "data/denoiser/kpcn-blend-v2.pbnn)")
      ->group(group);
}

std::optional<Image> run_denoiser(const DenoiseInput& input, const LoadedDenoiser& denoiser,
                                  const std::atomic<bool>* stop) {
  ProgressBar bar(fmt::format("denoise ({})", denoiser_name(denoiser.choice.kind)));
  auto update = bar.callback();
  DenoiseRun run = denoise_render(input, denoiser, [&](double fraction, const std::string& detail) {
    update(fraction, detail);
    return !(stop && stop->load());
  });
  if (run.interrupted) {
    bar.finish("interrupted");
    return std::nullopt;
  }
  bar.finish(
      fmt::format("{}x{} in {:.2f} s", input.color[0].width, input.color[0].height, run.seconds));
  return std::move(run.image);
}

std::vector<std::string> with_denoise_aovs(std::vector<std::string> aovs) {
  for (const char* name : {"albedo", "normal", "depth"})
    if (std::find(aovs.begin(), aovs.end(), name) == aovs.end()) aovs.push_back(name);
  return aovs;
}

}  // namespace pbrkit::cli
