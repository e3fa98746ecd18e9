#pragma once
// atan2 for the path tracer's environment lookups, which convert every escaped ray and
// every environment sample to lat-long coordinates: libm's atan2f and acosf were about 4%
// of a render. Accurate to a few float ulps (|error| < 4e-7 rad, tests/pt/fast_atan_test.cpp),
// far below a texel of any environment map (2 pi / 16384 = 4e-4 rad), and branch-free
// apart from selects.
#include <cmath>

#include "pbrkit/core/math.h"

namespace pbrkit {

/// atan2(y, x) in [-pi, pi]; 0 for (0, 0).
inline float fast_atan2(float y, float x) {
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float hi = std::max(ax, ay), lo = std::min(ax, ay);
  // atan(lo / hi) in [0, pi/4]. Cephes' atanf reduction: above tan(pi/8) use
  // atan(t) = pi/4 + atan((t - 1) / (t + 1)), written with one division; the kernel then
  // only sees |r| <= tan(pi/8), where Cephes' degree-9 odd polynomial is accurate to
  // about 1 ulp (Moshier 1989, "Methods and Programs for Mathematical Functions").
  const bool reduce = lo > 0.41421356237309503f * hi;
  const float num = reduce ? lo - hi : lo;
  const float den = reduce ? lo + hi : hi;
  const float r = den > 0.0f ? num / den : 0.0f;
  const float z = r * r;
  float a = (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
             3.33329491539e-1f) *
                z * r +
            r;
  if (reduce) a += 0.25f * kPi;
  if (ay > ax) a = 0.5f * kPi - a;
  if (x < 0.0f) a = kPi - a;
  return std::copysign(a, y);
}

}  // namespace pbrkit
