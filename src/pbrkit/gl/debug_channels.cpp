#include "pbrkit/gl/debug_channels.h"

#include <array>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pbrkit/util/error.h"

namespace pbrkit::gl {

namespace {

// By DebugChannel's value.
constexpr std::array<std::string_view, 12> kNames = {
    "none",     "base-color", "metallic", "roughness", "normal", "occlusion",
    "emissive", "diffuse",    "specular", "clearcoat", "sheen",  "transmission"};

}  // namespace

DebugChannel parse_debug_channel(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (kNames[i] == name) return DebugChannel(i);
  fail("unknown debug channel '{}' (expected one of: {})", name, fmt::join(kNames, ", "));
}

std::string_view debug_channel_name(DebugChannel c) {
  return kNames[std::size_t(c)];
}

std::vector<std::string> debug_channel_names() {
  return {kNames.begin(), kNames.end()};
}

bool is_lobe_channel(DebugChannel c) {
  return c >= DebugChannel::kDiffuse;
}

}  // namespace pbrkit::gl
