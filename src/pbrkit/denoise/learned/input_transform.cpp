#include "pbrkit/denoise/learned/input_transform.h"

#include <vector>

#include "pbrkit/util/parallel.h"

namespace pbrkit::learned {

double autoexposure(const Image& color) {
  constexpr int kBlock = 16;
  const int bw = (color.width + kBlock - 1) / kBlock;
  const int bh = (color.height + kBlock - 1) / kBlock;
  // Each block's log mean luminance (or nothing), one row of blocks per task; then summed
  // in block order, so the result does not depend on the schedule.
  std::vector<double> logs(std::size_t(bw) * bh, 0.0);
  std::vector<char> counts(logs.size(), 0);
  pbrkit::parallel_for(0, bh, [&](int by) {
    for (int bx = 0; bx < bw; ++bx) {
      const int x0 = bx * kBlock, x1 = std::min(x0 + kBlock, color.width);
      const int y0 = by * kBlock, y1 = std::min(y0 + kBlock, color.height);
      double sum = 0.0;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const float* p = color.pixel(x, y);
          sum += 0.2126 * sanitize_color(p[0]) + 0.7152 * sanitize_color(p[1]) +
                 0.0722 * sanitize_color(p[2]);
        }
      const double mean = sum / double((x1 - x0) * (y1 - y0));
      if (mean > 1e-8) {
        logs[std::size_t(by) * bw + bx] = std::log(mean);
        counts[std::size_t(by) * bw + bx] = 1;
      }
    }
  });
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < logs.size(); ++i)
    if (counts[i]) sum += logs[i], ++n;
  return n ? 0.18 / std::exp(sum / n) : 1.0;
}

void network_input_pixel(const Image& color, const Image& albedo, const Image& normal, double s,
                         int x, int y, float* input9, float* rgb) {
  const float* c = color.pixel(x, y);
  const float* a = albedo.pixel(x, y);
  const float* n = normal.pixel(x, y);
  for (int i = 0; i < 3; ++i) {
    rgb[i] = sanitize_color(c[i]);
    input9[i] = float(std::log1p(double(rgb[i]) * s));
    input9[3 + i] = sanitize_albedo(a[i]);
    input9[6 + i] = sanitize_normal(n[i]);
  }
}

void classic_input_pixel(const Image& classic, double s, int x, int y, float* input3, float* rgb) {
  const float* c = classic.pixel(x, y);
  for (int i = 0; i < 3; ++i) {
    rgb[i] = sanitize_color(c[i]);
    input3[i] = float(std::log1p(double(rgb[i]) * s));
  }
}

}  // namespace pbrkit::learned
