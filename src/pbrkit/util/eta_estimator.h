#pragma once
// The time-left estimate of ProgressBar (util/progress.h), private: only the bar and its
// tests use it.
#include <cstddef>
#include <deque>
#include <utility>

namespace pbrkit {

/// Time left from the recent rate of progress, not the average since the start: work
/// often gets slower as it goes (an adaptive render's cheap pixels converge first and
/// stop, leaving the expensive ones), and the average then promises too early an end.
/// The rate is measured over the last `window` of progress reports: max(min_window, 25%
/// of the elapsed time).
class EtaEstimator {
 public:
  double min_window = 3.0;  ///< seconds
  /// Records progress `fraction` (in [0, 1]) at time `t` (seconds since the start).
  void add(double t, double fraction);
  /// Seconds left after the last add(); negative when unknown (no progress yet, or less
  /// than a second of it).
  double eta() const;
  /// Reports kept: at most about 64 per window, however often the work reports.
  std::size_t history_size() const { return history_.size(); }

 private:
  std::deque<std::pair<double, double>> history_;  ///< (t, fraction), oldest first
};

}  // namespace pbrkit
