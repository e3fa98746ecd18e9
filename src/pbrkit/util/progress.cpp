#include "pbrkit/util/progress.h"

#include "pbrkit/util/eta_estimator.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace pbrkit {

ProgressBar::ProgressBar(std::string label, std::FILE* stream)
    : label_(std::move(label)),
      stream_(stream),
      tty_(::isatty(::fileno(stream)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_ - std::chrono::hours(1)),
      eta_(std::make_unique<EtaEstimator>()) {}

ProgressBar::~ProgressBar() = default;

static std::string format_seconds(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  char buf[32];
  if (s < 60) {
    std::snprintf(buf, sizeof buf, "%.1fs", s);
  } else if (s < 3600) {
    std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) % 3600) / 60);
  }
  return buf;
}

void EtaEstimator::add(double t, double fraction) {
  const double window = std::max(min_window, 0.25 * t);
  // At most ~64 reports per window, however often the work reports: a report closer than
  // window / 64 to the one before the last replaces the last.
  const std::size_t n = history_.size();
  if (n >= 2 && t - history_[n - 2].first < window / 64.0)
    history_.back() = {t, fraction};
  else
    history_.emplace_back(t, fraction);
  // Keep one report at or before the window's start (the rate's base) and those after it.
  while (history_.size() > 2 && history_[1].first <= t - window) history_.pop_front();
}

double EtaEstimator::eta() const {
  if (history_.empty()) return -1.0;
  const auto [t, f] = history_.back();
  if (f >= 1.0) return 0.0;
  // The first second's rate says little (start-up, first tiles): "?" rather than a guess.
  if (t < 1.0) return -1.0;
  const auto [t0, f0] = history_.front();
  if (t > t0 && f > f0) return (1.0 - f) * (t - t0) / (f - f0);
  // No progress within the window: the average since the start, if any.
  return f > 0.0 && t > 0.0 ? t * (1.0 - f) / f : -1.0;
}

void ProgressBar::update(double fraction, const std::string& detail) {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  fraction = std::clamp(fraction, 0.0, 1.0);
  const auto now = std::chrono::steady_clock::now();
  const double since_last = std::chrono::duration<double>(now - last_).count();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  eta_->add(elapsed, fraction);
  if (since_last < (tty_ ? 0.1 : plain_interval) && fraction < 1.0) return;
  last_ = now;
  const double eta = eta_->eta();
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = int(std::lround(fraction * kWidth));
    std::string bar(filled, '#');
    bar.resize(kWidth, '.');
    std::fprintf(stream_, "\r%s [%s] %5.1f%% ETA %s %s\033[K", label_.c_str(), bar.c_str(),
                 fraction * 100.0, format_seconds(eta).c_str(), detail.c_str());
  } else {
    std::fprintf(stream_, "%s: %5.1f%% elapsed %s ETA %s %s\n", label_.c_str(), fraction * 100.0,
                 format_seconds(elapsed).c_str(), format_seconds(eta).c_str(), detail.c_str());
  }
  std::fflush(stream_);
}

void ProgressBar::finish(const std::string& summary) {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  finished_ = true;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stream_, "%s%s: done in %s%s%s\n", tty_ ? "\r\033[K" : "", label_.c_str(),
               format_seconds(elapsed).c_str(), summary.empty() ? "" : ", ", summary.c_str());
  std::fflush(stream_);
}

ProgressCallback ProgressBar::callback() {
  return [this](double f, const std::string& d) {
    update(f, d);
    return true;
  };
}

}  // namespace pbrkit
