#include "path_view.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <exception>

#include "pbrkit/denoise/denoiser_choice.h"
#include "pbrkit/denoise/inputs.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

// By PathChannel's value.
constexpr std::array<std::string_view, 4> kPathChannelNames = {"color", "albedo", "normal",
                                                               "depth"};

}  // namespace

PathChannel parse_path_channel(std::string_view name) {
  for (std::size_t i = 0; i < kPathChannelNames.size(); ++i)
    if (kPathChannelNames[i] == name) return PathChannel(i);
  fail("unknown path channel '{}' (color, albedo, normal, depth)", name);
}

std::string_view path_channel_name(PathChannel channel) {
  return kPathChannelNames[std::size_t(channel)];
}

std::vector<std::string> path_channel_names() {
  return {kPathChannelNames.begin(), kPathChannelNames.end()};
}

Image path_channel_image(const ProgressiveSnapshot& snapshot, PathChannel channel) {
  if (snapshot.preview || channel == PathChannel::kColor) return snapshot.color;
  if (channel == PathChannel::kAlbedo) return snapshot.albedo;
  if (channel == PathChannel::kDepth) return snapshot.depth;
  Image encoded = snapshot.normal;
  for (float& v : encoded.data) v = 0.5f * v + 0.5f;
  return encoded;
}

Image path_channel_display(const Image& linear, PathChannel channel,
                           const DisplaySettings& display) {
  const DisplaySettings raw{0.0f, ToneMapper::kNone};
  if (channel == PathChannel::kColor) return display_image(linear, display);
  if (channel != PathChannel::kDepth) return display_image(linear, raw);
  float far = 0.0f;
  for (float d : linear.data) far = std::max(far, d);
  Image grey(linear.width, linear.height, 3);
  for (int y = 0; y < grey.height; ++y)
    for (int x = 0; x < grey.width; ++x)
      grey.set_rgb(x, y, glm::vec3(far > 0.0f ? linear.pixel(x, y)[0] / far : 0.0f));
  return display_image(grey, raw);
}

PathDenoiser::~PathDenoiser() {
  if (running_.valid()) running_.wait();
}

void PathDenoiser::request(const ProgressiveSnapshot& snapshot, const DenoiserChoice& choice) {
  if (!snapshot.complete || !snapshot.film || running_.valid()) return;
  if (snapshot.serial == done_serial_) return;
  running_serial_ = snapshot.serial;
  std::optional<LoadedDenoiser> loaded;
  if (loaded_ && loaded_->choice == choice) loaded = loaded_;
  running_ = std::async(std::launch::async, [film = snapshot.film, choice, loaded] {
    Denoised out{Image(), loaded ? *loaded : load_denoiser(choice)};
    out.image = denoise_render(denoise_input(*film), out.denoiser).image;
    return out;
  });
}

bool PathDenoiser::poll() {
  if (!running_.valid() || running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return false;
  done_serial_ = running_serial_;
  try {
    Denoised denoised = running_.get();
    done_ = std::move(denoised.image);
    loaded_ = std::move(denoised.denoiser);
    error_.reset();
  } catch (const std::exception& e) {
    done_ = Image();
    error_ = e.what();
  }
  return true;
}

const Image* PathDenoiser::result(std::uint64_t serial) const {
  return serial == done_serial_ && !done_.empty() ? &done_ : nullptr;
}

}  // namespace pbrkit
