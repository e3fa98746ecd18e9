// Dispersion end to end in the OpenGL renderer (KHR_materials_dispersion): a straight edge
// of an emitter seen through a tilted, strongly dispersive glass slab lands at a different
// place in each colour channel, where the screen-space refraction model (transmission.glsl,
// the Sample Viewer's getVolumeTransmissionRay) with that channel's ior puts it. An
// orthographic camera, far away so that the view vector is -Z everywhere, looks down -Z;
// behind the slab the emitter covers x < 0. The model refracts the view ray once at the
// front face (unit normal n, cos_i = n.z; Snell with the channel's ior from the README's
// Abbe form, written out here) and reads the opaque frame where the refracted ray, carried
// over the volume's thickness t, ends: x + t T.x, so the edge appears at x_c = -t T_c.x.
// (The path tracer's exact answer has t / cos_t: tests/pt/dispersion_end_to_end_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/primitives.h"
#include "support/dispersive_slab.h"

namespace pbrkit::gl {
namespace {

using namespace pbrkit::test::dispersive_slab;

// Where the edge appears (world x) in channel c: the model carries the refracted ray over
// the volume's thickness t, so x_c = -t T_c.x.
double predicted_edge(int c) {
  double cos_t = 0.0;
  return -double(kThickness) * refracted_x(c, cos_t);
}

Image render_slab(float dispersion) {
  testing::context();
  Camera camera;
  camera.type = Camera::Type::kOrthographic;
  camera.xmag = camera.ymag = kHalfHeight;
  camera.znear = 900.0f;
  camera.zfar = 1100.0f;
  camera.camera_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 1000.0f));
  RenderSettings settings;
  settings.msaa = 1;
  settings.background.mode = Background::Mode::kColor;
  settings.background.color = glm::vec3(0.0f);
  return render_headless(slab_scene(dispersion), camera, kWidth, kHeight, nullptr, nullptr,
                         settings);
}

TEST(GlDispersion, SlabSplitsAnEdgeByChannelAsTheRefractionModelPredicts) {
  const glm::dvec3 measured = measured_edges(render_slab(kDispersion));
  const double pixel = kPixel;
  for (int c = 0; c < 3; ++c) {
    const double predicted = predicted_edge(c);
    std::printf("channel %d (ior %.4f): edge at x = %.4f, Snell %.4f (%+.2f px)\n", c,
                channel_ior(c), measured[c], predicted, (measured[c] - predicted) / pixel);
    // Half a pixel: the crossing's interpolation (the frame is read bilinearly).
    EXPECT_NEAR(measured[c], predicted, 0.5 * pixel) << "channel " << c;
  }
  // The split itself: red and blue about 14 pixels apart, blue (higher ior) furthest.
  EXPECT_GT((measured.z - measured.x) / pixel, 10.0);
}

TEST(GlDispersion, WithoutDispersionTheChannelsAgree) {
  const glm::dvec3 measured = measured_edges(render_slab(0.0f));
  const double pixel = kPixel;
  const double green = predicted_edge(1);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(measured[c], green, 0.5 * pixel) << "channel " << c;
}

}  // namespace
}  // namespace pbrkit::gl
