#pragma once
// The learned denoiser: a small U-Net (Ronneberger et al. 2015) that predicts, at three
// scales, a 5x5 kernel per pixel applied to the noisy colour itself (Bako et al. 2017,
// "Kernel-Predicting Convolutional Networks for Denoising Monte Carlo Renderings") and
// blends the scales coarse to fine (Vogels et al. 2018, section 4.2), trained on pbrkit's
// own renders by tools/denoiser/ and run here on oneDNN. docs/LEARNED_DENOISER.md is the
// contract (network, input transform, output, tiles, weights file) this follows.
//
// Every output pixel is a normalised weighted average of noisy colours, blended across
// scales, and for kpcn-blend-v2 then blended per pixel with the classic denoiser's output
// (a weight in (0, 1) that the network predicts): the output is finite and never negative,
// also for NaN, infinite or negative input pixels (taken as 0).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "pbrkit/image/image.h"
#include "pbrkit/util/progress.h"

namespace pbrkit {

struct LearnedDenoiserOptions {
  /// The weights file (docs/LEARNED_DENOISER.md, "The weights file"); empty: the default
  /// one shipped with pbrkit, default_learned_denoiser_weights().
  std::filesystem::path weights;
  /// The side of a tile's inner square in pixels, rounded up to a multiple of 16; 0: the
  /// default (kDefaultLearnedDenoiserTile). Each tile runs extended by the network's
  /// receptive-field radius on every side, so the output does not depend on the tiling
  /// (but for rounding); larger tiles repeat less of that margin and take more memory.
  int tile = 0;
  /// Threads for the network (oneDNN's OpenMP team) and the kernels (oneTBB); 0: the
  /// runtimes' defaults (every core, or OMP_NUM_THREADS).
  int threads = 0;
};

/// The default inner tile: 1920x1080 then runs in 3x2 tiles of at most 832x640 pixels
/// with their margins, whose network activations take 187 MB (88 floats a pixel). With
/// kpcn-blend-v2 the classic denoiser's output is held beside the caller's images while it
/// runs: 1,024-pixel tiles (238 MB) took the whole `pbrkit denoise` of a 1920x1080 image to
/// 599 MB, these to 546 MB, for the same time (docs/LEARNED_DENOISER.md, "Tiles").
inline constexpr int kDefaultLearnedDenoiserTile = 768;

/// What the weights file's header says (docs/LEARNED_DENOISER.md, "The weights file").
struct LearnedWeightsInfo {
  std::filesystem::path file;
  std::string network;          ///< "kpcn-unet-v1" or "kpcn-blend-v2"
  std::string input_transform;  ///< "log1p-autoexposure-v1"
  std::string commit;           ///< the training code's git commit
  std::string dataset;          ///< its name and seed
  std::int64_t steps = 0;       ///< training steps
  std::string created;          ///< when the file was written
  std::uint32_t crc32 = 0;      ///< zlib's CRC-32 of the tensors' data
  std::int64_t parameters = 0;  ///< weights and biases: 367,325 (kpcn-unet-v1), 367,902
                                ///< (kpcn-blend-v2)
};

/// Diagnostics of one denoise() call.
struct LearnedDenoiseStats {
  double seconds = 0.0;
  double exposure = 1.0;  ///< the autoexposure s of the whole image
  int tiles = 0;          ///< tiles run (the image is one tile when it fits)
  /// The progress callback stopped it: the image returned is the input colour, undenoised
  /// (its non-finite and negative values taken as 0).
  bool interrupted = false;
};

/// data_dir() / "denoiser/kpcn-blend-v2.pbnn", the weights pbrkit uses by default (it ships
/// kpcn-unet-v1.pbnn too, from which kpcn-blend-v2 was trained).
std::filesystem::path default_learned_denoiser_weights();

/// The learned denoiser with its weights loaded. denoise() is const and may run from
/// several threads at once (each call allocates its own buffers).
class LearnedDenoiser {
 public:
  /// Reads and checks the weights file. Throws pbrkit::Error naming the file and the
  /// problem: missing, not a pbrkit network, another format version, network or input
  /// transform, a header that is not JSON or lacks a field, a tensor missing, of another
  /// shape or not finite, a file shorter than its data, a CRC mismatch.
  explicit LearnedDenoiser(const LearnedDenoiserOptions& options = {});
  ~LearnedDenoiser();
  LearnedDenoiser(LearnedDenoiser&&) noexcept;
  LearnedDenoiser& operator=(LearnedDenoiser&&) noexcept;

  /// Denoises `color` (linear HDR RGB, the mean of all samples) guided by the first
  /// non-specular vertex's `albedo` and world-space `normal` (pt/film.h's AOVs). The three
  /// images have one size and 3 or 4 channels (alpha ignored); otherwise pbrkit::Error.
  /// Returns an RGB image of that size, every value finite and >= 0. `progress` gets the
  /// fraction of tiles done; when it returns false the call stops and returns the input
  /// colour undenoised, with LearnedDenoiseStats::interrupted set (util/progress.h).
  /// For a network that blends with the classic denoiser's output (blends_classic()),
  /// pbrkit::Error: use the overload with that output.
  Image denoise(const Image& color, const Image& albedo, const Image& normal,
                const ProgressCallback& progress = {}, LearnedDenoiseStats* stats = nullptr) const;

  /// As above, with `classic`, the classic denoiser's output of the same render (denoise.h),
  /// which a kpcn-blend-v2 network reads and blends with its own per pixel; ignored (and
  /// may be empty) for kpcn-unet-v1. Its size must be the colour's when it is read.
  Image denoise(const Image& color, const Image& albedo, const Image& normal, const Image& classic,
                const ProgressCallback& progress = {}, LearnedDenoiseStats* stats = nullptr) const;

  /// Whether the network reads the classic denoiser's output (kpcn-blend-v2).
  bool blends_classic() const;

  /// The weights file's header.
  const LearnedWeightsInfo& info() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pbrkit
