#pragma once
// The one display path for every image pbrkit shows or writes as PNG (renders, merges,
// bake previews, viewer screenshots): linear RGB -> exposure -> tone mapper -> exact sRGB.
// The viewer's shader (gl/shaders/display.glsl) is a line-by-line port, tested against it.
#include <filesystem>

#include "pbrkit/core/color.h"
#include "pbrkit/image/image.h"

namespace pbrkit {

/// How a linear image becomes a display image.
struct DisplaySettings {
  float exposure_ev = 0.0f;  ///< stops: the linear values are scaled by 2^exposure_ev
  ToneMapper tone_mapper = ToneMapper::kPbrNeutral;
};

/// The RGB channels of `image` (1- and 2-channel images as rgb() reads them), alpha dropped.
Image rgb_channels(const Image& image);

/// display_transform of every pixel: a 3-channel image of sRGB-encoded values in [0, 1],
/// ready for write_png.
Image display_image(const Image& linear, const DisplaySettings& settings);

/// write_png(path, display_image(linear, settings)): an 8-bit sRGB PNG, written atomically.
void write_display_png(const std::filesystem::path& path, const Image& linear,
                       const DisplaySettings& settings);

}  // namespace pbrkit
