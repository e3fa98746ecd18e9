// The denoiser's entry point: checks the input, runs the stages of stages.h in order and
// reports progress.
#include "pbrkit/denoise/denoiser.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>

#include "pbrkit/util/error.h"
#include "stages.h"

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
}  // namespace

Image denoise(const DenoiseInput& input, const DenoiseOptions& options,
              const ProgressCallback& progress, DenoiseStats* stats, Image* error) {
  using namespace denoising;
  const auto start = std::chrono::steady_clock::now();
  validate_denoise_input(input);
  if (options.radius < 0 || options.patch_radius < 0 || options.variance_radius < 0 ||
      options.prefilter_radius < 0 || (options.candidates.empty() && options.first_order_k.empty()))
    fail("denoise: radii must be >= 0 and there must be at least one candidate");
  if (options.first_order_energy_radius < 0 || options.zero_order_energy_radius < 0)
    fail("denoise: first_order_energy_radius and zero_order_energy_radius must be >= 0");
  if (!(options.first_order_ridge >= 0.0f))
    fail("denoise: first_order_ridge must be >= 0 (it is {})", options.first_order_ridge);
  const int w = input.color[0].width, h = input.color[0].height;
  const int pad = std::max({options.radius + options.patch_radius, options.prefilter_radius + 1,
                            options.variance_radius, 1}) +
                  1;
  std::mutex progress_mutex;
  bool keep_going = true;
  auto report = [&](double fraction) {
    if (!progress) return true;
    const std::lock_guard lock(progress_mutex);
    if (keep_going) keep_going = progress(fraction, {});
    return keep_going;
  };

  // Features: albedo, normal and depth, the last normalised by its largest value so that
  // the feature floor tau means the same in every scene.
  float depth_max = 0.0f;
  for (const Image* d : {&input.depth[0], &input.depth[1]})
    for (float v : d->data) depth_max = std::max(depth_max, std::abs(v));
  Image depth_scaled[2] = {input.depth[0], input.depth[1]};
  if (depth_max > 0.0f)
    for (Image& d : depth_scaled)
      for (float& v : d.data) v /= depth_max;
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
  const int outliers = spread_outliers(color, feature_list, options,
                                       options.keep_direct_environment ? &environment : nullptr);
  const Channels variance =
      options.relative_variance
          ? half_variance_relative(color[0], color[1], options.variance_radius,
                                   options.variance_level_ratio)
          : half_variance(color[0], color[1], options.variance_radius);
  // Stopped (progress.h's rule): what it has is the input's mean, the undenoised image.
  auto interrupted = [&] {
    if (stats) {
      stats->seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      stats->outliers = outliers;
      stats->interrupted = true;
    }
    Image mean(w, h, 3);
    for (std::size_t i = 0; i < mean.data.size(); ++i)
      mean.data[i] = 0.5f * (input.color[0].data[i] + input.color[1].data[i]);
    return mean;
  };
  if (!report(0.1)) return interrupted();

  CrossFilterInput cf;
  cf.color[0] = &color[0];
  cf.color[1] = &color[1];
  cf.variance[0] = cf.variance[1] = &variance;  // equal halves: the same variance
  cf.features = feature_list;
  cf.normal = 1;
  cf.depth = 2;
  cf.lowest = cf.highest = input.color[0].data.front();
  for (const Image* c : {&input.color[0], &input.color[1]})
    for (float v : c->data) {
      cf.lowest = std::min(cf.lowest, v);
      cf.highest = std::max(cf.highest, v);
    }
  int strips = 1;
  std::atomic<int> done{0};
  Candidates candidates = cross_filter(
      cf, options,
      [&] { return report(0.1 + 0.85 * double(++done) / double(std::max(1, strips))); }, &strips);
  if (!keep_going) return interrupted();
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
  std::vector<double> share;
  Image out = select_candidates(candidates, options, &share, error);
  if (options.keep_direct_environment) keep_direct_environment(environment, color, out, error);
  report(1.0);
  if (stats) {
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->candidate_share = share;
    stats->outliers = outliers;
  }
  return out;
}

}  // namespace pbrkit
