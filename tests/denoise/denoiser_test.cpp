// The denoiser on synthetic inputs whose noise is known: every tolerance below comes from
// that noise (sigma), not from the output of the code under test.
#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "pbrkit/denoise/denoiser.h"
#include "pbrkit/util/error.h"

namespace pbrkit {
namespace {

constexpr int kSize = 64;

// Halves of a render whose every pixel has mean `truth(x, y)` (RGB grey) and whose half
// means each carry Gaussian noise of standard deviation `sigma_half`; the features are
// noise-free: albedo `albedo(x, y)`, a constant normal and depth.
DenoiseInput synthetic(const std::function<float(int, int)>& truth,
                       const std::function<float(int, int)>& albedo, float sigma_half,
                       std::uint32_t seed = 1) {
  DenoiseInput in;
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, sigma_half);
  for (int h = 0; h < 2; ++h) {
    in.color[h] = Image(kSize, kSize, 3);
    in.albedo[h] = Image(kSize, kSize, 3);
    in.normal[h] = Image(kSize, kSize, 3);
    in.depth[h] = Image(kSize, kSize, 1, 2.0f);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const float t = truth(x, y) + noise(rng);
        in.color[h].set_rgb(x, y, glm::vec3(t));
        in.albedo[h].set_rgb(x, y, glm::vec3(albedo(x, y)));
        in.normal[h].set_rgb(x, y, glm::vec3(0.0f, 0.0f, 1.0f));
      }
  }
  return in;
}

double region_mean(const Image& image, int x0, int y0, int x1, int y1) {
  double sum = 0.0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += image.pixel(x, y)[0];
  return sum / double((x1 - x0) * (y1 - y0));
}

TEST(Denoiser, ConstantImageComesBackConstant) {
  const float c = 0.5f, sigma_half = 0.1f;
  // The raw image is the mean of the halves: its per-pixel noise is sigma_half / sqrt 2.
  const float sigma_raw = sigma_half / std::sqrt(2.0f);
  const Image out =
      denoise(synthetic([&](int, int) { return c; }, [](int, int) { return 0.5f; }, sigma_half));
  double sq = 0.0, worst = 0.0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double d = out.pixel(x, y)[0] - c;
      sq += d * d;
      worst = std::max(worst, std::abs(d));
    }
  const double rms = std::sqrt(sq / (kSize * kSize));
  // A filter that averages at least 16 independent pixels cuts the noise 4-fold; the
  // 15x15 window averages far more wherever the features agree, as here everywhere.
  EXPECT_LT(rms, sigma_raw / 4.0) << "raw noise " << sigma_raw;
  // No pixel is left at a raw pixel's typical deviation.
  EXPECT_LT(worst, sigma_raw) << "raw noise " << sigma_raw;
}

TEST(Denoiser, AlbedoStepStaysSharp) {
  const float sigma_half = 0.05f;
  auto step = [](int x, int) { return x < kSize / 2 ? 0.2f : 0.8f; };
  const Image out = denoise(synthetic(step, step, sigma_half));
  // The column profile (mean over rows); the edge is between x = 31 and x = 32. Pixels
  // between 10% and 90% of the step make up its width.
  int width = 0;
  for (int x = 0; x < kSize; ++x) {
    const double v = region_mean(out, x, 0, x + 1, kSize);
    if (v > 0.2 + 0.1 * 0.6 && v < 0.8 - 0.1 * 0.6) ++width;
  }
  EXPECT_LE(width, 2);
  // Each side keeps its level within 4 standard errors of the raw side mean.
  const double se = sigma_half / std::sqrt(2.0) / std::sqrt(double(kSize * kSize / 2));
  EXPECT_NEAR(region_mean(out, 0, 0, kSize / 2, kSize), 0.2, 4 * se + 1e-3);
  EXPECT_NEAR(region_mean(out, kSize / 2, 0, kSize, kSize), 0.8, 4 * se + 1e-3);
}

