#pragma once
// Image comparison metrics (used by `pbrkit compare` and by image tests): RMSE, relative
// MSE, PSNR, mean relative error, and an error heatmap. All metrics are computed on the
// linear RGB values (a 1-channel image counts as grey, alpha is ignored) and averaged over
// the three channels and over the pixels where the mask is non-zero.
#include <cstddef>
#include <string>

#include "pbrkit/image/image.h"

namespace pbrkit {

struct CompareMetrics {
  double rmse = 0.0;                 ///< sqrt(mean (a - b)^2)
  double mse = 0.0;                  ///< mean (a - b)^2
  double relative_mse = 0.0;         ///< mean (a - b)^2 / (b^2 + 0.01)   (b is the reference)
  double psnr = 0.0;                 ///< 10 log10(1 / mse): peak 1 on linear values; +inf if equal
  double mean_relative_error = 0.0;  ///< mean |a - b| / (|b| + 0.01)
  std::size_t pixels = 0;            ///< pixels that entered the averages (mask non-zero)
};

/// The epsilon of the relative metrics: it keeps black reference pixels from dominating.
inline constexpr double kRelativeEpsilon = 0.01;

/// Compares `a` (test) with `b` (reference). `mask` (optional) selects the pixels where any
/// of its channels is non-zero. Throws pbrkit::Error (using `name_a` / `name_b` / `name_mask`)
/// when sizes differ or the mask selects no pixel.
CompareMetrics compare_images(const Image& a, const Image& b, const Image* mask = nullptr,
                              const std::string& name_a = "A", const std::string& name_b = "B",
                              const std::string& name_mask = "mask");

/// Per-pixel relative error |a - b| / (|b| + 0.01), averaged over the RGB channels.
/// A 1-channel image of the same size; masked-out pixels are 0.
Image relative_error_image(const Image& a, const Image& b, const Image* mask = nullptr);

/// Maps a 1-channel error image to a display-referred RGB heatmap: error 0 -> dark purple,
/// error >= `scale` -> yellow, along the viridis colour ramp (van der Walt & Smith 2015).
/// Pixels outside `mask` (when given) are mid grey. Values are sRGB-encoded, ready for
/// write_png.
Image error_heatmap(const Image& error, float scale, const Image* mask = nullptr);

/// The viridis ramp at t in [0,1] (sRGB-encoded colour; interpolated between 9 samples of
/// matplotlib's table).
glm::vec3 viridis(float t);

}  // namespace pbrkit
