#include "pbrkit/util/log.h"

#include <cstdio>
#include <mutex>

namespace pbrkit {
namespace {

std::mutex& sink_mutex() {
  static std::mutex m;
  return m;
}

LogSink& sink() {
  static LogSink s = [](LogLevel level, const std::string& message) {
    std::fprintf(stderr, "%s: %s\n", level == LogLevel::kWarning ? "warning" : "note",
                 message.c_str());
  };
  return s;
}

}  // namespace

LogSink set_log_sink(LogSink new_sink) {
  std::lock_guard lock(sink_mutex());
  LogSink old = std::move(sink());
  sink() = std::move(new_sink);
  return old;
}

void log_message(LogLevel level, const std::string& message) {
  std::lock_guard lock(sink_mutex());
  if (sink()) sink()(level, message);
}

}  // namespace pbrkit
