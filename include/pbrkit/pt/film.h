#pragma once
// The path tracer's film: per-pixel accumulation buffers (sums and sample counts), from
// which the colour image, the AOVs and the noise estimate are resolved. Because the pixel
// filter is importance-sampled, every sample has weight 1 and a pixel's state is just
// its sums and its count, so films of disjoint sample ranges merge by addition and a
// film saved to a float EXR resumes bit-exactly.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/image/image.h"
#include "pbrkit/image/image_io.h"

namespace pbrkit {

struct Film {
  int width = 0;
  int height = 0;
  std::uint32_t sample_begin = 0;  ///< the first sample index of this film's range
  std::uint32_t seed = 0;

  // Per pixel, in pixel order (row 0 at the top):
  std::vector<glm::vec3> sum;       ///< sum of radiance over all samples
  std::vector<glm::vec3> sum_even;  ///< sum over samples with an even index (half buffer)
  std::vector<glm::vec3> albedo;    ///< sum of the first-hit albedo
  std::vector<glm::vec3> normal;    ///< sum of the first-hit shading normal (world)
  std::vector<float> depth;         ///< sum of the first-hit distance (0 for a miss)
  // The features' half buffers (even-indexed samples), for the denoiser's feature variance.
  std::vector<glm::vec3> albedo_even;
  std::vector<glm::vec3> normal_even;
  std::vector<float> depth_even;
  std::vector<float> count;  ///< samples taken (exact in float up to 2^24)
  std::vector<float> done;   ///< 1 when adaptive sampling stopped the pixel
  /// Samples whose radiance was not finite (set to 0) and paths that overflowed the medium
  /// stack, over every sample in the film (PathTracerStats has those of one call); written
  /// to its EXRs as the header attributes kNonFiniteSamplesAttribute and
  /// kMediumOverflowsAttribute, summed by merge.
  std::uint64_t non_finite_samples = 0;
  std::uint64_t medium_overflows = 0;
  /// The passes of denoiser-driven sampling (denoise/denoiser_driven_sampling.h) that made
  /// this film, 0 for any other render: what resuming its checkpoint needs besides the
  /// counts. Written to its EXRs as kDenoiserPassesAttribute.
  std::uint32_t denoiser_passes = 0;

  Film() = default;
  Film(int w, int h);
  std::size_t pixel_count() const { return std::size_t(width) * height; }

  /// Mean radiance per pixel (RGB; black where no sample was taken).
  Image color() const;
  Image albedo_image() const;  ///< mean first-hit albedo (RGB)
  Image normal_image() const;  ///< mean first-hit shading normal (RGB = XYZ)
  Image depth_image() const;   ///< mean first-hit distance (1 channel)
  Image count_image() const;   ///< samples per pixel (1 channel)
  Image noise_image() const;   ///< per-pixel relative error estimate (1 channel)

  /// The mean of one half buffer (half 0: the even-indexed samples, half 1: the odd ones)
  /// of the colour and of each feature; a pixel whose half has no sample gets the full
  /// mean. What the denoiser reads (denoise/inputs.h).
  Image color_half(int half) const;
  Image albedo_half(int half) const;
  Image normal_half(int half) const;  ///< decoded to [-1, 1] like normal_image()
  Image depth_half(int half) const;

  /// Relative error of pixel i from the two half buffers (Cycles' adaptive sampling):
  /// sum|I - E| / sqrt(sum I) with I the full mean and E the even-sample mean
  /// (pt/adaptive_sampling.h).
  float pixel_noise(std::size_t i) const;

  /// Adds `other` (a disjoint sample range of the same image) into this film. A film of
  /// denoiser-driven sampling (denoiser_passes > 0) on either side is an error: its samples
  /// went where its own earlier samples said, so it is not a sample range.
  void merge(const Film& other);
};

/// The EXR header attributes (strings holding a decimal count) in which write_film and
/// write_render_exr record Film::non_finite_samples and Film::medium_overflows.
inline constexpr const char* kNonFiniteSamplesAttribute = "pbrkit:nonFiniteSamples";
inline constexpr const char* kMediumOverflowsAttribute = "pbrkit:mediumOverflows";
/// The EXR header attribute recording Film::denoiser_passes (absent: 0).
inline constexpr const char* kDenoiserPassesAttribute = "pbrkit:denoiserDrivenPasses";

/// Writes the film's buffers as a float EXR ("accumulation" file: layers sum, sum_even,
/// albedo, normal, depth, their even halves, count, done), atomically.
void write_film(const std::filesystem::path& path, const Film& film);
/// Reads a file written by write_film; pbrkit::Error naming the file if it is not one.
/// A file from before the features' half buffers existed loads with them set to the
/// expected share of the totals (so the feature variance reads as zero) and a warning.
Film read_film(const std::filesystem::path& path);

/// The AOV names write_render_exr knows.
const std::vector<std::string>& render_aov_names();

/// The final outputs of a render: a linear EXR (main RGB layer plus the chosen AOV
/// layers) and nothing else. AOV names: albedo, normal, depth, samples, noise, and
/// denoise (the half buffers the denoiser reads: layers color_a, color_b, albedo_a,
/// albedo_b, normal_a, normal_b (encoded 0.5 n + 0.5: EXR reading clamps negative
/// samples), depth_a, depth_b). With `main` (a denoised image) the
/// main layer is `main` and the film's own colour goes to a layer "raw".
void write_render_exr(const std::filesystem::path& path, const Film& film,
                      const std::vector<std::string>& aovs, ExrPixelType type,
                      const Image* main = nullptr);

}  // namespace pbrkit
