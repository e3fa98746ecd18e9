// A translucent volume (KHR_materials_diffuse_transmission with KHR_materials_volume) in both
// renderers: a wide slab of thickness d, diffuseTransmission 1, ior 1 (nothing reflects),
// lit from behind by a directional light of illuminance E at normal incidence, seen from
// the front.
//
// The path tracer's truth: the back face sends E / pi into the slab as a Lambertian
// radiance; a ray from the front face at cos theta = mu crosses d / mu of the medium, so
// the front face shows (E / pi) 2 E_3(tau), tau = sigma_a d (E_3 the exponential integral
// of order 3). The OpenGL renderer attenuates the diffuse BTDF's light by one straight
// segment of the thickness (the Sample Viewer's model, pbr_fragment.glsl): (E / pi)
// exp(-tau). Its over-estimate exp(-tau) / (2 E_3(tau)) - 1, about tau for a thin slab
// (+2.5%, +5.0%, +7.8% at the test's tau = 0.026, 0.056, 0.089), is the model's error; the
// test holds the two images' ratio to it, per channel, within 4 standard errors of the path
// tracer's mean (measured: equal to 1e-4). Without the volume's absorption in the path
// tracer the ratio would be exp(-tau) < 1.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_context.h"
#include "pbrkit/core/math.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::gl {
namespace {

// 2 E_3(tau) = 2 int_0^1 mu exp(-tau / mu) dmu, midpoint rule (error below 1e-9).
double two_e3(double tau) {
  const int n = 100000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) / n;
    sum += mu * std::exp(-tau / mu);
  }
  return 2.0 * sum / n;
}

TEST(GlTranslucentVolume, SlabAgreesWithThePathTracerWithinTheStraightSegmentModel) {
  testing::context();
  const float d = 0.25f, D = 1.0f, E = 3.0f;
  const glm::vec3 color(0.9f, 0.8f, 0.7f);
  Scene scene;
  scene.source = "test:translucent slab";
  Material m;
  m.base_color_factor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  m.metallic_factor = 0.0f;
  m.roughness_factor = 0.5f;
  m.ior = 1.0f;
  m.diffuse_transmission = DiffuseTransmissionExtension{};
  m.diffuse_transmission->factor = 1.0f;
  m.volume = VolumeExtension{};
  m.volume->thickness_factor = d;
  m.volume->attenuation_color = color;
  m.volume->attenuation_distance = D;
  scene.materials.push_back(m);
  // 20 wide: the front face's rays that leave through a side instead of the back face run
  // at cos theta < d / 10 (a 0.06% share of the cosine lobe).
  add_mesh_instance(
      scene, make_box(glm::vec3(-10.0f, -10.0f, -d / 2.0f), glm::vec3(10.0f, 10.0f, d / 2.0f)), 0);
  Light light;
  light.type = Light::Type::kDirectional;
  light.intensity = E;
  light.direction = glm::vec3(0.0f, 0.0f, 1.0f);  // travelling towards the camera
  scene.lights.push_back(light);
  Camera camera;
  camera.yfov = 0.4f;
  camera.camera_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 3.0f));

  constexpr int kSize = 16;
  RenderSettings settings;
  settings.msaa = 1;
  settings.ibl = false;
  settings.background.mode = Background::Mode::kColor;
  settings.background.color = glm::vec3(0.0f);
  const Image gl = render_headless(scene, camera, kSize, kSize, nullptr, nullptr, settings);

  PathTracerSettings pt;
  pt.width = pt.height = kSize;
  pt.spp = 64;
  pt.noise_threshold = 0.0f;
  pt.filter = PixelFilter::kBox;
  const PathTracerResult truth = render_path(scene, nullptr, camera, pt);
  EXPECT_EQ(truth.stats.non_finite_samples, 0u);

  for (int c = 0; c < 3; ++c) {
    // sigma_a = -ln(attenuationColor) / attenuationDistance (volume README).
    const double tau = -std::log(double(color[c])) / D * d;
    double sum_gl = 0.0, sum_pt = 0.0, sum_pt2 = 0.0;
    const int n = kSize * kSize;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        sum_gl += gl.rgb(x, y)[c];
        const double v = truth.color.rgb(x, y)[c];
        sum_pt += v;
        sum_pt2 += v * v;
      }
    const double mean_pt = sum_pt / n;
    const double se_pt = std::sqrt(std::max(0.0, sum_pt2 / n - mean_pt * mean_pt) / (n - 1));
    const double ratio = (sum_gl / n) / mean_pt;
    const double model = std::exp(-tau) / two_e3(tau);
    std::printf(
        "channel %d: tau %.4f, GL %.5f (exp(-tau) E/pi = %.5f), path tracer %.5f +- %.5f "
        "(2 E_3 E/pi = %.5f), GL / path tracer %.4f, model %.4f\n",
        c, tau, sum_gl / n, std::exp(-tau) * E / kPi, mean_pt, se_pt, two_e3(tau) * E / kPi, ratio,
        model);
    EXPECT_NEAR(ratio, model, 4.0 * se_pt / mean_pt * ratio + 1e-3) << "channel " << c;
  }
}

}  // namespace
}  // namespace pbrkit::gl
