// The learned denoiser (docs/LEARNED_DENOISER.md): the C++ inference against PyTorch's
// (tools/denoiser/model.py, through the files tools/denoiser/export_reference.py wrote into
// tests/data/denoiser), then its properties on weights drawn here (tiles, receptive field,
// guards, exposure, the mean, determinism, stopping), then the weights file's refusals.
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "pbrkit/denoise/denoiser.h"
#include "pbrkit/denoise/denoiser_choice.h"
#include "pbrkit/denoise/learned/layers.h"
#include "pbrkit/denoise/learned/tiles.h"
#include "pbrkit/denoise/learned_denoiser.h"
#include "pbrkit/util/data_dir.h"
#include "pbrkit/util/error.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

using learned::kLayerCount;
using learned::kLayers;

// ---------------------------------------------------------------------------------------
// Weights files, written as tools/denoiser/model.py's write_weights writes them.

struct LayerParams {
  std::vector<float> weight;  // OIHW
  std::vector<float> bias;
};
using Params = std::vector<LayerParams>;

// PyTorch's default Conv2d range, uniform in +-1/sqrt(fan_in); the heads scaled by
// `head_gain` so that the kernels are far from uniform (32: a kernel's largest weight then
// averages about 0.28, where a uniform 5x5 kernel has 0.04). `colour_blind` zeroes enc0a's
// weights on the three colour channels: the kernels then depend on albedo and normal only.
Params random_params(std::uint32_t seed, float head_gain = 32.0f, bool colour_blind = false) {
  std::mt19937 rng(seed);
  Params params;
  for (const learned::LayerSpec& spec : kLayers) {
    const float bound = 1.0f / std::sqrt(float(spec.in * 9));
    const float gain = spec.relu ? 1.0f : head_gain;
    std::uniform_real_distribution<float> u(-bound, bound);
    LayerParams p;
    p.weight.resize(std::size_t(spec.out) * spec.in * 9);
    p.bias.resize(std::size_t(spec.out));
    for (float& w : p.weight) w = u(rng) * gain;
    for (float& b : p.bias) b = u(rng) * gain;
    params.push_back(std::move(p));
  }
  if (colour_blind)
    for (int o = 0; o < kLayers[0].out; ++o)
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 9; ++k)
          params[0].weight[(std::size_t(o) * kLayers[0].in + i) * 9 + k] = 0;
  return params;
}

std::uint32_t crc_of(const std::vector<char>& data) {
  return std::uint32_t(
      crc32_z(0L, reinterpret_cast<const unsigned char*>(data.data()), data.size()));
}

// The file's bytes; `edit` may change the header before it is written (the tensors' data
// and its CRC are already in it).
std::vector<char> pbnn_bytes(const Params& params,
                             const std::function<void(nlohmann::json&)>& edit = {}) {
  std::vector<char> data;
  nlohmann::json tensors = nlohmann::json::array();
  for (int l = 0; l < kLayerCount; ++l) {
    const learned::LayerSpec& spec = kLayers[l];
    for (int part = 0; part < 2; ++part) {
      const std::vector<float>& v = part ? params[l].bias : params[l].weight;
      nlohmann::json shape = part ? nlohmann::json::array({spec.out})
                                  : nlohmann::json::array({spec.out, spec.in, 3, 3});
      tensors.push_back({{"name", std::string(spec.name) + (part ? ".bias" : ".weight")},
                         {"shape", shape},
                         {"offset", data.size()}});
      const char* bytes = reinterpret_cast<const char*>(v.data());
      data.insert(data.end(), bytes, bytes + v.size() * sizeof(float));
    }
  }
  nlohmann::json header = {{"network", "kpcn-unet-v1"},
                           {"input_transform", "log1p-autoexposure-v1"},
                           {"tensors", tensors},
                           {"data_bytes", data.size()},
                           {"crc32", crc_of(data)},
                           {"commit", "test"},
                           {"dataset", "random weights"},
                           {"steps", 0},
                           {"created", "now"}};
  if (edit) edit(header);
  const std::string h = header.dump();
  std::string out = "PBRKITNN";
  const std::uint32_t words[2] = {1, std::uint32_t(h.size())};
  out.append(reinterpret_cast<const char*>(words), sizeof words);
  out += h;
  out.resize((out.size() + 63) / 64 * 64, '\0');
  out.append(data.data(), data.size());
  return std::vector<char>(out.begin(), out.end());
}

