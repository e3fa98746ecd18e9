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

namespace pbrkit::test {
namespace {

constexpr int kWidth = 256, kHeight = 16;
constexpr float kHalfHeight = 0.125f;  // 64 pixels per unit: x in [-2, 2]
constexpr float kTilt = 1.0471976f;    // 60 degrees, about +Y
constexpr float kThickness = 1.0f;
constexpr float kIor = 1.5f;
constexpr float kDispersion = 20.0f;  // Abbe number 1: the channels' iors 1.25, 1.5, 1.75

// KHR_materials_dispersion README: n(lambda) = n_d + (n_d - 1) / V_d (523655 / lambda^2 -
// 1.5168), V_d = 20 / dispersion, at the channels' wavelengths (MODEL.md, "Dispersion").
double channel_ior(int c) {
  const double lambda[3] = {717.64, 587.57, 509.56};
  const double abbe = 20.0 / kDispersion;
  return kIor + (kIor - 1.0) / abbe * (523655.0 / (lambda[c] * lambda[c]) - 1.5168);
}

// Where the edge appears (world x) in channel c: the slab's normal n = (sin a, 0, cos a),
// the camera ray d = (0, 0, -1). Snell (vector form, eta = 1 / n_c): T = eta d + (eta cos_i
// - cos_t) n, cos_t = sqrt(1 - eta^2 (1 - cos_i^2)).
double predicted_edge(int c) {
  const double eta = 1.0 / channel_ior(c);
  const double cos_i = std::cos(double(kTilt)), sin_i = std::sin(double(kTilt));
  const double cos_t = std::sqrt(1.0 - eta * eta * sin_i * sin_i);
  const double Tx = (eta * cos_i - cos_t) * sin_i;
  return -(double(kThickness) / cos_t) * Tx;
}

// The scene: the emitter (x < 0, z = -20) and the slab, 10 wide and `kThickness` thick,
// centred on the origin and turned by kTilt about +Y, so it covers the whole view.
Scene slab_scene(float dispersion) {
  Scene scene;
  scene.source = "test:dispersive slab";
  Material emitter;
  emitter.base_color_factor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  emitter.emissive_factor = glm::vec3(1.0f);
  scene.materials.push_back(emitter);
  add_mesh_instance(scene, make_quad({-40, -5, -20}, {40, 0, 0}, {0, 10, 0}), 0);

  Material glass = make_material(glm::vec3(1.0f), 0.0f, 0.0f);
  glass.ior = kIor;
  glass.transmission = TransmissionExtension{};
  glass.transmission->factor = 1.0f;
  glass.volume = VolumeExtension{};
  glass.volume->thickness_factor = kThickness;
  glass.dispersion = DispersionExtension{dispersion};
  scene.materials.push_back(glass);
  // make_prism's outline is (x, z): the slab's section, the rectangle spanned by the
  // tangent u = (cos a, -sin a) (half width 5) and the normal n = (sin a, cos a).
  const glm::vec2 u(std::cos(kTilt), -std::sin(kTilt)), n(std::sin(kTilt), std::cos(kTilt));
  const float w = 5.0f, h = 0.5f * kThickness;
  const std::vector<glm::vec2> outline = {-w * u - h * n, w * u - h * n, w * u + h * n,
                                          -w * u + h * n};
  add_mesh_instance(scene, make_prism(outline, 2.0f), 1,
                    glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -1.0f, 0.0f)));
  return scene;
}

// Per channel, the world x where the row-averaged profile falls through half way between
// its left (emitter, pixels 48..63, x in [-1.25, -1)) and right (dark, the last 16 pixels)
// levels, searched from pixel 64 on and interpolated between pixel centres.
glm::dvec3 measured_edges(const Image& image) {
  glm::dvec3 edge(0.0);
  for (int c = 0; c < 3; ++c) {
    std::vector<double> profile(std::size_t(image.width), 0.0);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) profile[std::size_t(x)] += image.rgb(x, y)[c];
    double left = 0.0, right = 0.0;
    for (int x = 0; x < 16; ++x) {
      left += profile[std::size_t(48 + x)] / 16.0;
      right += profile[std::size_t(image.width - 1 - x)] / 16.0;
    }
    const double half = 0.5 * (left + right);
    double px = -1.0;
    for (int x = 64; x + 1 < image.width; ++x) {
      const double a = profile[std::size_t(x)], b = profile[std::size_t(x + 1)];
      if (a >= half && b < half) {
        px = double(x) + 0.5 + (a - half) / (a - b);
        break;
      }
    }
    const double half_width = double(kHalfHeight) * kWidth / kHeight;
    edge[c] = (px / kWidth * 2.0 - 1.0) * half_width;
  }
  return edge;
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
  const double pixel = 2.0 * double(kHalfHeight) / kHeight;
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
  const double pixel = 2.0 * double(kHalfHeight) / kHeight;
  const double green = predicted_edge(1);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(measured[c], green, 0.5 * pixel) << "channel " << c;
}

}  // namespace
}  // namespace pbrkit::test
