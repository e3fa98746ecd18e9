// The pixel filters' names (path_tracer.h); their sampling is in pixel_filter.h.
#include <array>
#include <string>
#include <utility>

#include "pbrkit/pt/pixel_filter.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

// The one table of names: parsing, printing and the CLI's choices all read it.
constexpr std::array<std::pair<PixelFilter, std::string_view>, 2> kNames = {{
    {PixelFilter::kTent, "tent"},
    {PixelFilter::kBox, "box"},
}};

}  // namespace

PixelFilter parse_pixel_filter(std::string_view name) {
  for (const auto& [filter, filter_name] : kNames)
    if (name == filter_name) return filter;
  std::string expected;
  for (const auto& entry : kNames)
    expected += (expected.empty() ? "" : ", ") + std::string(entry.second);
  fail("unknown pixel filter '{}' (expected one of: {})", name, expected);
}

std::string_view pixel_filter_name(PixelFilter filter) {
  for (const auto& [f, name] : kNames)
    if (f == filter) return name;
  return kNames[0].second;
}

std::vector<std::string> pixel_filter_names() {
  std::vector<std::string> names;
  for (const auto& entry : kNames) names.emplace_back(entry.second);
  return names;
}

}  // namespace pbrkit
