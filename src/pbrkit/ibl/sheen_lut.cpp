// The sheen LUT (see sheen_lut.h).
#include "pbrkit/ibl/sheen_lut.h"

#include "pbrkit/core/sheen.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

Image compute_sheen_lut(int size) {
  if (size < 1 || size > 4096) fail("sheen LUT: size must be in 1..4096, got {}", size);
  const SheenTable& table = SheenTable::get();
  Image lut(size, size, 4, 0.0f);
  pbrkit::parallel_for(0, size, [&](int y) {
    const float r = (float(y) + 0.5f) / float(size);
    // E_avg = 2 int_0^1 E(mu) mu dmu; with mu = s^2: 4 int_0^1 E(s^2) s^3 ds (the table's
    // nodes are uniform in s), midpoint rule over 256 intervals.
    constexpr int kAvgNodes = 256;
    double avg = 0.0;
    for (int k = 0; k < kAvgNodes; ++k) {
      const double s = (k + 0.5) / kAvgNodes;
      avg += double(table.E(float(s * s), r)) * s * s * s;
    }
    const float e_avg = float(4.0 * avg / kAvgNodes);
    for (int x = 0; x < size; ++x) {
      float* p = lut.pixel(x, y);
      p[0] = table.E((float(x) + 0.5f) / float(size), r);
      p[1] = e_avg;
      p[2] = 0.0f;
      p[3] = 1.0f;
    }
  });
  return lut;
}

}  // namespace pbrkit
