#include "pbrkit/image/display.h"

#include "pbrkit/image/image_io.h"

namespace pbrkit {

Image rgb_channels(const Image& image) {
  Image out(image.width, image.height, 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) out.set_rgb(x, y, image.rgb(x, y));
  return out;
}

Image display_image(const Image& linear, const DisplaySettings& settings) {
  Image out(linear.width, linear.height, 3);
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x)
      out.set_rgb(x, y,
                  display_transform(linear.rgb(x, y), settings.exposure_ev, settings.tone_mapper));
  return out;
}

void write_display_png(const std::filesystem::path& path, const Image& linear,
                       const DisplaySettings& settings) {
  write_png(path, display_image(linear, settings));
}

}  // namespace pbrkit
