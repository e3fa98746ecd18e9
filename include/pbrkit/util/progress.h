#pragma once
// Progress reporting for long work (bake, render). The library calls a ProgressCallback;
// the CLI decides how to show it. ProgressBar is the CLI's terminal display: a redrawn
// bar with percent and ETA on a TTY, plain periodic lines otherwise.
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

namespace pbrkit {

/// fraction in [0,1]; `detail` is free text such as "1.9 M samples*px/s, noise 0.012".
/// Return false to ask the computation to stop early.
///
/// The one rule of every library function that takes a ProgressCallback: asked to stop, it
/// stops at its next report and returns normally with what it has (nothing is lost: a
/// caller can write it), never throwing for the stop, and its result says it was stopped
/// where a partial result could pass for a complete one:
/// - render_path: the samples taken (PathTracerStats::stopped, ::complete);
/// - denoise: the input's mean, undenoised (DenoiseStats::interrupted);
/// - bake_environment: the stages finished, of the specular and sheen chains the levels
///   finished (BakeResult::interrupted);
/// - load_scene (LoadOptions::progress): the nodes set up so far (Scene::interrupted).
/// ProgressiveRender (the viewer's) is stopped through its stop() and keeps its last
/// snapshot, the same rule. Bad input is still an Error, stopped or not.
using ProgressCallback = std::function<bool(double fraction, const std::string& detail)>;

class EtaEstimator;

class ProgressBar {
 public:
  /// `label` is printed before the bar. `stream` is normally stderr.
  explicit ProgressBar(std::string label, std::FILE* stream = stderr);
  ~ProgressBar();
  /// Thread-safe; redraws at most ~10 times a second on a TTY and every `plain_interval`
  /// seconds (and at 100%) otherwise.
  void update(double fraction, const std::string& detail = {});
  /// Ends the line and prints the total time.
  void finish(const std::string& summary = {});
  /// A ProgressCallback that forwards to update() and never asks to stop.
  ProgressCallback callback();

  double plain_interval = 10.0;

 private:
  std::string label_;
  std::FILE* stream_;
  bool tty_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_;
  std::unique_ptr<EtaEstimator> eta_;  ///< the time left, from the recent rate
  bool finished_ = false;
};

}  // namespace pbrkit
