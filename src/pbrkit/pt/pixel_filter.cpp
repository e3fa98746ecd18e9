// The pixel filters' names (path_tracer.h); their sampling is in pixel_filter.h.
#include "pbrkit/pt/pixel_filter.h"

#include "pbrkit/util/error.h"

namespace pbrkit {

PixelFilter parse_pixel_filter(std::string_view name) {
  if (name == "tent") return PixelFilter::kTent;
  if (name == "box") return PixelFilter::kBox;
  fail("unknown pixel filter '{}' (expected 'tent' or 'box')", name);
}

std::string_view pixel_filter_name(PixelFilter filter) {
  return filter == PixelFilter::kBox ? "box" : "tent";
}

}  // namespace pbrkit
