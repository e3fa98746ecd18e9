// The denoiser under heavy-tailed noise: rare samples about 1000x the rest, as a rough
// metal reflecting a small, very bright light gives. The energy of the rare samples must
// be kept (the denoised mean stays the true mean within the noise of the samples) while
// the fireflies themselves disappear.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "pbrkit/denoise/denoiser.h"
#include "pbrkit/denoise/energy.h"

namespace pbrkit {
namespace {

constexpr int kSize = 64;
constexpr int kSamplesPerHalf = 8;
// Every sample is kHigh = 1000 kLow with probability kP, else uniform in [kLow / 2,
// 3 kLow / 2] (ordinary noise of mean kLow): mean kLow + kP (kHigh - kLow).
constexpr double kLow = 0.1, kHigh = 100.0, kP = 0.002;
// Its variance: E[X^2] - mean^2, with E[X^2] of the ordinary samples 13/12 kLow^2.
constexpr double kMean = kLow + kP * (kHigh - kLow);
constexpr double kVariance =
    (1.0 - kP) * 13.0 / 12.0 * kLow * kLow + kP * kHigh * kHigh - kMean * kMean;

// A uniform number in [0, 1) from the raw 32-bit output of mt19937 (whose sequence the
// standard fixes, unlike the distributions').
double uniform(std::mt19937& rng) {
  return double(rng()) / 4294967296.0;
}

DenoiseInput heavy_tailed(std::uint32_t seed) {
  DenoiseInput in;
  std::mt19937 rng(seed);
  for (int h = 0; h < 2; ++h) {
    in.color[h] = Image(kSize, kSize, 3);
    in.albedo[h] = Image(kSize, kSize, 3, 0.5f);
    in.normal[h] = Image(kSize, kSize, 3);
    in.depth[h] = Image(kSize, kSize, 1, 2.0f);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        double sum = 0.0;
        for (int s = 0; s < kSamplesPerHalf; ++s) {
          const double u = uniform(rng), v = uniform(rng);
          sum += u < kP ? kHigh : kLow * (0.5 + v);
        }
        in.color[h].set_rgb(x, y, glm::vec3(float(sum / kSamplesPerHalf)));
        in.normal[h].set_rgb(x, y, glm::vec3(0.0f, 0.0f, 1.0f));
      }
  }
  return in;
}

double image_mean(const Image& image) {
  double sum = 0.0;
  for (float v : image.data) sum += v;
  return sum / double(image.data.size());
}

TEST(DenoiserHeavyTails, MeanIsKeptAndFirefliesAreGone) {
  const double mean = kMean;
  // The frame mean of N samples has the standard deviation sigma / sqrt(N): the raw
  // image's own uncertainty about the true mean (0.0174 here, 6% of the mean).
  const double samples = double(kSize) * kSize * 2 * kSamplesPerHalf;
  const double sigma_frame = std::sqrt(kVariance / samples);
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const DenoiseInput in = heavy_tailed(seed);
    DenoiseStats stats;
    const Image out = denoise(in, {}, {}, &stats);
    Image raw(kSize, kSize, 3);
    for (std::size_t i = 0; i < raw.data.size(); ++i)
      raw.data[i] = 0.5f * (in.color[0].data[i] + in.color[1].data[i]);
    const double raw_mean = image_mean(raw), denoised_mean = image_mean(out);
    // The denoised mean is the true mean within 3 sigma of the samples' own noise (a
    // filter that clamped the rare samples would give about kLow = 0.1, 11 sigma off).
    EXPECT_NEAR(denoised_mean, mean, 3.0 * sigma_frame)
        << "seed " << seed << ", raw mean " << raw_mean;
    // And it keeps the raw image's energy much more tightly: only what leaves the frame's
    // border can differ (the filter window is 15x15 on a 64x64 frame), well within one
    // sigma of the frame mean.
    EXPECT_NEAR(denoised_mean, raw_mean, sigma_frame) << "seed " << seed;
    // Fireflies gone. A pixel with one rare sample among its 16 has a raw value of about
    // kHigh / 16 = 6.3, twenty times the mean; the raw image has about 4096 (1 - (1 -
    // kP)^16) = 128 of them. A value both halves share is signal to the denoiser (each
    // half is an independent estimate), so the pixels with a rare sample in each half,
    // 4096 q^2 = 1.04 expected with q = 1 - (1 - kP)^8, may stay; more than 6 of them has
    // a Poisson probability below 1e-4. No other pixel may stay above 5x the mean (a
    // quarter of one rare sample's energy).
    const auto above = [&](const Image& image) {
      return std::count_if(image.data.begin(), image.data.end(),
                           [&](float v) { return v > 5.0 * mean; }) /
             3;
    };
    EXPECT_GT(above(raw), 64) << "the input has fireflies";
    EXPECT_LE(above(out), 6) << "seed " << seed << ", raw " << above(raw);
  }
}

TEST(DenoiserHeavyTails, BlockMeansStayWithinTheRawNoise) {
  // Every 16x16 block's denoised mean stays within 2 raw standard errors (estimated from
  // the halves, src/pbrkit/denoise/energy.h) of the raw one: the rare samples' energy
  // is moved over a few pixels, never removed (a clamp would leave every block about
  // 0.2 / 0.05 = 4 standard errors dark).
  for (std::uint32_t seed : {4u, 5u}) {
    const DenoiseInput in = heavy_tailed(seed);
    const EnergyReport report = measure_energy(in, denoise(in), 16);
    EXPECT_LT(std::abs(report.frame.z), 2.0) << "seed " << seed;
    for (const RegionEnergy& block : report.blocks)
      EXPECT_LT(std::abs(block.z), 2.0)
          << "seed " << seed << ", block " << block.id << ": raw " << block.raw << ", denoised "
          << block.denoised << ", standard error " << block.error;
  }
}

}  // namespace
}  // namespace pbrkit
