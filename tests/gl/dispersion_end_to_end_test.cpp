// Dispersion end to end in the OpenGL renderer (KHR_materials_dispersion): a straight edge
// of an emitter seen through a tilted, strongly dispersive glass slab lands at a different
// place in each colour channel, where Snell's law with that channel's ior at both faces puts
// it (thick_refraction.glsl: the slab's back faces are drawn, so the refracted ray is
// carried to the back face and refracted out again). An orthographic camera, far away so
// that the view vector is -Z everywhere, looks down -Z; behind the slab the emitter covers
// x < 0. The view ray refracts at the front face (unit normal n, cos_i = n.z; Snell with
// the channel's ior from the README's Abbe form, written out here), crosses the slab of
// thickness t over t / cos_t, and leaves through the parallel back face along -Z again:
// the edge appears at x_c = -t T_c.x / cos_t, the path tracer's exact answer
// (tests/pt/dispersion_end_to_end_test.cpp). The one-refraction model (the Sample Viewer's
// getVolumeTransmissionRay, without the back faces) puts it at -t T_c.x.
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

// Where the edge appears (world x) in channel c: the refracted ray crosses the slab over
// t / cos_t, so x_c = -t T_c.x / cos_t.
double predicted_edge(int c) {
  double cos_t = 0.0;
  const double tx = refracted_x(c, cos_t);
  return -double(kThickness) * tx / cos_t;
}

Image render_slab(float dispersion) {
  testing::context();
  Camera camera;
  camera.type = Camera::Type::kOrthographic;
  camera.xmag = camera.ymag = kHalfHeight;
  // The renderer's view vector points at the camera's position (pbr_fragment.glsl), so the
  // exit ray leaves tilted by x / distance; over the 20 units to the emitter that moves the
  // edge by 20 x 0.6 / 10^4 = 0.0012, 0.08 pixel, at this distance.
  camera.znear = 9900.0f;
  camera.zfar = 10100.0f;
  camera.camera_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 10000.0f));
  RenderSettings settings;
  settings.msaa = 1;
  settings.background.mode = Background::Mode::kColor;
  settings.background.color = glm::vec3(0.0f);
  // The dark side is a black quad rather than nothing: the exit ray is followed to the
  // frame's depth, and where it meets no geometry at all it reads the environment (here
  // black) instead of the frame, which would put the edge on the depth texels' grid.
  Scene scene = slab_scene(dispersion);
  Material black;
  black.base_color_factor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  scene.materials.push_back(black);
  add_mesh_instance(scene, make_quad({0, -5, -20}, {40, 0, 0}, {0, 10, 0}),
                    int(scene.materials.size()) - 1);
  return render_headless(scene, camera, kWidth, kHeight, nullptr, nullptr, settings);
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