std::filesystem::path write_file(const std::filesystem::path& path, const std::vector<char>& b) {
  std::ofstream(path, std::ios::binary).write(b.data(), std::streamsize(b.size()));
  return path;
}

LearnedDenoiser denoiser_with(const Params& params, int tile = 0, int threads = 0) {
  LearnedDenoiserOptions options;
  options.weights = write_file(test::scratch_dir() / "weights.pbnn", pbnn_bytes(params));
  options.tile = tile;
  options.threads = threads;
  return LearnedDenoiser(options);
}

// ---------------------------------------------------------------------------------------
// Images.

struct Inputs {
  Image color, albedo, normal;
};

// Colour: a gradient times log-normal noise (about 1e-3 to 1e2) with a few fireflies;
// albedo uniform in [0, 1]; unit normals in random directions.
Inputs random_inputs(int width, int height, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Inputs in{Image(width, height, 3), Image(width, height, 3), Image(width, height, 3)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float base = 0.05f + 2.0f * float(x) / float(width) * (1.0f - 0.5f * float(y) / height);
      glm::vec3 n(gauss(rng), gauss(rng), gauss(rng));
      for (int c = 0; c < 3; ++c) {
        in.color.pixel(x, y)[c] = base * std::exp(1.2f * gauss(rng));
        in.albedo.pixel(x, y)[c] = u(rng);
      }
      in.normal.set_rgb(x, y, glm::normalize(n));
      if (u(rng) < 0.002f) in.color.set_rgb(x, y, glm::vec3(5000.0f));
    }
  return in;
}

// The Portable Float Map export_reference.py writes: "PF\n<w> <h>\n-1.0\n", little-endian
// float32 RGB, rows bottom to top.
Image read_pfm(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int width = 0, height = 0;
  float scale = 0.0f;
  in >> magic >> width >> height >> scale;
  in.get();  // the one whitespace character before the data
  if (!in || magic != "PF" || scale >= 0.0f) fail("{}: not a little-endian RGB PFM", path.string());
  Image image(width, height, 3);
  for (int y = height - 1; y >= 0; --y)
    in.read(reinterpret_cast<char*>(image.pixel(0, y)), std::streamsize(width) * 3 * sizeof(float));
  if (!in) fail("{}: truncated", path.string());
  return image;
}

std::filesystem::path gunzip(const std::filesystem::path& from, const std::filesystem::path& to) {
  gzFile gz = gzopen(from.c_str(), "rb");
  if (!gz) fail("{}: cannot open", from.string());
  std::vector<char> bytes;
  char buffer[1 << 16];
  int n = 0;
  while ((n = gzread(gz, buffer, sizeof buffer)) > 0) bytes.insert(bytes.end(), buffer, buffer + n);
  gzclose(gz);
  if (n < 0) fail("{}: not gzip", from.string());
  return write_file(to, bytes);
}

// The largest |a - b| / (|b| + floor) over every value: relative, but near 0 relative to
// `floor` (where the compositor's r0 = d0 - a0 U(D(d0)) + a0 U(r1) cancels, or the clamp
// at 0 cuts, a relative figure measures only rounding of much larger terms).
double worst_relative(const Image& a, const Image& b, double floor) {
  EXPECT_EQ(a.data.size(), b.data.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.data.size() && i < b.data.size(); ++i)
    worst = std::max(worst, std::abs(double(a.data[i]) - double(b.data[i])) /
                                (std::abs(double(b.data[i])) + floor));
  return worst;
}

double mean_value(const Image& image) {
  double sum = 0.0;
  for (float v : image.data) sum += v;
  return sum / double(image.data.size());
}

template <typename F>
void expect_error_containing(F&& f, const std::string& text) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one containing '" << text << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

void expect_finite_non_negative(const Image& image) {
  for (std::size_t i = 0; i < image.data.size(); ++i)
    ASSERT_TRUE(std::isfinite(image.data[i]) && image.data[i] >= 0.0f)
        << "value " << i << " is " << image.data[i];
}

// ---------------------------------------------------------------------------------------
// C++ against PyTorch.

