#pragma once
// The denoiser as the CLI runs it (render --denoise, merge --denoise, pbrkit denoise):
// a progress bar on stderr and an optional stop flag (Ctrl-C during a render).
#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "pbrkit/denoise/denoiser.h"

namespace pbrkit::cli {

/// Denoises `input`; returns nothing when `stop` was set meanwhile.
std::optional<Image> run_denoiser(const DenoiseInput& input,
                                  const std::atomic<bool>* stop = nullptr);

/// `aovs` plus the layers a denoised EXR always keeps beside the raw image (albedo,
/// normal, depth), without duplicates.
std::vector<std::string> with_denoise_aovs(std::vector<std::string> aovs);

}  // namespace pbrkit::cli