TEST(Denoiser, AlbedoTextureKeepsItsContrast) {
  const float sigma_half = 0.05f;
  // Stripes 2 px wide, 0.3 and 0.7: a texture the albedo shows.
  auto stripes = [](int x, int) { return (x / 2) % 2 == 0 ? 0.3f : 0.7f; };
  const Image out = denoise(synthetic(stripes, stripes, sigma_half));
  double hi = 0.0, lo = 0.0;
  int n_hi = 0, n_lo = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      if (stripes(x, y) > 0.5f) {
        hi += out.pixel(x, y)[0];
        ++n_hi;
      } else {
        lo += out.pixel(x, y)[0];
        ++n_lo;
      }
    }
  const double contrast = hi / n_hi - lo / n_lo;
  EXPECT_NEAR(contrast, 0.4, 0.1 * 0.4);
}

TEST(Denoiser, RegionMeansArePreserved) {
  const float sigma_half = 0.2f;
  // Blocks of different albedo under one light: radiance = albedo.
  auto blocks = [](int x, int y) { return 0.1f + 0.2f * float((x / 16 + 2 * (y / 16)) % 4); };
  const DenoiseInput in = synthetic(blocks, blocks, sigma_half, 7);
  const Image out = denoise(in);
  const double sigma_raw = sigma_half / std::sqrt(2.0);
  for (int by = 0; by < kSize; by += 32)
    for (int bx = 0; bx < kSize; bx += 32) {
      double truth = 0.0;
      for (int y = by; y < by + 32; ++y)
        for (int x = bx; x < bx + 32; ++x) truth += blocks(x, y);
      truth /= 32.0 * 32.0;
      // The raw mean of a 32x32 region has standard error sigma_raw / 32; a weighted mean
      // of the same pixels (and neighbours of the same block) no more than twice that.
      const double tolerance = 4.0 * 2.0 * sigma_raw / 32.0;
      EXPECT_NEAR(region_mean(out, bx, by, bx + 32, by + 32), truth, tolerance)
          << "region " << bx << "," << by;
    }
}

// Fireflies: a constant noisy image with a few single-sample outliers of known energy in
// one half. The denoised image must keep their energy (the sum over the image of the mean
// of the halves) within the noise of that sum, and stay near the constant away from them.
// A corrugated sheet seen from above: the normal swings between -69 and +69 degrees every
// 16 pixels and the radiance is linear in it (0.5 + 0.4 n_x), as diffuse shading under a
// broad light roughly is. Albedo and depth are constant, so only the normal tells the
// shades apart.
float corrugation(int x) {
  return 1.2f * std::sin(2.0f * 3.14159265f * float(x) / 16.0f);
}
float corrugated_shading(int x) {
  return 0.5f + 0.4f * std::sin(corrugation(x));
}

DenoiseInput corrugated(float sigma_half, std::uint32_t seed,
                        float (*shading)(int) = corrugated_shading) {
  DenoiseInput in = synthetic([&](int x, int) { return shading(x); }, [](int, int) { return 0.5f; },
                              sigma_half, seed);
  for (int h = 0; h < 2; ++h)
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const float theta = corrugation(x);
        in.normal[h].set_rgb(x, y, glm::vec3(std::sin(theta), 0.0f, std::cos(theta)));
      }
  return in;
}

TEST(Denoiser, ShadingThatFollowsTheNormalIsFitted) {
  const float sigma_half = 0.1f;
  const double sigma_raw = sigma_half / std::sqrt(2.0);
  auto rms_error = [&](const DenoiseOptions& options) {
    double sq = 0.0;
    for (std::uint32_t seed = 1; seed <= 4; ++seed) {
      const Image out = denoise(corrugated(sigma_half, seed), options);
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          const double d = out.pixel(x, y)[0] - corrugated_shading(x);
          sq += d * d;
        }
    }
    return std::sqrt(sq / (4.0 * kSize * kSize));
  };
  // The features alone guide both: the fit regresses on the normal, the mean weighs by it.
  DenoiseOptions fit_only, mean_only;
  fit_only.candidates.clear();
  fit_only.first_order_k = {0.0f};
  fit_only.first_order_energy_radius = 0;  // the fit itself (no mean to correct it towards)
  mean_only.first_order_k.clear();
  mean_only.candidates = {DenoiseCandidate{0.0f, 0}};
  const DenoiseOptions defaults;
  const double fit = rms_error(fit_only), mean = rms_error(mean_only), both = rms_error(defaults);
  // Without colour weights the fit is ordinary least squares over the whole 15x15 window
  // (albedo and depth agree everywhere): its intercept's noise is sigma_raw / 15 where the
  // pixel's regressors sit mid-range and up to about 2-3x that where it is an extrapolation
  // (a crest of the sheet, every normal of the window on one side of the pixel's).
  EXPECT_LT(fit, sigma_raw / 5.0);
  // The weighted mean over the same window must keep to alike normals, which leaves more
  // noise (and averages different shades where the normal's noise-free distance allows).
  EXPECT_LT(fit, 0.85 * mean);
  // The defaults, whatever SURE picks, cut the noise as much as on a constant image.
  EXPECT_LT(both, sigma_raw / 4.0);
}

