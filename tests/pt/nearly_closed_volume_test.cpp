// A volume on a nearly closed mesh (KHR_materials_volume on a UV sphere whose seam and
// pole miss their copies by rounding, as three.js writes spheres): loaded from glTF, it is
// a closed volume, so a ray through its centre is absorbed as Beer-Lambert says over the
// diameter, not rendered as a thin wall.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pbrkit/scene/load.h"
#include "pt/pt_test_util.h"
#include "scene/threejs_sphere.h"
#include "support/test_paths.h"

namespace pbrkit::test {
namespace {

TEST(PathTracerVolume, NearlyClosedSphereAbsorbsBeerLambertThroughItsCentre) {
  const double r = 0.5, n = 1.5, D = 0.5;
  const glm::vec3 color(0.8f, 0.5f, 0.2f);
  Scene sphere;
  Material m = make_material(glm::vec3(1.0f), 0.0f, 0.0f);
  m.ior = float(n);
  m.transmission = TransmissionExtension{};
  m.transmission->factor = 1.0f;
  m.volume = VolumeExtension{};
  m.volume->thickness_factor = 1.0f;
  m.volume->attenuation_color = color;
  m.volume->attenuation_distance = float(D);
  sphere.materials.push_back(m);
  add_mesh_instance(sphere, threejs_sphere(r, 64, 32), 0);
  const auto path = scratch_dir() / "nearly_closed_sphere.glb";
  write_glb(sphere, path);
  Scene scene = load_scene(path.string());
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_TRUE(scene.meshes[0].closed);

  // Behind it, an emitting quad (radiance Le, both sides) that every transmitted ray meets.
  const glm::vec3 Le(1.0f, 2.0f, 3.0f);
  scene.materials.push_back(make_material(glm::vec3(0.0f), 0.0f, 1.0f, Le, true));
  add_mesh_instance(scene,
                    make_quad(glm::vec3(-50.0f, -50.0f, -2.0f), glm::vec3(100.0f, 0.0f, 0.0f),
                              glm::vec3(0.0f, 100.0f, 0.0f)),
                    1);
  // An orthographic view of the sphere's centre, 0.02 r across: the rays cross the surface
  // at a vertex of the tessellation (phi = pi/2 on the equator) within 1.5 degrees of
  // normal incidence.
  const float half = 0.01f;
  PathTracerSettings settings = small_settings(8, 64);
  settings.max_bounces = 64;
  const PathTracerResult res = render_path(scene, nullptr, ortho_camera(half), settings);

  // Normal incidence through a diameter: R = ((n - 1) / (n + 1))^2 at each face,
  // a = attenuationColor^(2 r / attenuationDistance) per crossing, and the light reflected
  // back and forth along the diameter: Le (1 - R)^2 a / (1 - R^2 a^2). A thin wall (the
  // sphere taken as open) would transmit Le (1 - R) / (1 + R), without a.
  // Allowance for the geometry: a ray at offset b <= sqrt(2) half refracts into a chord
  // 2 sqrt(r^2 - (b/n)^2), (b/n)^2 / (2 r^2) = 8e-5 shorter, and the facets around the
  // vertex stay within b^2 / (2 r) of the sphere: |ln a| * 3e-4 < 0.1% relative.
  const double R = std::pow((n - 1.0) / (n + 1.0), 2.0);
  for (int c = 0; c < 3; ++c) {
    const double a = std::pow(double(color[c]), 2.0 * r / D);
    const double expected = Le[c] * (1.0 - R) * (1.0 - R) * a / (1.0 - R * R * a * a);
    std::vector<double> residuals;
    for (int y = 0; y < res.color.height; ++y)
      for (int x = 0; x < res.color.width; ++x)
        residuals.push_back(double(res.color.rgb(x, y)[c]) - expected);
    const ResidualStats s = residual_stats(residuals);
    std::printf("channel %d: expected %.5f, mean residual %.6f +- %.6f (thin wall: %.5f)\n", c,
                expected, s.mean, s.std_error, Le[c] * (1.0 - R) / (1.0 + R));
    EXPECT_LT(std::fabs(s.mean), 4.0 * s.std_error + 1e-3 * expected)
        << "channel " << c << ": expected " << expected;
  }
}

}  // namespace
}  // namespace pbrkit::test
