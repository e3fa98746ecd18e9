#pragma once
// The path view's images, private to the viewer: the path tracer's colour or one of its
// film's first-hit features, linear (what the EXR screenshot holds) and for display, and
// the colour denoised by the chosen denoiser (denoise/denoiser_choice.h) on a worker
// thread, once per finished render.
#include <cstdint>
#include <future>
#include <optional>
#include <string>

#include "pbrkit/denoise/denoiser_choice.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/image.h"
#include "pbrkit/pt/progressive_render.h"
#include "viewer/viewer.h"

namespace pbrkit {

/// The snapshot's linear image of `channel`: the colour, the albedo, the normal encoded as
/// n * 0.5 + 0.5 (as render's EXR layers hold it) or the depth (1 channel). A preview has
/// its colour only, which it returns for every channel.
Image path_channel_image(const ProgressiveSnapshot& snapshot, PathChannel channel);

/// `linear` (path_channel_image's) for the screen: the colour through `display`; the
/// albedo and normal as they are (no exposure or tone mapping), the depth over the
/// farthest hit.
Image path_channel_display(const Image& linear, PathChannel channel,
                           const DisplaySettings& display);

/// The denoised colour of the path tracer's finished render. A complete snapshot carries
/// its film (pt/progressive_render.h), whose half buffers the denoiser reads; the work
/// runs on a thread of its own so the window keeps drawing, and is done once per snapshot:
/// a new one is computed only when the accumulation has advanced to another final image.
/// The learned denoiser's weights are loaded once, by the first denoise (or given by
/// use()), and kept for every later image of the same choice.
class PathDenoiser {
 public:
  PathDenoiser() = default;
  ~PathDenoiser();  ///< waits for a denoise under way
  PathDenoiser(const PathDenoiser&) = delete;
  PathDenoiser& operator=(const PathDenoiser&) = delete;

  /// Starts denoising `snapshot` unless it is not complete, has no film, or is the one
  /// denoised or being denoised (one at a time: a newer one waits for the next call).
  void request(const ProgressiveSnapshot& snapshot, const DenoiserChoice& choice);
  /// Denoises with `loaded` (load_denoiser's) while its choice is the one requested.
  void use(LoadedDenoiser loaded) { loaded_ = std::move(loaded); }
  /// Takes a finished result; true when a new denoised image (or an error) arrived.
  bool poll();
  /// The denoised colour of the snapshot numbered `serial`, once done; null otherwise.
  const Image* result(std::uint64_t serial) const;
  bool busy() const { return running_.valid(); }
  /// Why the last denoise failed, if it did.
  const std::optional<std::string>& error() const { return error_; }

 private:
  struct Denoised {
    Image image;
    LoadedDenoiser denoiser;  ///< what denoised it, kept for the next image
  };
  std::future<Denoised> running_;
  std::optional<LoadedDenoiser> loaded_;
  std::uint64_t running_serial_ = 0, done_serial_ = 0;
  Image done_;
  std::optional<std::string> error_;
};

}  // namespace pbrkit
