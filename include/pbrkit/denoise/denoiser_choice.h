#pragma once
// Which denoiser denoises a render: the learned network (denoise/learned_denoiser.h,
// docs/LEARNED_DENOISER.md) or the classic feature-guided filter (denoise/denoiser.h,
// docs/DENOISER.md), which needs no weights file. One entry point
// for every caller (`pbrkit render/merge/denoise`, the viewer's path view, Python), so
// that the choice means the same everywhere.
#include <filesystem>
#include <memory>
#include <string>

#include "pbrkit/denoise/denoiser.h"
#include "pbrkit/util/progress.h"

namespace pbrkit {

enum class DenoiserKind {
  kLearned,  ///< the learned kernel-predicting network on oneDNN
  kClassic,  ///< the feature-guided cross filter with SURE selection
};

/// What `--denoise` and Python's `denoise=True` use when no denoiser is named: the one
/// that measures better on BENCHMARKS.md's denoiser tables (and keeps every region's
/// energy within its noise, which the shipped network does not yet).
inline constexpr DenoiserKind kDefaultDenoiser = DenoiserKind::kClassic;

/// "learned" or "classic".
const char* denoiser_name(DenoiserKind kind);

struct DenoiserChoice {
  DenoiserKind kind = kDefaultDenoiser;
  /// The learned denoiser's weights file; empty: the one pbrkit ships
  /// (default_learned_denoiser_weights()).
  std::filesystem::path weights;
  /// Threads of the learned denoiser's network (0: every core); the classic one runs on
  /// oneTBB's arena like the rest of the library.
  int threads = 0;

  bool operator==(const DenoiserChoice&) const = default;
};

class LearnedDenoiser;

/// A chosen denoiser ready to run (load_denoiser): the learned one's weights read and
/// checked once, for every denoise_render the caller makes with it; copies share them.
struct LoadedDenoiser {
  DenoiserChoice choice;
  std::shared_ptr<const LearnedDenoiser> learned;  ///< the network, for DenoiserKind::kLearned
};

struct DenoiseRun {
  /// The denoised image; if interrupted, the halves' mean, or for a learned network that
  /// blends with the classic denoiser (kpcn-blend-v2) stopped after that one finished, the
  /// classic denoiser's image.
  Image image;
  bool interrupted = false;  ///< the progress callback asked to stop
  double seconds = 0.0;
};

/// Loads the chosen denoiser: reads and checks the learned denoiser's weights file
/// (nothing for the classic one). Throws pbrkit::Error naming the file and the problem when
/// it cannot be read, so a caller loads before a long render, not after it, and keeps what
/// it loaded for the run.
LoadedDenoiser load_denoiser(const DenoiserChoice& choice);

/// Denoises a render's half buffers with the chosen denoiser. The learned denoiser reads
/// the halves' mean colour, albedo and normal (the same as the film's own images but for
/// the odd half's one sample fewer), and passes through, as the classic one does, the
/// pixels whose every sample saw the environment directly (depth 0 in both halves); the
/// classic one reads the halves themselves.
DenoiseRun denoise_render(const DenoiseInput& input, const LoadedDenoiser& denoiser,
                          const ProgressCallback& progress = {});
/// denoise_render(input, load_denoiser(choice), progress), for a caller that denoises once:
/// throws pbrkit::Error (naming the file) when the learned denoiser's weights cannot be read.
DenoiseRun denoise_render(const DenoiseInput& input, const DenoiserChoice& choice,
                          const ProgressCallback& progress = {});

}  // namespace pbrkit