TEST(LearnedDenoiser, MatchesPyTorchOnTheReference) {
  const auto dir = test::test_data("denoiser");
  LearnedDenoiserOptions options;
  options.weights = gunzip(dir / "reference.pbnn.gz", test::scratch_dir() / "reference.pbnn");
  const LearnedDenoiser denoiser(options);
  EXPECT_EQ(denoiser.info().network, "kpcn-unet-v1");
  EXPECT_EQ(denoiser.info().parameters, 367325);
  nlohmann::json reference;
  std::ifstream(dir / "reference.json") >> reference;

  const Image color = read_pfm(dir / "reference_color.pfm");
  const Image albedo = read_pfm(dir / "reference_albedo.pfm");
  const Image normal = read_pfm(dir / "reference_normal.pfm");
  const Image expected = read_pfm(dir / "reference_output.pfm");
  ASSERT_EQ(color.width, reference["width"].get<int>());
  LearnedDenoiseStats stats;
  const Image out = denoiser.denoise(color, albedo, normal, {}, &stats);
  // The contract's autoexposure, in double precision, summed in another order than numpy's
  // pairwise sums: 1e-12, against export_reference.py's own and model.py's, which its
  // output used.
  EXPECT_NEAR(stats.exposure / reference["exposure_float64"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(stats.exposure / reference["exposure"].get<double>(), 1.0, 1e-7);
  expect_finite_non_negative(out);
  // 1e-4 relative to each value, or to a tenth of the image's mean where the value is
  // smaller: two float32 implementations (oneDNN's and PyTorch's convolutions sum in other
  // orders) differ by about 1e-6 in the logits, the kernels' weights then by about 1e-6
  // relative, and where r0's terms cancel (to a small or clamped value) that is relative
  // to the terms, not to r0.
  const double floor = 0.1 * mean_value(expected);
  EXPECT_LT(worst_relative(out, expected, floor), 1e-4);
}

TEST(LearnedDenoiser, BlendNetworkMatchesPyTorchOnTheReference) {
  // kpcn-blend-v2 (docs/LEARNED_DENOISER.md): the classic output's three input channels and
  // the per-pixel blend with it, on random weights whose blend weights span (0.1, 0.9).
  const auto dir = test::test_data("denoiser");
  LearnedDenoiserOptions options;
  options.weights =
      gunzip(dir / "blend_reference.pbnn.gz", test::scratch_dir() / "blend_reference.pbnn");
  const LearnedDenoiser denoiser(options);
  EXPECT_EQ(denoiser.info().network, "kpcn-blend-v2");
  EXPECT_EQ(denoiser.info().parameters, 367902);
  EXPECT_TRUE(denoiser.blends_classic());
  const Image color = read_pfm(dir / "reference_color.pfm");
  const Image albedo = read_pfm(dir / "reference_albedo.pfm");
  const Image normal = read_pfm(dir / "reference_normal.pfm");
  const Image classic = read_pfm(dir / "blend_reference_classic.pfm");
  const Image expected = read_pfm(dir / "blend_reference_output.pfm");
  const Image out = denoiser.denoise(color, albedo, normal, classic);
  expect_finite_non_negative(out);
  EXPECT_LT(worst_relative(out, expected, 0.1 * mean_value(expected)), 1e-4);
  // The output does depend on the classic image: a network that ignored it (or read the
  // colour in its place) would give the same image for a classic output scaled by 2.
  Image doubled = classic;
  for (float& v : doubled.data) v *= 2.0f;
  EXPECT_GT(worst_relative(denoiser.denoise(color, albedo, normal, doubled), expected,
                           0.1 * mean_value(expected)),
            0.05);
  // Without the classic output, or with one of another size: errors naming what is missing.
  expect_error_containing([&] { (void)denoiser.denoise(color, albedo, normal); },
                          "needs the classic denoiser's output");
  expect_error_containing([&] { (void)denoiser.denoise(color, albedo, normal, Image(8, 8, 3)); },
                          "classic");
}

// ---------------------------------------------------------------------------------------
// Properties, on weights drawn here.

TEST(LearnedDenoiser, TiledEqualsUntiled) {
  // 300x260 in inner tiles of 64: five columns and rows (the last ones 44 and 4 pixels), so
  // that tiles start inside the image on both axes (x0 - 96 > 0) and end at its edges, and
  // one of 4 rows is padded to 16.
  const Params params = random_params(11);
  const Inputs in = random_inputs(300, 260, 12);
  LearnedDenoiseStats whole_stats, tiled_stats;
  const Image whole =
      denoiser_with(params).denoise(in.color, in.albedo, in.normal, {}, &whole_stats);
  const Image tiled =
      denoiser_with(params, 64).denoise(in.color, in.albedo, in.normal, {}, &tiled_stats);
  EXPECT_EQ(whole_stats.tiles, 1);
  EXPECT_EQ(tiled_stats.tiles, 25);
  // The same arithmetic on the same values but for the convolutions' summation order,
  // which oneDNN may pick by the tensor's size: a few float32 roundings.
  EXPECT_LT(worst_relative(tiled, whole, 0.1 * mean_value(whole)), 1e-5);
}

TEST(LearnedDenoiser, NoOutputPixelBeyondTheReceptiveFieldChanges) {
  // One albedo value changed (the autoexposure, from the colour, stays): every output pixel
  // that changes lies within learned::receptive_field_radius() of it, for the pixel at each
  // alignment that reaches furthest to one side or the other (0, 1, 14, 15 mod 16). And the
  // change does travel through the coarse levels (beyond 48 pixels): a radius too small
  // would break the tiles (TiledEqualsUntiled), one this test cannot see stays this test's.
  const int size = 256, radius = learned::receptive_field_radius();
  const LearnedDenoiser denoiser = denoiser_with(random_params(21));
  const Inputs in = random_inputs(size, size, 22);
  const Image before = denoiser.denoise(in.color, in.albedo, in.normal);
  for (const int p : {32, 33, 46, 47}) {
    Inputs changed = in;
    changed.albedo.set_rgb(p + 64, p, glm::vec3(1.0f) - in.albedo.rgb(p + 64, p));
    const Image after = denoiser.denoise(changed.color, changed.albedo, changed.normal);
    int farthest = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        if (std::memcmp(before.pixel(x, y), after.pixel(x, y), 3 * sizeof(float)) != 0)
          farthest = std::max(farthest, std::max(std::abs(x - (p + 64)), std::abs(y - p)));
    EXPECT_LE(farthest, radius) << "albedo changed at (" << p + 64 << ", " << p << ")";
    EXPECT_GT(farthest, 48) << "albedo changed at (" << p + 64 << ", " << p << ")";
  }
}

TEST(LearnedDenoiser, OutputIsFiniteAndNonNegativeForAnyInput) {
  const LearnedDenoiser denoiser = denoiser_with(random_params(31));
  Inputs in = random_inputs(70, 40, 32);
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float big = std::numeric_limits<float>::max();
  // Colour values the input transform takes as 0, and their twin image with those zeros.
  Inputs zeroed = in;
  const std::vector<std::pair<int, glm::vec3>> bad = {
      {3, {nan, 1.0f, 2.0f}}, {17, {inf, -inf, 0.5f}}, {40, {-3.0f, -1e-20f, nan}}};
  for (const auto& [x, v] : bad) {
    in.color.set_rgb(x, 5, v);
    glm::vec3 z = v;
    for (int c = 0; c < 3; ++c) z[c] = std::isfinite(v[c]) && v[c] > 0.0f ? v[c] : 0.0f;
    zeroed.color.set_rgb(x, 5, z);
  }
  for (Inputs* i : {&in, &zeroed}) {
    i->albedo.set_rgb(8, 9, {nan, inf, -inf});
    i->normal.set_rgb(9, 9, {nan, -inf, 3.0f});
  }
  const Image out = denoiser.denoise(in.color, in.albedo, in.normal);
  expect_finite_non_negative(out);
  EXPECT_EQ(out.data, denoiser.denoise(zeroed.color, zeroed.albedo, zeroed.normal).data);

  // The largest floats: the kernels' averages stay finite, but the compositor's 2x2 sums
  // overflow; the output is still finite and non-negative.
  Inputs huge = random_inputs(48, 48, 33);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; x += 2) huge.color.set_rgb(x, y, glm::vec3(big));
  expect_finite_non_negative(denoiser.denoise(huge.color, huge.albedo, huge.normal));
  // An image that is all 0 (no block counts for the autoexposure: s = 1) gives 0.
  const Image black(33, 17, 3, 0.0f);
  const Image out_black = denoiser.denoise(black, Image(33, 17, 4, 0.5f), Image(33, 17, 3, 0.0f));
  EXPECT_EQ(out_black.data, std::vector<float>(33 * 17 * 3, 0.0f));
}

TEST(LearnedDenoiser, FlatImageComesBackFlat) {
  // Every kernel's weights sum to 1, D and U keep a constant, the compositor's coefficients
  // (1, -a, a) sum to 1: a constant image comes back constant but for float rounding (a
  // sum of 25 products, three scales: well under 1e-5 relative), whatever the features.
  const LearnedDenoiser denoiser = denoiser_with(random_params(41));
  const Inputs in = random_inputs(90, 70, 42);
  for (const float level : {1e-3f, 0.5f, 7e3f}) {
    const Image out = denoiser.denoise(Image(90, 70, 3, level), in.albedo, in.normal);
    for (float v : out.data) ASSERT_NEAR(v, level, 1e-5f * level);
  }
}

TEST(LearnedDenoiser, FlatNoisyImageKeepsItsMean) {
  // A flat grey m with uniform noise of standard deviation sigma (never negative, so the
  // input transform's clamp at 0 adds no bias), denoised by a network blind to the colour
  // (enc0a's colour weights zeroed), so that each output pixel is sum_i W_pi c_i with
  // weights W independent of the noise and sum_i W_pi = 1 (FlatImageComesBackFlat).
  // Then E[mean(out)] = m exactly, and mean(out) - m = (1/N) sum_i col_i n_i with col_i =
  // sum_p W_pi, the total weight input pixel i gets, which averages 1: its standard
  // deviation is sigma rms(col) / sqrt(N), against the input mean's sigma / sqrt(N).
  // Over K noise draws, the errors' mean must be within 4 standard errors of 0 (its own
  // spread, measured: a t-test, false alarm about 1e-4), and their spread within 3 times
  // the input mean's (rms(col) <= 3: a pixel weighing in 3 times its share on average
  // would be a kernel concentrating on a few pixels, no longer a denoiser's average).
  const int width = 128, height = 96, draws = 8;
  const float m = 0.5f, sigma = 0.1f;
  const float half_width = sigma * std::sqrt(3.0f);  // uniform on [m - hw, m + hw]
  const LearnedDenoiser denoiser = denoiser_with(random_params(51, 32.0f, true));
  const Inputs features = random_inputs(width, height, 52);
  std::mt19937 rng(53);
  std::uniform_real_distribution<float> noise(-half_width, half_width);
  std::vector<double> errors;
  for (int k = 0; k < draws; ++k) {
    Image color(width, height, 3);
    for (float& v : color.data) v = m + noise(rng);
    errors.push_back(mean_value(denoiser.denoise(color, features.albedo, features.normal)) - m);
  }
  double mean = 0.0, square = 0.0;
  for (double e : errors) mean += e / draws, square += e * e / draws;
  const double spread = std::sqrt(std::max(square - mean * mean, 0.0) * draws / (draws - 1));
  const double input_mean_sd = sigma / std::sqrt(double(width) * height * 3);
  EXPECT_LT(std::abs(mean), 4.0 * spread / std::sqrt(double(draws)) + 1e-7);
  EXPECT_LT(std::sqrt(square), 3.0 * input_mean_sd);
}

TEST(LearnedDenoiser, ExposureScalingCommutes) {
  // denoise(k c) = k denoise(c): s(k c) = s(c) / k, so the network sees the same input,
  // and the kernels and compositor are linear in the colour. Only rounding differs: k c is
  // rounded to float (2^-24 relative), which moves log1p(s c) and so the logits by about
  // 1e-7, the kernels' weights by about 1e-6 relative; with the reference's floor (a tenth
  // of the mean) 1e-4 leaves two orders of magnitude.
  const LearnedDenoiser denoiser = denoiser_with(random_params(61));
  const Inputs in = random_inputs(120, 80, 62);
  LearnedDenoiseStats stats;
  const Image out = denoiser.denoise(in.color, in.albedo, in.normal, {}, &stats);
  for (const float k : {0.01f, 100.0f}) {
    Image scaled = in.color;
    for (float& v : scaled.data) v *= k;
    LearnedDenoiseStats scaled_stats;
    Image out_k = denoiser.denoise(scaled, in.albedo, in.normal, {}, &scaled_stats);
    EXPECT_NEAR(scaled_stats.exposure * k / stats.exposure, 1.0, 1e-6) << "k = " << k;
    for (float& v : out_k.data) v /= k;
    EXPECT_LT(worst_relative(out_k, out, 0.1 * mean_value(out)), 1e-4) << "k = " << k;
  }
}

TEST(LearnedDenoiser, TwoRunsAreBitIdentical) {
  const Params params = random_params(71);
  const Inputs in = random_inputs(160, 120, 72);  // 3x2 tiles of 64
  for (const int tile : {0, 64}) {
    const LearnedDenoiser denoiser = denoiser_with(params, tile);
    const Image a = denoiser.denoise(in.color, in.albedo, in.normal);
    const Image b = denoiser.denoise(in.color, in.albedo, in.normal);
    ASSERT_EQ(a.data.size(), b.data.size());
    EXPECT_EQ(std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)), 0)
        << "tile " << tile;
  }
  // One thread: the same image but for the convolutions' summation order.
  const Image many = denoiser_with(params).denoise(in.color, in.albedo, in.normal);
  const Image one = denoiser_with(params, 0, 1).denoise(in.color, in.albedo, in.normal);
  EXPECT_LT(worst_relative(one, many, 0.1 * mean_value(many)), 1e-5);
}

