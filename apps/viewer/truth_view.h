#pragma once
// What the viewer's truth modes show besides the raster frame: the path-traced image, the
// raster/path split and the per-pixel error between them, as CPU images (what the
// screenshots write) and GL textures drawn behind the panel. Private to the viewer.
#include <cstdint>
#include <string>
#include <string_view>

#include "pbrkit/image/display.h"
#include "pbrkit/image/image.h"
#include "viewer/viewer.h"

namespace pbrkit {

/// The per-pixel relative luminance error of `raster` against `truth`,
/// |Y_r - Y_t| / (Y_t + 0.01) (the epsilon of `pbrkit compare`, which keeps black pixels
/// of the truth from dominating), as a 1-channel image; its mean and 95th percentile.
struct ErrorView {
  Image error;
  double mean = 0.0, p95 = 0.0;
};
ErrorView luminance_error(const Image& raster, const Image& truth);

/// Columns [0, split_column) of `left`, the rest of `right` (same size; RGB).
Image split_image(const Image& left, const Image& right, int split_column);

/// The column where the divider at `split` (0..1 of the width) falls.
inline int split_column(float split, int width) {
  const int c = int(split * float(width) + 0.5f);
  return c < 0 ? 0 : (c > width ? width : c);
}

/// A GL texture holding an 8-bit sRGB display image (values in [0, 1], row 0 at the top),
/// resized as needed; the name for Dear ImGui's AddImage.
class DisplayTexture {
 public:
  DisplayTexture() = default;
  ~DisplayTexture();
  DisplayTexture(const DisplayTexture&) = delete;
  DisplayTexture& operator=(const DisplayTexture&) = delete;
  void upload(const Image& display);
  std::uint32_t id() const { return texture_; }
  bool empty() const { return texture_ == 0; }

 private:
  std::uint32_t texture_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace pbrkit
