#include "denoising.h"

#include <algorithm>

#include "pbrkit/util/error.h"
#include "pbrkit/util/progress.h"

namespace pbrkit::cli {

std::optional<Image> run_denoiser(const DenoiseInput& input, const std::atomic<bool>* stop) {
  ProgressBar bar("denoise");
  auto update = bar.callback();
  DenoiseStats stats;
  Image out = denoise(
      input, {},
      [&](double fraction, const std::string& detail) {
        update(fraction, detail);
        return !(stop && stop->load());
      },
      &stats);
  if (stats.interrupted) {
    bar.finish("interrupted");
    return std::nullopt;
  }
  bar.finish(
      fmt::format("{}x{} in {:.2f} s", input.color[0].width, input.color[0].height, stats.seconds));
  return out;
}

std::vector<std::string> with_denoise_aovs(std::vector<std::string> aovs) {
  for (const char* name : {"albedo", "normal", "depth"})
    if (std::find(aovs.begin(), aovs.end(), name) == aovs.end()) aovs.push_back(name);
  return aovs;
}

}  // namespace pbrkit::cli