TEST(LearnedDenoiser, StopsWhenAskedWithTheInputUndenoised) {
  const LearnedDenoiser denoiser = denoiser_with(random_params(81), 64);
  Inputs in = random_inputs(160, 100, 82);
  in.color.set_rgb(3, 3, glm::vec3(-1.0f));
  // Asked to stop once the second tile begins, and within the first tile (the callback
  // is asked before each layer, so a stop is seen within one convolution).
  for (const bool within_first : {false, true}) {
    int calls = 0;
    LearnedDenoiseStats stats;
    const Image out = denoiser.denoise(
        in.color, in.albedo, in.normal,
        [&](double, const std::string& detail) {
          ++calls;
          return within_first ? calls < 3 : detail.rfind("tile 2/", 0) != 0;
        },
        &stats);
    EXPECT_TRUE(stats.interrupted);
    EXPECT_EQ(stats.tiles, within_first ? 0 : 1);
    for (int y = 0; y < 100; ++y)
      for (int x = 0; x < 160; ++x)
        for (int c = 0; c < 3; ++c)
          ASSERT_EQ(out.pixel(x, y)[c], std::max(in.color.pixel(x, y)[c], 0.0f));
  }
}

// Two random half buffers of one render (their features a's, every pixel at depth 3, not the
// environment), the DenoiseInput of them and the halves' mean colour.
struct Halves {
  Inputs a, b;
  DenoiseInput input;
  Image mean;
};

