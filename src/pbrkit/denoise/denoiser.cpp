// The denoiser's entry point: checks the input, runs the stages of stages.h in order and
// reports progress.
#include "pbrkit/denoise/denoiser.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <utility>

#include "pbrkit/denoise/inputs.h"
#include "pbrkit/util/error.h"
#include "stages.h"
#include "tile_spans.h"

namespace pbrkit {

std::vector<DenoiseCandidate> default_denoise_candidates() {
  return {DenoiseCandidate{1.0f, 3}, DenoiseCandidate{0.45f, 0}};
}

std::vector<std::string> denoise_layer_names() {
  return {"color_a",  "color_b",  "albedo_a", "albedo_b",
          "normal_a", "normal_b", "depth_a",  "depth_b"};
}

void validate_denoise_input(const DenoiseInput& in) {
  const Image* images[8] = {&in.color[0],  &in.color[1],  &in.albedo[0], &in.albedo[1],
                            &in.normal[0], &in.normal[1], &in.depth[0],  &in.depth[1]};
  const int channels[8] = {3, 3, 3, 3, 3, 3, 1, 1};
  const std::vector<std::string> names = denoise_layer_names();
  std::vector<std::string> missing;
  for (int i = 0; i < 8; ++i)
    if (images[i]->empty()) missing.push_back(names[std::size_t(i)]);
  if (!missing.empty()) {
    std::string list;
    for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m;
    fail("denoise: missing input layers: {}", list);
  }
  const int w = in.color[0].width, h = in.color[0].height;
  for (int i = 0; i < 8; ++i) {
    const Image& image = *images[i];
    const std::string& name = names[std::size_t(i)];
    if (image.width != w || image.height != h)
      fail("denoise: layer '{}' is {}x{} but color_a is {}x{}", name, image.width, image.height, w,
           h);
    if (image.channels != channels[i])
      fail("denoise: layer '{}' has {} channels, expected {}", name, image.channels, channels[i]);
    if (image.data.size() != image.pixel_count() * std::size_t(image.channels))
      fail("denoise: layer '{}' holds {} values, expected {}", name, image.data.size(),
           image.pixel_count() * std::size_t(image.channels));
    for (std::size_t j = 0; j < image.data.size(); ++j)
      if (!std::isfinite(image.data[j])) {
        const std::size_t p = j / std::size_t(image.channels);
        fail("denoise: layer '{}' has a non-finite value ({}) at pixel ({}, {})", name,
             image.data[j], p % std::size_t(w), p / std::size_t(w));
      }
  }
  if (w < 1 || h < 1) fail("denoise: the image is empty");
}

namespace {
// What every tile shares with the whole image: the depth's largest magnitude (the depth
// feature's scale) and the colour's range (the first-order fits are clamped to it).
struct ValueRange {
  float depth_max = 0.0f, lowest = 0.0f, highest = 0.0f;
};

// One half's colour, unpadded.
denoising::Channels channels_unpadded(const denoising::Channels& color, int w, int h) {
  denoising::Channels out;
  for (std::size_t c = 0; c < 3; ++c) {
    denoising::Plane m(w, h, 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) m.at(x, y) = color[c].at(x, y);
    out.push_back(std::move(m));
  }
  return out;
}

// The pixels no sample of which hit the scene: depth 0 (a miss) in both halves.
std::vector<unsigned char> direct_environment_mask(const DenoiseInput& input) {
  std::vector<unsigned char> mask(input.depth[0].data.size());
  for (std::size_t i = 0; i < mask.size(); ++i)
    mask[i] = input.depth[0].data[i] == 0.0f && input.depth[1].data[i] == 0.0f;
  return mask;
}

// Those pixels get the mean of their halves, and, in `error`, that mean's own relative
// error: the squared half difference over four (the variance of the mean of two halves),
// relative to the channel mean's level as select_candidates makes it.
void keep_direct_environment(const std::vector<unsigned char>& mask,
                             const denoising::Channels color[2], Image& out, Image* error) {
  const int w = out.width, h = out.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      if (!mask[i]) continue;
      float level = 0.0f, squared = 0.0f;
      for (std::size_t c = 0; c < 3; ++c) {
        const float a = color[0][c].at(x, y), b = color[1][c].at(x, y);
        out.data[i * 3 + c] = 0.5f * (a + b);
        level += 0.5f * (a + b) / 3.0f;
        squared += 0.25f * (a - b) * (a - b) / 3.0f;
      }
      if (error && !error->empty()) error->data[i] = squared / (level * level + 0.01f);
    }
}

// Denoises the whole of `input` (a tile or the image) with the image's `range`; false when
// `report` stopped it. `share` and `outliers` get DenoiseStats' diagnostics.
bool denoise_whole(const DenoiseInput& input, const DenoiseOptions& options,
                   const ValueRange& range, const std::function<bool(double)>& report, Image& out,
                   std::vector<double>& share, int& outliers, Image* error) {
  using namespace denoising;
  const int w = input.color[0].width, h = input.color[0].height;
  const int pad = std::max({options.radius + options.patch_radius, options.prefilter_radius + 1,
                            options.variance_radius, 1}) +
                  1;
  // Features: albedo, normal and depth, the last normalised by the image's largest value
  // so that the feature floor tau means the same in every scene.
  Image depth_scaled[2] = {input.depth[0], input.depth[1]};
  if (range.depth_max > 0.0f)
    for (Image& d : depth_scaled)
      for (float& v : d.data) v /= range.depth_max;
  std::vector<Feature> features;
  features.push_back(prefilter_feature(channels_from(input.albedo[0], pad),
                                       channels_from(input.albedo[1], pad), options,
                                       options.feature_tau));
  features.push_back(prefilter_feature(
      channels_from(input.normal[0], pad), channels_from(input.normal[1], pad), options,
      options.normal_tau > 0 ? options.normal_tau : options.feature_tau));
  features.push_back(prefilter_feature(channels_from(depth_scaled[0], pad),
                                       channels_from(depth_scaled[1], pad), options,
                                       options.feature_tau));
  // Fireflies first: the variance, the weights and the averages all see the treated halves.
  Channels color[2] = {channels_from(input.color[0], pad), channels_from(input.color[1], pad)};
  std::vector<const Feature*> feature_list;
  for (const Feature& f : features) feature_list.push_back(&f);
  const std::vector<unsigned char> environment = options.keep_direct_environment
                                                     ? direct_environment_mask(input)
                                                     : std::vector<unsigned char>{};
  outliers = spread_outliers(color, feature_list, options,
                             options.keep_direct_environment ? &environment : nullptr);
  const Channels variance =
      options.relative_variance
          ? half_variance_relative(color[0], color[1], options.variance_radius,
                                   options.variance_level_ratio)
          : half_variance(color[0], color[1], options.variance_radius);
  if (!report(0.1)) return false;

  CrossFilterInput cf;
  cf.color[0] = &color[0];
  cf.color[1] = &color[1];
  cf.variance[0] = cf.variance[1] = &variance;  // equal halves: the same variance
  cf.features = feature_list;
  cf.normal = 1;
  cf.depth = 2;
  cf.lowest = range.lowest;
  cf.highest = range.highest;
  int strips = 1;
  std::atomic<int> done{0};
  std::atomic<bool> keep_going{true};
  Candidates candidates = cross_filter(
      cf, options,
      [&] {
        if (!report(0.1 + 0.85 * double(++done) / double(std::max(1, strips)))) keep_going = false;
        return keep_going.load();
      },
      &strips);
  if (!keep_going) return false;
  // The fits (and, with zero_order_energy_radius > 0, the other zero-order candidates)
  // keep the energy of the first zero-order candidate (the 7x7 weighted mean), each half
  // against its own (first_order.cpp, docs/DENOISER.md "Energy"); the raw half when there
  // is no zero-order candidate.
  for (int half = 0; half < 2; ++half) {
    const bool reference_is_candidate = !options.candidates.empty();
    const Channels raw = reference_is_candidate ? Channels{} : channels_unpadded(color[half], w, h);
    const Channels& reference = reference_is_candidate ? candidates.color[half][0] : raw;
    for (std::size_t k = 1; k < candidates.size(); ++k) {
      const bool fit = k >= options.candidates.size();
      first_order::restore_energy(
          candidates.color[half][k], reference,
          fit ? options.first_order_energy_radius : options.zero_order_energy_radius, cf.lowest,
          cf.highest);
    }
    if (!reference_is_candidate && !candidates.color[half].empty())
      first_order::restore_energy(candidates.color[half][0], reference,
                                  options.first_order_energy_radius, cf.lowest, cf.highest);
  }
  if (options.raw_candidate) {
    // The unfiltered halves: the error of their mean is its variance, exactly (half a
    // half's), so where every filter would blur more than it removes (converged or
    // noise-free pixels: a sharp environment seen directly) the selection keeps the input.
    const Plane half_variance_mean = channel_mean(variance);
    for (int half = 0; half < 2; ++half) {
      Plane error(w, h, 0);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) error.at(x, y) = 0.5f * half_variance_mean.at(x, y);
      candidates.color[half].push_back(channels_unpadded(color[half], w, h));
      candidates.error[half].push_back(std::move(error));
    }
  }
  out = select_candidates(candidates, options, &share, error);
  if (options.keep_direct_environment) keep_direct_environment(environment, color, out, error);
  return true;
}