TEST(Denoiser, FirstOrderFitKeepsTheEnergyOfCurvedShading) {
  // Radiance quadratic in the normal (0.2 + 0.7 n_x^2: bright crests, a dark valley
  // between), as a highlight's peak is: a linear fit under-fits every peak, and nothing
  // raises the neighbours in exchange, so the fit alone darkens the image; the energy
  // correction gives the loss back within a 15x15 box (here towards the mean of the
  // halves, as there is no weighted-mean candidate to correct towards).
  const float sigma_half = 0.1f;
  auto shading = [](int x) {
    const float n = std::sin(corrugation(x));
    return 0.2f + 0.7f * n * n;
  };
  auto mean_error = [&](bool energy) {
    DenoiseOptions options;
    options.candidates.clear();
    if (!energy) options.first_order_energy_radius = 0;
    double sum = 0.0;
    for (std::uint32_t seed = 1; seed <= 4; ++seed) {
      const DenoiseInput in = corrugated(sigma_half, seed, shading);
      // Against the input's own mean (the mean of its halves), so that the noise of the
      // input cancels: what is left is what the filter moved.
      sum += region_mean(denoise(in, options), 0, 0, kSize, kSize) -
             0.5 * (region_mean(in.color[0], 0, 0, kSize, kSize) +
                    region_mean(in.color[1], 0, 0, kSize, kSize));
    }
    return sum / 4.0;
  };
  // What the filter moves, as a fraction of the image's level: 0.15% at most (the issue's
  // goal for object means is 1%; the box is clamped at the image's borders, so it is not
  // exactly mass-preserving there). Measured: 0.08% with the correction, 0.25% without.
  double level = 0.0;
  for (int x = 0; x < kSize; ++x) level += shading(x);
  level /= kSize;
  const double corrected = mean_error(true) / level, fit_alone = mean_error(false) / level;
  EXPECT_LT(std::abs(corrected), 0.0015);
  // Without the correction the fit loses more than that: the test can tell.
  EXPECT_LT(fit_alone, -0.0015);
}

// A light seen directly, flush with the ceiling around it (the features agree), with the
// levels and noise of the cornell box's light at 256x256 and 16 spp: a square at 15 with a
// half-buffer noise of 0.2, its rim of partly covered pixels at 10 with 1.5, the ceiling at
// 0.25 with 0.2. Smoothed over a box that reaches the rim, the square's relative variance
// took in the rim's and the ceiling's, and the colour distance then let its pixels take in
// the rim: the square's mean fell by more than 2 of its raw standard errors (seeds 1 and
// 2). With the variance smoothed over pixels of its own level it keeps its energy. (A rim
// three times noisier still pulls it down by 0.15-0.3%: docs/DENOISER.md, "Known limits".)
TEST(Denoiser, QuietBrightRegionBesideNoisyEdgesKeepsItsEnergy) {
  constexpr int kLo = 20, kHi = 44;
  auto kind = [](int x, int y) {
    const bool in = x >= kLo && x < kHi && y >= kLo && y < kHi;
    const bool inner = x > kLo && x < kHi - 1 && y > kLo && y < kHi - 1;
    return inner ? 0 : in ? 1 : 2;  // square, rim, ceiling
  };
  const float level[3] = {15.0f, 10.0f, 0.25f}, sigma[3] = {0.2f, 1.5f, 0.2f};
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    DenoiseInput in =
        synthetic([](int, int) { return 0.0f; }, [](int, int) { return 0.5f; }, 0.0f, seed);
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    for (int h = 0; h < 2; ++h)
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          const int k = kind(x, y);
          in.color[h].set_rgb(x, y, glm::vec3(std::max(0.0f, level[k] + sigma[k] * noise(rng))));
        }
    const Image out = denoise(in);
    double raw = 0.0, denoised = 0.0, variance = 0.0;
    int n = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        if (kind(x, y) == 0) {
          const double a = in.color[0].pixel(x, y)[0], b = in.color[1].pixel(x, y)[0];
          raw += 0.5 * (a + b);
          denoised += out.pixel(x, y)[0];
          variance += 0.25 * (a - b) * (a - b);
          ++n;
        }
    const double z = (denoised - raw) / std::sqrt(variance);
    EXPECT_LT(std::abs(z), 2.0) << "seed " << seed << ": raw mean " << raw / n << ", denoised "
                                << denoised / n;
  }
}