Halves random_halves(int w, int h, std::uint32_t seed) {
  Halves r{random_inputs(w, h, seed), random_inputs(w, h, seed + 1), {}, Image(w, h, 3)};
  r.input.color[0] = r.a.color, r.input.color[1] = r.b.color;
  r.input.albedo[0] = r.input.albedo[1] = r.a.albedo;
  r.input.normal[0] = r.input.normal[1] = r.a.normal;
  for (Image& d : r.input.depth) d = Image(w, h, 1, 3.0f);
  for (std::size_t i = 0; i < r.mean.data.size(); ++i)
    r.mean.data[i] = 0.5f * (r.a.color.data[i] + r.b.color.data[i]);
  return r;
}

// denoise_render's learned path (denoise/denoiser_choice.h): the network on the halves'
// mean, and the pixels whose every sample saw the environment (depth 0 in both halves)
// passed through as that mean, as the classic denoiser keeps them.
TEST(LearnedDenoiser, RenderPathDenoisesTheHalvesMeanAndKeepsTheDirectEnvironment) {
  const Params params = random_params(95);
  DenoiserChoice choice;
  choice.kind = DenoiserKind::kLearned;
  choice.weights = write_file(test::scratch_dir() / "render_path.pbnn", pbnn_bytes(params));
  const int w = 70, h = 50;
  Halves halves = random_halves(w, h, 96);
  const Inputs& a = halves.a;
  DenoiseInput& input = halves.input;
  const Image& mean = halves.mean;
  // The left third saw only the environment in both halves; one more pixel in one half only.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w / 3; ++x)
      input.depth[0].pixel(x, y)[0] = input.depth[1].pixel(x, y)[0] = 0;
  input.depth[0].pixel(50, 20)[0] = 0.0f;
  const DenoiseRun run = denoise_render(input, choice);
  ASSERT_FALSE(run.interrupted);
  const Image direct =
      LearnedDenoiser(LearnedDenoiserOptions{choice.weights}).denoise(mean, a.albedo, a.normal);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(run.image.pixel(x, y)[c], x < w / 3 ? mean.pixel(x, y)[c] : direct.pixel(x, y)[c])
            << x << "," << y;
  EXPECT_NE(direct.pixel(5, 5)[0], mean.pixel(5, 5)[0]);  // the pass-through is not a no-op
}

