#include "numeric_options.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "pbrkit/util/error.h"

namespace pbrkit::cli {

CLI::Validator finite_number() {
  // (No description: the option's help keeps its type name as it was.)
  return CLI::Validator(
      [](std::string& value) -> std::string {
        const char* begin = value.c_str();
        char* end = nullptr;
        const double v = std::strtod(begin, &end);
        // Text that is not a number is left to the option's conversion, which says so.
        if (end == begin || *end != '\0') return std::string();
        // Options are floats (a few doubles): a value beyond the largest float would become
        // infinite in a float option (compared in double: the cast itself would overflow).
        if (std::fabs(v) <= double(std::numeric_limits<float>::max())) return std::string();
        return "'" + value + "' is not a finite number (or is beyond a float's range, 3.4e38)";
      },
      "");
}

void require_finite_numbers(CLI::App& app) {
  for (CLI::Option* opt : app.get_options())
    if (opt->get_type_name().rfind("FLOAT", 0) == 0) opt->check(finite_number());
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    require_finite_numbers(*sub);
}

float parse_finite_float(std::string_view text, std::string_view flag, std::string_view whole) {
  float v = 0.0f;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size())
    fail("{}: '{}' is not a number (in '{}')", flag, text, whole);
  if (!std::isfinite(v)) fail("{}: '{}' is not a finite number (in '{}')", flag, text, whole);
  return v;
}

}  // namespace pbrkit::cli
