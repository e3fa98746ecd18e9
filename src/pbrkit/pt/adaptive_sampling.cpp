// Adaptive sampling (adaptive_sampling.h): the half-buffer error estimate and the
// stopping rule.
#include "pbrkit/pt/adaptive_sampling.h"

#include <cmath>
#include <limits>
#include <vector>

namespace pbrkit {

float half_buffer_error(glm::vec3 sum, glm::vec3 sum_even, float count) {
  // Cycles compares the mean of all samples, I, with the mean of the even-indexed half,
  // E; their difference estimates the error of I. Normalised by sqrt(I) as Cycles does so
  // that the threshold is perceptually uniform-ish.
  const float n = count;
  if (n < 2.0f) return std::numeric_limits<float>::infinity();
  const float n_even = std::ceil(n * 0.5f);  // ranges starting on an even index
  const glm::vec3 I = sum / n;
  const glm::vec3 E = sum_even / n_even;
  const glm::vec3 d = glm::abs(I - E);
  const float err = (d.x + d.y + d.z) / (1e-4f + std::sqrt(I.x + I.y + I.z));
  return err;
}

void stop_converged_pixels(Film& film, std::uint32_t target, float noise_threshold,
                           std::uint32_t min_spp) {
  if (!(noise_threshold > 0.0f) || target < min_spp) return;
  // As in Cycles (adaptive_sampling_filter_x/y), a pixel only stops when its 3x3
  // neighbours agree too: a pixel whose few samples all missed a small bright light looks
  // "converged" at 0, and its noisier neighbours keep it going.
  const int w = film.width, h = film.height;
  std::vector<std::uint8_t> converged(film.pixel_count(), 0);
  for (std::size_t i = 0; i < film.pixel_count(); ++i)
    converged[i] = film.done[i] > 0.0f ||
                   (film.count[i] >= float(target) && film.pixel_noise(i) < noise_threshold);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      if (film.done[i] > 0.0f || !converged[i]) continue;
      bool all = true;
      for (int dy = -1; dy <= 1 && all; ++dy)
        for (int dx = -1; dx <= 1 && all; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx >= 0 && xx < w && yy >= 0 && yy < h)
            all = converged[std::size_t(yy) * w + xx] != 0;
        }
      if (all) film.done[i] = 1.0f;
    }
}

}  // namespace pbrkit
