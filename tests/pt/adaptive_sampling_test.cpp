// Adaptive sampling (pt/adaptive_sampling.h): the half-buffer error estimate's properties
// and the stopping rule's neighbourhood test on hand-made films.
#include <gtest/gtest.h>

#include <cmath>

#include "pbrkit/pt/adaptive_sampling.h"

namespace pbrkit::test {
namespace {

TEST(AdaptiveSampling, EvenIndicesFormTheHalfBuffer) {
  EXPECT_TRUE(in_half_buffer(0));
  EXPECT_FALSE(in_half_buffer(1));
  EXPECT_TRUE(in_half_buffer(1000));
  EXPECT_FALSE(in_half_buffer(0xffffffffu));
}

TEST(AdaptiveSampling, HalfBufferErrorProperties) {
  // Unknown below two samples.
  EXPECT_TRUE(std::isinf(half_buffer_error(glm::vec3(1.0f), glm::vec3(1.0f), 1.0f)));
  EXPECT_TRUE(std::isinf(half_buffer_error(glm::vec3(0.0f), glm::vec3(0.0f), 0.0f)));
  // Samples all equal to c: zero, for even and odd counts (an odd count from index 0 has
  // one more even sample than odd).
  const glm::vec3 c(0.3f, 0.5f, 2.0f);
  EXPECT_EQ(half_buffer_error(4.0f * c, 2.0f * c, 4.0f), 0.0f);
  EXPECT_EQ(half_buffer_error(5.0f * c, 3.0f * c, 5.0f), 0.0f);
  // Samples 1, 0, 1, 0, ... (the even ones 1): the halves disagree.
  const float alternating = half_buffer_error(glm::vec3(8.0f), glm::vec3(8.0f), 16.0f);
  EXPECT_GT(alternating, 0.1f);
  // Relative to sqrt(I) (Cycles): radiance scaled by k scales the error by sqrt(k).
  const float scaled = half_buffer_error(glm::vec3(800.0f), glm::vec3(800.0f), 16.0f);
  EXPECT_NEAR(scaled, 10.0f * alternating, 1e-3f * scaled);
}

// A w x h film whose pixels all have `n` samples of constant radiance (error 0).
Film converged_film(int w, int h, float n) {
  Film film(w, h);
  for (std::size_t i = 0; i < film.pixel_count(); ++i) {
    film.count[i] = n;
    film.sum[i] = glm::vec3(n);
    film.sum_even[i] = glm::vec3(std::ceil(n * 0.5f));
  }
  return film;
}

TEST(AdaptiveSampling, PixelsStopWhenTheirNeighboursAgree) {
  Film film = converged_film(7, 5, 16.0f);
  // One noisy pixel at (3, 2): it and its 8 neighbours keep going.
  const std::size_t noisy = 2 * 7 + 3;
  film.sum_even[noisy] = glm::vec3(16.0f);
  stop_converged_pixels(film, 16, 0.02f, 16);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) {
      const bool near_noisy = std::abs(x - 3) <= 1 && std::abs(y - 2) <= 1;
      EXPECT_EQ(film.done[std::size_t(y) * 7 + x], near_noisy ? 0.0f : 1.0f)
          << "x " << x << " y " << y;
    }
}

TEST(AdaptiveSampling, NothingStopsWhenOffEarlyOrShort) {
  Film off = converged_film(4, 4, 16.0f);
  stop_converged_pixels(off, 16, 0.0f, 16);  // threshold 0: adaptive sampling off
  Film early = converged_film(4, 4, 8.0f);
  stop_converged_pixels(early, 8, 0.02f, 16);  // below min_spp
  Film behind = converged_film(4, 4, 8.0f);
  behind.count[5] = 7.0f;  // one pixel has not reached the pass's target yet
  stop_converged_pixels(behind, 8, 0.02f, 4);
  for (std::size_t i = 0; i < 16; ++i) {
    EXPECT_EQ(off.done[i], 0.0f);
    EXPECT_EQ(early.done[i], 0.0f);
  }
  // The pixel behind and its neighbours keep going; the far corner stops.
  EXPECT_EQ(behind.done[5], 0.0f);
  EXPECT_EQ(behind.done[0], 0.0f);
  EXPECT_EQ(behind.done[15], 1.0f);
}

}  // namespace
}  // namespace pbrkit::test