TEST(Denoiser, FireflyEnergyIsKeptAndStaysLocal) {
  const float c = 0.5f, sigma_half = 0.1f, excess = 200.0f;
  DenoiseInput in =
      synthetic([&](int, int) { return c; }, [](int, int) { return 0.5f; }, sigma_half, 3);
  const int fireflies[4][2] = {{12, 12}, {50, 14}, {14, 49}, {48, 50}};
  for (const auto& f : fireflies)
    for (int ch = 0; ch < 3; ++ch) in.color[0].pixel(f[0], f[1])[ch] += excess;
  DenoiseStats stats;
  const Image out = denoise(in, {}, {}, &stats);
  EXPECT_GE(stats.outliers, 4);
  // The truth: every pixel c, plus each firefly's excess once in one half (half of it in
  // the mean of the halves). The sum of the raw mean has noise sigma_half / sqrt 2 per
  // pixel, so sigma_half / sqrt 2 * kSize over the image; a weighted mean of it no more
  // than twice that. Dropping the fireflies (clamping) misses by 400.
  const double n = double(kSize) * kSize;
  const double truth = c * n + 4 * 0.5 * excess;
  const double sigma_sum = sigma_half / std::sqrt(2.0) * kSize;
  EXPECT_NEAR(region_mean(out, 0, 0, kSize, kSize) * n, truth, 4.0 * 2.0 * sigma_sum);
  // Away from them (the cross (x or y in [24, 40)) is more than 10 pixels from every
  // firefly): the constant, within a raw pixel's noise, as without fireflies.
  const float sigma_raw = sigma_half / std::sqrt(2.0f);
  double worst = 0.0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const bool far = (x >= 24 && x < 40) || (y >= 24 && y < 40);
      if (far) worst = std::max(worst, std::abs(double(out.pixel(x, y)[0]) - c));
    }
  EXPECT_LT(worst, sigma_raw);
  // Near them the excess is spread, not left as a spike: no pixel keeps more than a
  // tenth of a firefly's contribution to the mean (excess / 2).
  float peak = 0.0f;
  for (float v : out.data) peak = std::max(peak, v);
  EXPECT_LT(peak, c + 0.1f * 0.5f * excess);
}

TEST(Denoiser, SameOutputWithAnyThreadCount) {
  auto ramp = [](int x, int y) { return 0.01f * float(x + y); };
  const DenoiseInput in = synthetic(
      ramp, [](int x, int) { return x < 20 ? 0.3f : 0.6f; }, 0.1f);
  Image one, many;
  tbb::task_arena(1).execute([&] { one = denoise(in); });
  tbb::task_arena(2).execute([&] { many = denoise(in); });
  ASSERT_EQ(one.data.size(), many.data.size());
  EXPECT_TRUE(one.data == many.data);
}

