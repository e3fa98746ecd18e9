#pragma once
// Adaptive sampling as in Cycles (intern/cycles/kernel/film/adaptive_sampling.h): every
// sample of a pixel goes to its full sum and every even-indexed one also to a second,
// interleaved half buffer (Film::sum_even); the difference between the two means
// estimates the error of the pixel, and a pixel stops receiving samples once its error
// and its neighbours' are below the threshold.
#include <cstdint>

#include <glm/glm.hpp>

#include "pbrkit/pt/film.h"

namespace pbrkit {

/// Whether sample `index` of a pixel's sequence also goes to the half buffer. By index,
/// not by arrival, so that split, resumed and interrupted renders fill it alike.
inline bool in_half_buffer(std::uint32_t index) {
  return (index & 1u) == 0u;
}

/// The relative error of a pixel's mean from its two buffers (`count` samples summing to
/// `sum`, the even-indexed of them to `sum_even`): sum|I - E| / sqrt(sum I) with I the
/// full mean and E the half buffer's; infinite below 2 samples. Film::pixel_noise.
float half_buffer_error(glm::vec3 sum, glm::vec3 sum_even, float count);

/// The stopping rule, after a pass that brought every running pixel to `target` samples:
/// with `noise_threshold` > 0 and at least `min_spp` samples, a pixel whose error is below
/// the threshold stops (Film::done) when its 3x3 neighbours' errors are below it too.
void stop_converged_pixels(Film& film, std::uint32_t target, float noise_threshold,
                           std::uint32_t min_spp);

}  // namespace pbrkit
