#pragma once
// Warnings and notes go to stderr through one place, so tests can capture them and the
// CLI can silence them (--quiet).
#include <functional>
#include <string>

#include <fmt/format.h>

namespace pbrkit {

enum class LogLevel { kNote, kWarning };

/// Replaces the sink (default: "warning: ..." / "note: ..." lines on stderr).
/// Returns the previous sink so a test can restore it.
using LogSink = std::function<void(LogLevel, const std::string&)>;
LogSink set_log_sink(LogSink sink);

void log_message(LogLevel level, const std::string& message);

template <typename... Args>
void warn(fmt::format_string<Args...> format, Args&&... args) {
  log_message(LogLevel::kWarning, fmt::format(format, std::forward<Args>(args)...));
}
template <typename... Args>
void note(fmt::format_string<Args...> format, Args&&... args) {
  log_message(LogLevel::kNote, fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace pbrkit
