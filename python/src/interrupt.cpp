#include "interrupt.h"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <optional>
#include <thread>

namespace py = pybind11;

namespace pbrkit::python {

ProgressCallback WorkControl::callback() {
  return [this](double fraction, const std::string& detail) {
    fraction_.store(fraction);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      detail_ = detail;
    }
    return !stop.load();
  };
}

std::string WorkControl::detail() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return detail_;
}

void run_interruptible(const std::function<void(WorkControl&)>& work, const py::object& progress) {
  WorkControl control;
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::thread worker([&] {
    try {
      work(control);
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex);
    done = true;
    finished.notify_all();
  });

  std::optional<py::error_already_set> raised;  // KeyboardInterrupt, or the callable's error
  double reported = -1.0;
  for (;;) {
    bool over = false;
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(mutex);
      over = finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; });
    }
    if (over) break;
    if (raised) continue;  // stopping: wait for the work to return
    if (PyErr_CheckSignals() != 0) {
      raised.emplace();
      control.stop = true;
      continue;
    }
    const double f = control.fraction();
    if (!progress.is_none() && f != reported) {
      reported = f;
      try {
        const py::object r = progress(f, control.detail());
        if (!r.is_none() && !r.cast<bool>()) control.stop = true;
      } catch (py::error_already_set& e) {
        raised.emplace(std::move(e));
        control.stop = true;
      }
    }
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (raised) throw std::move(*raised);
  if (failure) std::rethrow_exception(failure);
  if (!progress.is_none() && reported < 1.0 && !control.stop.load())
    progress(1.0, control.detail());
}

}  // namespace pbrkit::python
