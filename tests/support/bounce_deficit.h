#pragma once
// The light a bounce limit drops: a built-in scene rendered at two bounce counts with the
// same seed, so that their paths agree up to the shallower limit and the per-pixel
// difference holds only what the deeper render adds (its standard error over the pixels is
// the noise of the measured deficit). For tests/pt/default_bounces_test.cpp and the table
// of the README's "Bounces", bench/bounces_bench.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "pbrkit/core/color.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit::test {

// 64 bounces stand for converged: no built-in scene gains more than its noise from 64 to
// 128 (README, "Bounces").
inline constexpr int kConverged = 64;

// Per-pixel luminance of a built-in scene at `width` (the height from the camera's aspect),
// in the built-in environment, `spp` samples without adaptive sampling, seed 0.
struct Luminance {
  int width = 0, height = 0;
  std::vector<double> y;
};
inline Luminance render_luminance(const Scene& scene, int width, std::uint32_t spp, int bounces) {
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  const RenderView view = select_view(scene, std::nullopt, width, std::nullopt);
  PathTracerSettings s;
  s.width = view.size.width;
  s.height = view.size.height;
  s.spp = spp;
  s.noise_threshold = 0.0f;
  s.max_bounces = bounces;
  const Image image = render_path(scene, &env, view.camera, s).color;
  Luminance out{image.width, image.height, {}};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) out.y.push_back(luminance(image.rgb(x, y)));
  return out;
}

struct Deficit {
  double deficit = 0.0;      ///< 1 - mean(shallow) / mean(deep) over the image
  double std_error = 0.0;    ///< of the deficit, from the per-pixel differences
  double worst_block = 0.0;  ///< the largest deficit of any 16x16 block (mean > 0.01)
};

inline Deficit deficit(const Luminance& shallow, const Luminance& deep) {
  double sum_deep = 0.0, sum_d = 0.0, sum_d2 = 0.0;
  const double n = double(deep.y.size());
  for (std::size_t i = 0; i < deep.y.size(); ++i) {
    const double d = deep.y[i] - shallow.y[i];
    sum_deep += deep.y[i];
    sum_d += d;
    sum_d2 += d * d;
  }
  Deficit out;
  out.deficit = sum_d / sum_deep;
  const double mean_d = sum_d / n;
  const double var_d = std::max(0.0, (sum_d2 / n - mean_d * mean_d) * n / (n - 1.0));
  out.std_error = std::sqrt(var_d / n) / (sum_deep / n);
  constexpr int kBlock = 16;
  for (int by = 0; by + kBlock <= deep.height; by += kBlock)
    for (int bx = 0; bx + kBlock <= deep.width; bx += kBlock) {
      double a = 0.0, b = 0.0;
      for (int y = by; y < by + kBlock; ++y)
        for (int x = bx; x < bx + kBlock; ++x) {
          const std::size_t i = std::size_t(y) * std::size_t(deep.width) + std::size_t(x);
          a += shallow.y[i];
          b += deep.y[i];
        }
      if (b / (kBlock * kBlock) > 0.01) out.worst_block = std::max(out.worst_block, 1.0 - a / b);
    }
  return out;
}

}  // namespace pbrkit::test
