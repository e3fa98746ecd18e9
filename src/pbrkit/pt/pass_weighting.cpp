// The weighted combination of a guided render's passes (pass_weighting.h).
#include "pbrkit/pt/pass_weighting.h"

#include <cmath>

namespace pbrkit {

namespace {

// The film's convention for its half buffers (half_buffer_error): of n samples, ceil(n / 2)
// are even.
float even_count(float n) {
  return std::ceil(n * 0.5f);
}

// The even sample indices in [lo, hi).
float evens_in(std::uint32_t lo, std::uint32_t hi) {
  return float((hi + 1) / 2 - (lo + 1) / 2);
}

}  // namespace

PassWeighting::PassWeighting(const Film& film) {
  const std::size_t n = film.pixel_count();
  for (int h = 0; h < 2; ++h) {
    pass_[h].assign(n, glm::vec3(0.0f));
    weighted_[h].assign(n, glm::vec3(0.0f));
    weight_[h].assign(n, 0.0f);
  }
  start_count_ = film.count;
  sample_begin_ = film.sample_begin;
  // A resumed film's c samples in a pixel: one pass of c samples, each of weight c.
  for (std::size_t i = 0; i < n; ++i) {
    const float c = film.count[i];
    if (!(c > 0.0f)) continue;
    const float ne = even_count(c);
    weighted_[0][i] = c * film.sum_even[i];
    weighted_[1][i] = c * (film.sum[i] - film.sum_even[i]);
    weight_[0][i] = c * ne;
    weight_[1][i] = c * (c - ne);
  }
}

void PassWeighting::end_pass(Film& film, float w) {
  for (std::size_t i = 0; i < film.pixel_count(); ++i) {
    const float c = film.count[i], c0 = start_count_[i];
    if (!(c > c0)) continue;
    const float ne = evens_in(sample_begin_ + std::uint32_t(c0), sample_begin_ + std::uint32_t(c));
    const float n[2] = {ne, c - c0 - ne};
    for (int h = 0; h < 2; ++h) {
      weighted_[h][i] += w * pass_[h][i];
      weight_[h][i] += w * n[h];
      pass_[h][i] = glm::vec3(0.0f);
    }
    start_count_[i] = c;
    // The film: each half's weighted mean times the film's count of that half (a half with
    // no sample yet takes the other's mean).
    glm::vec3 mean[2];
    for (int h = 0; h < 2; ++h)
      mean[h] = weight_[h][i] > 0.0f ? weighted_[h][i] / weight_[h][i] : glm::vec3(0.0f);
    if (!(weight_[0][i] > 0.0f)) mean[0] = mean[1];
    if (!(weight_[1][i] > 0.0f)) mean[1] = mean[0];
    const float film_even = even_count(c);
    film.sum_even[i] = film_even * mean[0];
    film.sum[i] = film.sum_even[i] + (c - film_even) * mean[1];
  }
}

}  // namespace pbrkit
