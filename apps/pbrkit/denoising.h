#pragma once
// The denoiser as the CLI runs it (render --denoise, merge --denoise, pbrkit denoise):
// the --denoiser and --denoiser-weights options, a progress bar on stderr and an optional
// stop flag (Ctrl-C during a render).
#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "pbrkit/denoise/denoiser_choice.h"

namespace pbrkit::cli {

/// The denoiser options as given on the command line.
struct DenoiserFlags {
  std::string denoiser = denoiser_name(kDefaultDenoiser);
  std::string weights;
  /// The typed choice, its weights file unread.
  DenoiserChoice choice() const;
  /// The choice loaded (load_denoiser): the learned denoiser's weights file read and
  /// checked once, a clear error naming it before a long render, not after.
  LoadedDenoiser load() const;
};

/// Adds --denoiser and --denoiser-weights to a command, in `group`.
void add_denoiser_options(CLI::App& cmd, DenoiserFlags* flags, const std::string& group = "");

/// Denoises `input`; returns nothing when `stop` was set meanwhile.
std::optional<Image> run_denoiser(const DenoiseInput& input, const LoadedDenoiser& denoiser,
                                  const std::atomic<bool>* stop = nullptr);

/// `aovs` plus the layers a denoised EXR always keeps beside the raw image (albedo,
/// normal, depth), without duplicates.
std::vector<std::string> with_denoise_aovs(std::vector<std::string> aovs);

}  // namespace pbrkit::cli
