#include "pbrkit/image/compare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "pbrkit/util/error.h"

namespace pbrkit {
namespace {

bool selected(const Image* mask, int x, int y) {
  if (!mask) return true;
  const float* p = mask->pixel(x, y);
  for (int c = 0; c < mask->channels; ++c)
    if (p[c] != 0.0f) return true;
  return false;
}

void check_sizes(const Image& a, const Image& b, const Image* mask, const std::string& name_a,
                 const std::string& name_b, const std::string& name_mask) {
  if (a.empty()) fail("{}: image is empty", name_a);
  if (b.empty()) fail("{}: image is empty", name_b);
  if (a.width != b.width || a.height != b.height)
    fail("{} is {} x {} but {} is {} x {}: images must have the same size", name_a, a.width,
         a.height, name_b, b.width, b.height);
  if (mask && (mask->width != a.width || mask->height != a.height))
    fail("{} is {} x {} but the images are {} x {}: the mask must have the same size", name_mask,
         mask->width, mask->height, a.width, a.height);
}

}  // namespace

CompareMetrics compare_images(const Image& a, const Image& b, const Image* mask,
                              const std::string& name_a, const std::string& name_b,
                              const std::string& name_mask) {
  check_sizes(a, b, mask, name_a, name_b, name_mask);
  // Sums in double: a 4K image has 25 M samples and float sums would lose digits.
  double se = 0.0, rel_se = 0.0, rel_e = 0.0;
  std::size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!selected(mask, x, y)) continue;
      const glm::vec3 pa = a.rgb(x, y), pb = b.rgb(x, y);
      for (int c = 0; c < 3; ++c) {
        const double d = double(pa[c]) - double(pb[c]);
        const double ref = pb[c];
        se += d * d;
        rel_se += d * d / (ref * ref + kRelativeEpsilon);
        rel_e += std::abs(d) / (std::abs(ref) + kRelativeEpsilon);
      }
      ++n;
    }
  if (n == 0) fail("{}: the mask selects no pixel", name_mask);
  CompareMetrics m;
  const double samples = 3.0 * double(n);
  m.pixels = n;
  m.mse = se / samples;
  m.rmse = std::sqrt(m.mse);
  m.relative_mse = rel_se / samples;
  m.mean_relative_error = rel_e / samples;
  m.psnr = m.mse > 0.0 ? 10.0 * std::log10(1.0 / m.mse) : std::numeric_limits<double>::infinity();
  return m;
}

Image relative_error_image(const Image& a, const Image& b, const Image* mask) {
  check_sizes(a, b, mask, "A", "B", "mask");
  Image out(a.width, a.height, 1);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!selected(mask, x, y)) continue;
      const glm::vec3 pa = a.rgb(x, y), pb = b.rgb(x, y);
      double e = 0.0;
      for (int c = 0; c < 3; ++c)
        e += std::abs(double(pa[c]) - pb[c]) / (std::abs(double(pb[c])) + kRelativeEpsilon);
      out.pixel(x, y)[0] = static_cast<float>(e / 3.0);
    }
  return out;
}

glm::vec3 viridis(float t) {
  // matplotlib's viridis at t = 0, 1/8, ..., 1, in 8-bit sRGB.
  static const std::array<glm::vec3, 9> kRamp = {{{68, 1, 84},
                                                  {71, 44, 122},
                                                  {59, 81, 139},
                                                  {44, 113, 142},
                                                  {33, 144, 141},
                                                  {39, 173, 129},
                                                  {92, 200, 99},
                                                  {170, 220, 50},
                                                  {253, 231, 37}}};
  if (!(t > 0.0f)) return kRamp.front() / 255.0f;
  if (t >= 1.0f) return kRamp.back() / 255.0f;
  const float s = t * float(kRamp.size() - 1);
  const int i = std::min(static_cast<int>(s), int(kRamp.size()) - 2);
  return glm::mix(kRamp[i], kRamp[i + 1], s - float(i)) / 255.0f;
}

Image error_heatmap(const Image& error, float scale, const Image* mask) {
  if (!(scale > 0.0f)) fail("heatmap scale must be positive (got {})", scale);
  if (mask && (mask->width != error.width || mask->height != error.height))
    fail("mask is {} x {} but the error image is {} x {}", mask->width, mask->height, error.width,
         error.height);
  Image out(error.width, error.height, 3);
  for (int y = 0; y < error.height; ++y)
    for (int x = 0; x < error.width; ++x)
      out.set_rgb(x, y,
                  selected(mask, x, y) ? viridis(error.pixel(x, y)[0] / scale) : glm::vec3(0.5f));
  return out;
}

}  // namespace pbrkit
