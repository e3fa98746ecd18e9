// Dispersion end to end in the path tracer (KHR_materials_dispersion): a straight edge of an
// emitter seen through a tilted, strongly dispersive glass slab lands at a different place
// in each colour channel, where Snell's law with that channel's ior puts it. An orthographic
// camera looks down -Z; behind the slab the emitter covers x < 0. A camera ray at x enters
// the slab's front face (unit normal n, incidence cos_i = n.z), refracts to T (Snell, the
// channel's ior from the README's Abbe form, written out here), crosses the slab's
// thickness t along T (a length t / cos_t) and leaves parallel to the camera ray, so it
// sees the emitter at x + (t / cos_t) T.x: the edge appears at x_c = -(t / cos_t) T_c.x.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "pbrkit/image/environment.h"
#include "pbrkit/scene/primitives.h"
#include "pt/pt_test_util.h"
#include "support/dispersive_slab.h"

namespace pbrkit::test {
namespace {

using namespace dispersive_slab;

// Where the edge appears (world x) in channel c: the ray crosses the slab's thickness t
// along T (a length t / cos_t) and leaves parallel to the camera ray, so x_c = -(t / cos_t)
// T_c.x.
double predicted_edge(int c) {
  double cos_t = 0.0;
  const double tx = refracted_x(c, cos_t);
  return -(double(kThickness) / cos_t) * tx;
}

Image render_slab(float dispersion) {
  PathTracerSettings s = small_settings(kWidth, 64);
  s.height = kHeight;
  s.max_bounces = 16;
  const Environment env = Environment::constant(glm::vec3(0.0f));
  return render_path(slab_scene(dispersion), &env, ortho_camera(kHalfHeight, 10.0f), s).color;
}

TEST(PathTracerDispersion, SlabSplitsAnEdgeByChannelAsSnellsLawPredicts) {
  const glm::dvec3 measured = measured_edges(render_slab(kDispersion));
  const double pixel = kPixel;
  for (int c = 0; c < 3; ++c) {
    const double predicted = predicted_edge(c);
    std::printf("channel %d (ior %.4f): edge at x = %.4f, Snell %.4f (%+.2f px)\n", c,
                channel_ior(c), measured[c], predicted, (measured[c] - predicted) / pixel);
    // Half a pixel: the crossing's interpolation and the 64-spp noise at the ramp.
    EXPECT_NEAR(measured[c], predicted, 0.5 * pixel) << "channel " << c;
  }
  // The split itself: red and blue about 12 pixels apart, blue (higher ior) furthest.
  EXPECT_GT((measured.z - measured.x) / pixel, 10.0);
}

TEST(PathTracerDispersion, WithoutDispersionTheChannelsAgree) {
  const glm::dvec3 measured = measured_edges(render_slab(0.0f));
  const double pixel = kPixel;
  const double green = predicted_edge(1);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(measured[c], green, 0.5 * pixel) << "channel " << c;
}

}  // namespace
}  // namespace pbrkit::test
