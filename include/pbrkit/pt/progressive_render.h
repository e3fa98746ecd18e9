#pragma once
// A path-traced image refined on a worker thread while the caller keeps drawing: the
// viewer's path mode. Each job is one render_path call (so its final image is exactly a
// `pbrkit render` of the same settings) whose checkpoints are published as snapshots;
// starting a job stops the previous one first. A job first renders a quarter-resolution
// one-sample preview, so that an image appears at once after a change, then the full one
// from its first sample up.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "pbrkit/image/environment.h"
#include "pbrkit/image/image.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit {

struct ProgressiveJob {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const Environment> env;  ///< null: no environment
  Camera camera;
  /// The render's settings. `stop` and `checkpoint` are the job's own; `min_spp` and
  /// `noise_threshold` stay as given (a render to exactly `spp` samples per pixel needs
  /// noise_threshold 0). checkpoint_interval is how often snapshots are published.
  PathTracerSettings settings;
  bool preview = true;  ///< the quarter-resolution one-sample image first
};

struct ProgressiveSnapshot {
  Image color;                  ///< linear RGB at the job's size (a preview is upscaled)
  Image albedo, normal, depth;  ///< the film's first-hit features (empty for a preview)
  double spp = 0.0;             ///< mean samples per pixel (0 for the preview)
  double noise = 0.0;           ///< mean per-pixel relative error estimate (0: unknown)
  double seconds = 0.0;         ///< since the job started
  bool preview = false;
  bool complete = false;  ///< the render reached its target: this image is final
  /// The final film (complete snapshots only): its half buffers are what the denoiser
  /// reads (denoise/inputs.h), kept only once, when the image no longer changes.
  std::shared_ptr<const Film> film;
  std::uint64_t job = 0;     ///< which start() it belongs to (1, 2, ...)
  std::uint64_t serial = 0;  ///< increases with every published snapshot
};

class ProgressiveRender {
 public:
  ProgressiveRender() = default;
  ~ProgressiveRender();
  ProgressiveRender(const ProgressiveRender&) = delete;
  ProgressiveRender& operator=(const ProgressiveRender&) = delete;

  /// Stops the running job (waiting for it) and starts `job`; until it publishes, latest()
  /// has nothing. Returns its number.
  std::uint64_t start(ProgressiveJob job);
  /// Stops the running job and waits for it; its last snapshot stays readable.
  void stop();
  /// The newest snapshot if its serial is above `seen` (none yet: nullopt).
  std::optional<ProgressiveSnapshot> latest(std::uint64_t seen = 0) const;
  /// The error that ended the last job, if any (e.g. a scene the path tracer refuses).
  std::optional<std::string> error() const;

 private:
  void publish(ProgressiveSnapshot snapshot);
  std::thread worker_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::shared_ptr<const ProgressiveSnapshot> latest_;
  std::optional<std::string> error_;
  std::uint64_t jobs_ = 0, serial_ = 0;
};

}  // namespace pbrkit
