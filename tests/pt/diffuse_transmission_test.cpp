// KHR_materials_diffuse_transmission with KHR_materials_volume in the path tracer: light
// diffusely transmitted into a closed mesh is absorbed (Beer-Lambert) along its path inside,
// as for specular transmission (the volume README: the volume is entered through any
// extension that lets light through the surface).
//
// The closed form: a wide slab of thickness d, diffuseTransmission 1 (white), ior 1 (no
// specular layer: nothing reflects), in a uniform environment of radiance L, seen from the
// front. The back face transmits L into the slab as a Lambertian radiance L; the ray from the
// front face at cos theta = mu to the back face is d / mu long; the front face transmits
//   L_o = int (1 / pi) L exp(-sigma d / mu) mu dw = 2 L int_0^1 mu exp(-tau / mu) dmu
//       = 2 L E_3(tau),   tau = sigma d,
// the exponential integral of order 3 (the diffuse transmittance of a slab, Chandrasekhar's
// radiative transfer). Without absorption inside the slab every pixel would be L.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pbrkit/image/environment.h"
#include "pt/pt_test_util.h"

namespace pbrkit::test {
namespace {

// 2 E_3(tau) = 2 int_0^1 mu exp(-tau / mu) dmu by the midpoint rule (1e5 points: its error is
// below 1e-9, far under the render's noise).
double two_e3(double tau) {
  const int n = 100000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) / n;
    sum += mu * std::exp(-tau / mu);
  }
  return 2.0 * sum / n;
}

Material translucent(glm::vec3 attenuation_color, float attenuation_distance, float thickness) {
  Material m = make_material(glm::vec3(0.3f, 0.6f, 0.9f), 0.0f, 0.5f);
  m.ior = 1.0f;  // no interface: the diffuse lobe is all there is
  m.diffuse_transmission = DiffuseTransmissionExtension{};
  m.diffuse_transmission->factor = 1.0f;  // nothing of the base colour is reflected
  m.volume = VolumeExtension{};
  m.volume->thickness_factor = thickness;
  m.volume->attenuation_color = attenuation_color;
  m.volume->attenuation_distance = attenuation_distance;
  return m;
}

// A slab of `m`, 100 wide and `d` thick around z = 0, in a uniform environment of radiance
// L, rendered from the front; each channel's mean over the pixels against `expected` (4
// standard errors of the mean residual).
void expect_slab(const Material& m, float d, float L, glm::vec3 expected, std::uint32_t spp,
                 const char* what) {
  Scene scene;
  scene.source = "test:translucent slab";
  scene.materials.push_back(m);
  add_mesh_instance(
      scene, make_box(glm::vec3(-50.0f, -50.0f, -d / 2.0f), glm::vec3(50.0f, 50.0f, d / 2.0f)), 0);
  const Environment env = Environment::constant(glm::vec3(L));
  const PathTracerResult res =
      render_path(scene, &env, ortho_camera(1.0f), small_settings(16, spp));
  for (int c = 0; c < 3; ++c) {
    std::vector<double> r;
    for (int y = 0; y < res.color.height; ++y)
      for (int x = 0; x < res.color.width; ++x)
        r.push_back(double(res.color.rgb(x, y)[c]) - expected[c]);
    const ResidualStats s = residual_stats(r);
    std::printf("%s, channel %d: expected %.5f, mean residual %.5f +- %.5f\n", what, c,
                double(expected[c]), s.mean, s.std_error);
    EXPECT_LT(std::fabs(s.mean), 4.0 * s.std_error + 1e-4 * expected[c])
        << what << ", channel " << c;
  }
}

TEST(PathTracerDiffuseTransmission, SlabWithVolumeTransmitsTwoE3) {
  // The paths that reach a side face from the pixels seen run at cos theta < d / 49, through
  // an optical depth over 49 tau / d: nothing of them is left.
  const float d = 0.25f, D = 0.5f, L = 2.0f;
  const glm::vec3 color(0.8f, 0.5f, 0.2f);
  glm::vec3 expected;
  for (int c = 0; c < 3; ++c) {
    // sigma_a = -ln(attenuationColor) / attenuationDistance (volume README).
    const double tau = -std::log(double(color[c])) / D * d;
    expected[c] = float(L * two_e3(tau));
  }
  // (Without the volume's absorption every channel would be L = 2: expected is 1.63, 1.12,
  // 0.57.)
  expect_slab(translucent(color, D, d), d, L, expected, 64, "translucent slab");
}

TEST(PathTracerDiffuseTransmission, ThinTranslucentSheetIsNotAbsorbed) {
  // The same material with thickness 0 is thin-walled (volume README): nothing is absorbed,
  // and the white slab in the uniform environment shows L.
  const float L = 2.0f;
  expect_slab(translucent(glm::vec3(0.2f), 0.1f, 0.0f), 0.25f, L, glm::vec3(L), 32,
              "thin-walled translucent slab");
}

}  // namespace
}  // namespace pbrkit::test