TEST(Denoiser, BadInputGivesClearErrors) {
  const DenoiseInput good =
      synthetic([](int, int) { return 0.5f; }, [](int, int) { return 0.5f; }, 0.1f);
  auto message = [](const DenoiseInput& in) -> std::string {
    try {
      denoise(in);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  DenoiseInput missing = good;
  missing.albedo[1] = Image();
  missing.depth[0] = Image();
  EXPECT_NE(message(missing).find("missing input layers: albedo_b, depth_a"), std::string::npos)
      << message(missing);
  DenoiseInput size = good;
  size.normal[0] = Image(kSize, kSize - 1, 3);
  EXPECT_NE(message(size).find("'normal_a' is 64x63"), std::string::npos) << message(size);
  DenoiseInput channels = good;
  channels.depth[1] = Image(kSize, kSize, 3);
  EXPECT_NE(message(channels).find("'depth_b' has 3 channels"), std::string::npos);
  for (float bad : {std::nanf(""), INFINITY, -INFINITY}) {
    DenoiseInput nan = good;
    nan.color[1].pixel(5, 9)[2] = bad;
    EXPECT_NE(message(nan).find("'color_b' has a non-finite value"), std::string::npos);
    EXPECT_NE(message(nan).find("(5, 9)"), std::string::npos) << message(nan);
    DenoiseInput feature = good;
    feature.depth[0].pixel(3, 4)[0] = bad;
    EXPECT_NE(message(feature).find("'depth_a' has a non-finite value"), std::string::npos);
  }
  // Options that cannot work: no candidate at all, a negative or NaN ridge.
  auto option_message = [&](const DenoiseOptions& options) -> std::string {
    try {
      denoise(good, options);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  DenoiseOptions none;
  none.candidates.clear();
  none.first_order_k.clear();
  EXPECT_NE(option_message(none).find("at least one candidate"), std::string::npos);
  for (float ridge : {-1e-3f, std::nanf("")}) {
    DenoiseOptions bad_ridge;
    bad_ridge.first_order_ridge = ridge;
    EXPECT_NE(option_message(bad_ridge).find("first_order_ridge must be >= 0"), std::string::npos);
  }
}

TEST(Denoiser, HugeValuesGiveFiniteOutput) {
  DenoiseInput in = synthetic([](int, int) { return 0.5f; }, [](int, int) { return 0.5f; }, 0.1f);
  in.color[0].pixel(10, 10)[0] = 3e38f;
  in.color[1].pixel(40, 40)[1] = 1e30f;
  in.depth[0].pixel(20, 20)[0] = 1e30f;
  const Image out = denoise(in);
  for (float v : out.data) ASSERT_TRUE(std::isfinite(v));
}

// util/progress.h's rule: a callback that returns false stops the work, which returns
// what it has (the halves' mean, undenoised) and says so; it never throws for it.
TEST(Denoiser, ProgressCanStopItAndGetsTheUndenoisedMean) {
  const DenoiseInput in = synthetic([](int x, int) { return x < 32 ? 0.25f : 1.0f; },
                                    [](int, int) { return 0.5f; }, 0.1f);
  Image mean(in.color[0].width, in.color[0].height, 3);
  for (std::size_t i = 0; i < mean.data.size(); ++i)
    mean.data[i] = 0.5f * (in.color[0].data[i] + in.color[1].data[i]);
  // Stopped at the first report (after the variance) and at a later one (inside the cross
  // filter, after its first strip).
  for (const double stop_after : {0.0, 0.1}) {
    SCOPED_TRACE(stop_after);
    DenoiseStats stats;
    int calls = 0;
    Image out;
    ASSERT_NO_THROW(out = denoise(
                        in, {},
                        [&](double f, const std::string&) {
                          ++calls;
                          return f <= stop_after;
                        },
                        &stats));
    EXPECT_TRUE(stats.interrupted);
    EXPECT_GE(calls, 1);
    ASSERT_EQ(out.data.size(), mean.data.size());
    EXPECT_EQ(out.data, mean.data);
  }
  DenoiseStats stats;
  double last = 0.0;
  const Image out = denoise(
      in, {},
      [&](double f, const std::string&) {
        last = f;
        return true;
      },
      &stats);
  EXPECT_EQ(last, 1.0);
  EXPECT_FALSE(stats.interrupted);
  EXPECT_NE(out.data, mean.data);  // denoised: the noise of the halves' mean is gone
}

}  // namespace
}  // namespace pbrkit