// The rectangle [x0, x1) x [y0, y1) of every layer.
DenoiseInput crop(const DenoiseInput& input, int x0, int y0, int x1, int y1) {
  DenoiseInput out;
  auto cut = [&](const Image& image) {
    Image c(x1 - x0, y1 - y0, image.channels);
    for (int y = y0; y < y1; ++y)
      std::copy_n(image.pixel(x0, y), std::size_t(x1 - x0) * std::size_t(image.channels),
                  c.pixel(0, y - y0));
    return c;
  };
  for (int half = 0; half < 2; ++half) {
    out.color[half] = cut(input.color[half]);
    out.albedo[half] = cut(input.albedo[half]);
    out.normal[half] = cut(input.normal[half]);
    out.depth[half] = cut(input.depth[half]);
  }
  return out;
}

}  // namespace

int denoise_tile_margin(const DenoiseOptions& o) {
  // The longest chain of stages (docs/DENOISER.md, "Tiles"), each reading the previous
  // one's output within its radius of a pixel:
  // - a prefiltered feature reads its halves' variance (a box of variance_radius) over 3x3
  //   patches (1) in its window (prefilter_radius), then its residual variance (another
  //   box) and its gradient (1);
  // - the firefly treatment scales a pixel by its window (outlier_radius) and spreads the
  //   excess over outlier_spread_radius by feature weights normalised over that same
  //   radius around the outlier: a treated pixel reads features up to twice that far;
  // - the colour's variance is a box (variance_radius) of treated colour;
  // - a candidate weighs a window (radius) of patches (patch_radius) of colour and
  //   variance;
  // - the fits get their energy back over a box (the larger energy radius);
  // - the selection smooths the errors (error_radius) and the choice (selection_radius).
  const int feature = 2 * o.variance_radius + 1 + o.prefilter_radius + 1;
  const bool fireflies = o.outlier_k > 0.0f && o.outlier_radius > 0;
  const int spread = std::max(0, o.outlier_spread_radius);
  const int treated = fireflies ? std::max(o.outlier_radius + spread, 2 * spread + feature) : 0;
  return std::max(treated + o.variance_radius, feature) + o.radius + o.patch_radius +
         std::max(o.first_order_energy_radius, o.zero_order_energy_radius) + o.error_radius +
         o.selection_radius;
}

