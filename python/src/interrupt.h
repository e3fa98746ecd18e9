#pragma once
// Long library calls from Python: the work runs on its own thread while the calling
// thread waits with the GIL released (so other Python threads, and other renders, run),
// waking every 50 ms to let Python handle signals (Ctrl-C raises KeyboardInterrupt in
// the main thread: the work is asked to stop through its stop flag / progress callback and
// the exception is raised once it has returned) and to call the user's progress callable.
#include <pybind11/pybind11.h>

#include <atomic>
#include <functional>
#include <mutex>
#include <string>

#include "pbrkit/util/progress.h"

namespace pbrkit::python {

/// What the work sees: a stop flag and a ProgressCallback to report through.
class WorkControl {
 public:
  std::atomic<bool> stop{false};
  /// Records the fraction and detail for the waiting thread; returns false once stopping.
  ProgressCallback callback();
  double fraction() const { return fraction_.load(); }
  std::string detail() const;

 private:
  std::atomic<double> fraction_{0.0};
  mutable std::mutex mutex_;
  std::string detail_;
};

/// Runs `work` as described above. `progress` is None or a callable (fraction: float,
/// detail: str) -> bool | None; returning False stops the work early (it returns what it
/// has), raising stops it and re-raises. Exceptions from `work` propagate (pbrkit::Error
/// becomes pbrkit.Error).
void run_interruptible(const std::function<void(WorkControl&)>& work,
                       const pybind11::object& progress);

}  // namespace pbrkit::python