// kpcn-blend-v2 through denoise_render: the classic denoiser's output of the same input
// (denoiser.h, default options) is what the network reads and blends with.
TEST(LearnedDenoiser, RenderPathGivesTheBlendNetworkTheClassicOutput) {
  DenoiserChoice choice;
  choice.kind = DenoiserKind::kLearned;
  choice.weights = gunzip(test::test_data("denoiser") / "blend_reference.pbnn.gz",
                          test::scratch_dir() / "render_path_blend.pbnn");
  const Halves halves = random_halves(48, 40, 98);
  const Inputs& a = halves.a;
  const DenoiseInput& input = halves.input;
  const Image& mean = halves.mean;
  std::vector<double> fractions;
  const DenoiseRun run = denoise_render(input, choice, [&](double f, const std::string&) {
    fractions.push_back(f);
    return true;
  });
  ASSERT_FALSE(run.interrupted);
  const LearnedDenoiser network(LearnedDenoiserOptions{choice.weights});
  const Image classic = denoise(input);
  EXPECT_EQ(run.image.data, network.denoise(mean, a.albedo, a.normal, classic).data);
  // Another classic image gives another output: the one read is the classic denoiser's.
  EXPECT_NE(run.image.data, network.denoise(mean, a.albedo, a.normal, mean).data);
  // The progress runs through both, once, never backwards.
  ASSERT_FALSE(fractions.empty());
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  // Stopped once the network runs: the classic denoiser's image, not the raw mean.
  const DenoiseRun stopped = denoise_render(input, choice, [&](double, const std::string& detail) {
    return detail.rfind("classic", 0) == 0;
  });
  EXPECT_TRUE(stopped.interrupted);
  EXPECT_EQ(stopped.image.data, classic.data);
}