Image denoise(const DenoiseInput& input, const DenoiseOptions& options,
              const ProgressCallback& progress, DenoiseStats* stats, Image* error) {
  const auto start = std::chrono::steady_clock::now();
  validate_denoise_input(input);
  if (options.radius < 0 || options.patch_radius < 0 || options.variance_radius < 0 ||
      options.prefilter_radius < 0 || (options.candidates.empty() && options.first_order_k.empty()))
    fail("denoise: radii must be >= 0 and there must be at least one candidate");
  if (options.first_order_energy_radius < 0 || options.zero_order_energy_radius < 0)
    fail("denoise: first_order_energy_radius and zero_order_energy_radius must be >= 0");
  if (!(options.first_order_ridge >= 0.0f))
    fail("denoise: first_order_ridge must be >= 0 (it is {})", options.first_order_ridge);
  if (options.tile < 0) fail("denoise: tile must be >= 0 (it is {})", options.tile);
  const int w = input.color[0].width, h = input.color[0].height;
  // What every tile must share with the whole image: the depth's scale and the input's
  // range (the fits are clamped to it).
  ValueRange range;
  for (const Image* d : {&input.depth[0], &input.depth[1]})
    for (float v : d->data) range.depth_max = std::max(range.depth_max, std::abs(v));
  range.lowest = range.highest = input.color[0].data.front();
  for (const Image* c : {&input.color[0], &input.color[1]})
    for (float v : c->data) {
      range.lowest = std::min(range.lowest, v);
      range.highest = std::max(range.highest, v);
    }

  const bool whole = options.tile == 0 || (w <= options.tile && h <= options.tile);
  const int tile = whole ? std::max(w, h) : options.tile;
  const auto rows = denoising::tile_spans(h, tile, 1);
  const auto columns = denoising::tile_spans(w, tile, 1);
  const int margin = whole ? 0 : denoise_tile_margin(options);
  const double tiles = double(rows.size() * columns.size());
  std::mutex progress_mutex;
  bool keep_going = true;
  int tile_index = 0;
  auto report = [&](double fraction) {
    if (!progress) return true;
    const std::lock_guard lock(progress_mutex);
    if (keep_going) keep_going = progress((double(tile_index) + fraction) / tiles, {});
    return keep_going;
  };

  Image out(w, h, 3), tiled_error;
  if (error && !whole) tiled_error = Image(w, h, 1);
  std::vector<double> share;
  int outliers = 0;
  bool finished = true;
  for (std::size_t t = 0; finished && t < rows.size() * columns.size(); ++t) {
    const auto [y0, y1] = rows[t / columns.size()];
    const auto [x0, x1] = columns[t % columns.size()];
    // The rectangle the tile runs on: its own with the margin, within the image.
    const int ex0 = std::max(0, x0 - margin), ey0 = std::max(0, y0 - margin);
    const int ex1 = std::min(w, x1 + margin), ey1 = std::min(h, y1 + margin);
    std::vector<double> tile_share;
    int tile_outliers = 0;
    if (whole) {
      finished =
          denoise_whole(input, options, range, report, out, tile_share, tile_outliers, error);
    } else {
      Image tile_out, tile_error;
      finished = denoise_whole(crop(input, ex0, ey0, ex1, ey1), options, range, report, tile_out,
                               tile_share, tile_outliers, error ? &tile_error : nullptr);
      if (finished)
        for (int y = y0; y < y1; ++y) {
          std::copy_n(tile_out.pixel(x0 - ex0, y - ey0), std::size_t(x1 - x0) * 3,
                      out.pixel(x0, y));
          if (error)
            std::copy_n(tile_error.pixel(x0 - ex0, y - ey0), std::size_t(x1 - x0),
                        tiled_error.pixel(x0, y));
        }
    }
    // Each tile's share weighs by the pixels it chose among (its margins included).
    const double pixels = double(ex1 - ex0) * double(ey1 - ey0);
    share.resize(tile_share.size(), 0.0);
    for (std::size_t k = 0; k < tile_share.size(); ++k) share[k] += pixels * tile_share[k];
    outliers += tile_outliers;
    ++tile_index;
  }
  if (stats) {
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->outliers = outliers;
    stats->interrupted = !finished;
  }
  // Stopped (progress.h's rule): what it has is the input's mean, the undenoised image.
  if (!finished) return mean_of_halves(input.color);
  double total = 0.0;
  for (double s : share) total += s;
  if (total > 0.0)
    for (double& s : share) s /= total;
  if (stats) stats->candidate_share = share;
  if (error && !whole) *error = std::move(tiled_error);
  if (progress) progress(1.0, {});
  return out;
}

}  // namespace pbrkit
