#pragma once
// pbrkit::Error: the one exception type the library throws for bad input and failed I/O.
// Its message always names the file (or option) and the problem, so the CLI can print it
// as-is and exit non-zero.
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace pbrkit {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// Throws pbrkit::Error with a fmt-formatted message.
template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace pbrkit