TEST(LearnedDenoiser, RefusesImagesOfAnotherSizeOrTooFewChannels) {
  const LearnedDenoiser denoiser = denoiser_with(random_params(91));
  const Image c(20, 10, 3, 1.0f);
  EXPECT_THROW(denoiser.denoise(c, Image(20, 11, 3), Image(20, 10, 3)), Error);
  EXPECT_THROW(denoiser.denoise(c, Image(20, 10, 3), Image(20, 10, 1)), Error);
  EXPECT_THROW(denoiser.denoise(Image(), Image(), Image()), Error);
}

TEST(LearnedDenoiser, DefaultWeightsAreFoundInTheDataDirectory) {
  const auto path = default_learned_denoiser_weights();
  EXPECT_EQ(path, data_dir() / "denoiser" / "kpcn-blend-v2.pbnn");
  // Until training ships the file, the default constructor names where it looked.
  if (!std::filesystem::exists(path)) {
    try {
      LearnedDenoiser denoiser;
      ADD_FAILURE() << "no error without " << path;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  } else {
    EXPECT_EQ(LearnedDenoiser().info().network, "kpcn-blend-v2");
  }
  // The network it was trained from ships beside it and reads.
  LearnedDenoiserOptions v1;
  v1.weights = data_dir() / "denoiser" / "kpcn-unet-v1.pbnn";
  EXPECT_EQ(LearnedDenoiser(v1).info().network, "kpcn-unet-v1");
}

// ---------------------------------------------------------------------------------------
// The weights file's refusals (docs/LEARNED_DENOISER.md, "The weights file"): each a
// pbrkit::Error whose message names the file and the problem.

void expect_refused(const std::filesystem::path& path, const std::string& problem) {
  try {
    LearnedDenoiserOptions options;
    options.weights = path;
    LearnedDenoiser denoiser(options);
    ADD_FAILURE() << path << " was accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
  }
}

std::filesystem::path weights_path() {
  return test::scratch_dir() / "weights.pbnn";
}

TEST(LearnedWeightsFile, ReadsAValidFile) {
  const LearnedDenoiser denoiser = denoiser_with(random_params(101));
  EXPECT_EQ(denoiser.info().network, "kpcn-unet-v1");
  EXPECT_EQ(denoiser.info().input_transform, "log1p-autoexposure-v1");
  EXPECT_EQ(denoiser.info().commit, "test");
  EXPECT_EQ(denoiser.info().parameters, 367325);
}

TEST(LearnedWeightsFile, RefusesAMissingFile) {
  expect_refused(test::scratch_dir() / "nothing.pbnn", "cannot open");
}

TEST(LearnedWeightsFile, RefusesATruncatedFile) {
  std::vector<char> bytes = pbnn_bytes(random_params(1));
  bytes.resize(bytes.size() - 100);
  expect_refused(write_file(weights_path(), bytes), "truncated");
  bytes.resize(40);  // inside the header
  expect_refused(write_file(weights_path(), bytes), "truncated");
}

TEST(LearnedWeightsFile, RefusesACorruptedByte) {
  std::vector<char> bytes = pbnn_bytes(random_params(1));
  bytes[bytes.size() - 1000] ^= 0x10;
  expect_refused(write_file(weights_path(), bytes), "CRC-32");
}

TEST(LearnedWeightsFile, RefusesAWrongMagic) {
  std::vector<char> bytes = pbnn_bytes(random_params(1));
  bytes[3] = 'X';
  expect_refused(write_file(weights_path(), bytes), "magic");
}

TEST(LearnedWeightsFile, RefusesAnotherFormatVersion) {
  std::vector<char> bytes = pbnn_bytes(random_params(1));
  bytes[8] = 2;
  expect_refused(write_file(weights_path(), bytes), "version 2");
}

TEST(LearnedWeightsFile, RefusesAnotherNetwork) {
  const auto bytes = pbnn_bytes(random_params(1), [](auto& h) { h["network"] = "kpcn-unet-v2"; });
  expect_refused(write_file(weights_path(), bytes), "network 'kpcn-unet-v2'");
}

TEST(LearnedWeightsFile, RefusesAnotherInputTransform) {
  const auto bytes = pbnn_bytes(random_params(1), [](auto& h) { h["input_transform"] = "log"; });
  expect_refused(write_file(weights_path(), bytes), "input transform 'log'");
}

TEST(LearnedWeightsFile, RefusesAMissingTensor) {
  const auto bytes = pbnn_bytes(random_params(1), [](auto& h) {
    auto& t = h["tensors"];
    t.erase(std::remove_if(t.begin(), t.end(), [](auto& e) { return e["name"] == "dec2b.bias"; }),
            t.end());
  });
  expect_refused(write_file(weights_path(), bytes), "dec2b.bias is missing");
}

TEST(LearnedWeightsFile, RefusesAWrongShape) {
  const auto bytes = pbnn_bytes(random_params(1), [](auto& h) {
    for (auto& t : h["tensors"])
      if (t["name"] == "enc1.weight") t["shape"] = {32, 16, 1, 9};
  });
  expect_refused(write_file(weights_path(), bytes), "enc1.weight has shape [32,16,1,9]");
}

TEST(LearnedWeightsFile, RefusesATensorOutsideTheData) {
  const auto bytes = pbnn_bytes(random_params(1), [](auto& h) {
    for (auto& t : h["tensors"])
      if (t["name"] == "head0.bias") t["offset"] = h["data_bytes"].template get<int>() - 8;
  });
  expect_refused(write_file(weights_path(), bytes), "head0.bias");
}

TEST(LearnedWeightsFile, RefusesAHeaderThatIsNotJsonOrLacksAField) {
  std::vector<char> bytes = pbnn_bytes(random_params(1));
  bytes[16] = '[';  // the header's opening brace
  expect_refused(write_file(weights_path(), bytes), "not JSON");
  for (const char* field : {"network", "tensors", "data_bytes", "crc32", "commit", "created"}) {
    const auto b = pbnn_bytes(random_params(1), [&](auto& h) { h.erase(field); });
    expect_refused(write_file(weights_path(), b), std::string("lacks the field '") + field);
  }
}

TEST(LearnedWeightsFile, RefusesANonFiniteWeight) {
  Params params = random_params(1);
  params[kLayers.size() - 1].weight[5] = std::numeric_limits<float>::quiet_NaN();
  expect_refused(write_file(weights_path(), pbnn_bytes(params)), "head0.weight holds");
}

}  // namespace
}  // namespace pbrkit
