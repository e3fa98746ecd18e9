// fast_atan2 against libm in double precision: every quadrant, the octant boundaries,
// the reduction threshold tan(pi/8), zeros, tiny and huge arguments.
#include <gtest/gtest.h>

#include <cmath>

#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/fast_atan.h"

namespace pbrkit::test {
namespace {

constexpr double kMaxError = 4e-7;  // radians

TEST(FastAtan2, MatchesLibmOnRandomDirections) {
  Pcg32 rng(5);
  double worst = 0.0;
  for (int i = 0; i < 2000000; ++i) {
    const float y = 2.0f * rng.next_float() - 1.0f, x = 2.0f * rng.next_float() - 1.0f;
    const double err = std::fabs(double(fast_atan2(y, x)) - std::atan2(double(y), double(x)));
    worst = std::max(worst, err);
  }
  EXPECT_LT(worst, kMaxError);
}

TEST(FastAtan2, MatchesLibmOnSpecialRatios) {
  double worst = 0.0;
  // Around 0, tan(pi/8), 1 and their mirror images, in every quadrant, over a range of
  // magnitudes (the result depends on the ratio only).
  for (double scale : {1e-30, 1e-6, 1.0, 1e6, 1e30})
    for (double t : {0.0, 1e-8, 0.25, 0.41421354, 0.41421356, 0.41421358, 0.7, 0.99999994, 1.0,
                     1.0000001, 2.41421, 1e8})
      for (int q = 0; q < 4; ++q) {
        const float x = float((q & 1 ? -1.0 : 1.0) * scale);
        const float y = float((q & 2 ? -1.0 : 1.0) * scale * t);
        const double err = std::fabs(double(fast_atan2(y, x)) - std::atan2(double(y), double(x)));
        worst = std::max(worst, err);
        // and with the arguments swapped
        const double err2 = std::fabs(double(fast_atan2(x, y)) - std::atan2(double(x), double(y)));
        worst = std::max(worst, err2);
      }
  EXPECT_LT(worst, kMaxError);
}

TEST(FastAtan2, AxesAndZero) {
  const float pi = 3.14159265358979323846f;
  EXPECT_FLOAT_EQ(fast_atan2(0.0f, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(fast_atan2(1.0f, 0.0f), 0.5f * pi);
  EXPECT_FLOAT_EQ(fast_atan2(-1.0f, 0.0f), -0.5f * pi);
  EXPECT_FLOAT_EQ(fast_atan2(0.0f, -1.0f), pi);
  EXPECT_FLOAT_EQ(fast_atan2(-0.0f, -1.0f), -pi);
  EXPECT_EQ(fast_atan2(0.0f, 0.0f), 0.0f);
}

}  // namespace
}  // namespace pbrkit::test
