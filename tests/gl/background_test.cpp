// The GL background is the environment seen through each pixel, in the project's one
// orientation convention: every pixel of a background-only frame equals Environment::eval
// (the path tracer's lookup) along the same primary ray (gl_image_test_util.h's
// pixel_ray), for a perspective and an orthographic camera, with and without rotation.
#include <gtest/gtest.h>

#include <cmath>

#include "gl_image_test_util.h"
#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"

#include <glm/gtc/matrix_transform.hpp>

namespace pbrkit::gl {
namespace {

// A smooth map with different colours in every direction (no two of +-X, +-Y, +-Z alike),
// slow enough that GL's and Environment::eval's bilinear filtering agree closely.
Environment asymmetric_environment(float rotation_deg) {
  Environment env;
  env.map = Image(64, 32, 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      const float u = (float(x) + 0.5f) / 64.0f, v = (float(y) + 0.5f) / 32.0f;
      const float phi = 2.0f * 3.14159265f * u;
      env.map.set_rgb(x, y,
                      {1.0f + 0.5f * std::cos(phi), 1.0f + 0.5f * std::sin(phi), 0.2f + 1.5f * v});
    }
  env.rotation_deg = rotation_deg;
  env.source = "asymmetric";
  return env;
}

void expect_background_matches_environment(const Camera& camera, float rotation_deg) {
  testing::context();
  const Environment env = asymmetric_environment(rotation_deg);
  constexpr int kWidth = 48, kHeight = 32;
  RenderSettings settings;
  settings.msaa = 1;
  settings.env_rotation_deg = rotation_deg;
  Renderer renderer;
  renderer.set_scene(Scene{});
  renderer.set_environment(&env);
  renderer.render(camera, kWidth, kHeight, settings);
  const Image image = renderer.read_back();
  double worst = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const Ray ray = testing::pixel_ray(camera, x, y, kWidth, kHeight);
      const glm::vec3 expected = env.eval(ray.direction);
      const glm::vec3 got = image.rgb(x, y);
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, double(std::fabs(got[k] - expected[k]) / expected[k]));
    }
  // A wrong axis, sign or rotation would be off by tens of percent.
  EXPECT_LT(worst, 5e-3) << "rotation " << rotation_deg;
}

Camera turned_camera(Camera::Type type) {
  Camera camera;
  camera.type = type;
  camera.yfov = 1.2f;
  camera.xmag = camera.ymag = 1.0f;
  // Looking along (1, 0.3, -1) from the origin: no axis-aligned view hides a swapped sign.
  camera.camera_to_world = glm::inverse(
      glm::lookAt(glm::vec3(0.0f), glm::vec3(1.0f, 0.3f, -1.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
  return camera;
}

TEST(GlBackground, PerspectivePixelsSeeTheEnvironmentAlongTheirRays) {
  for (float rotation : {0.0f, 90.0f, -37.0f})
    expect_background_matches_environment(turned_camera(Camera::Type::kPerspective), rotation);
}

TEST(GlBackground, OrthographicPixelsSeeTheEnvironmentAlongTheViewDirection) {
  expect_background_matches_environment(turned_camera(Camera::Type::kOrthographic), 30.0f);
}

}  // namespace
}  // namespace pbrkit::gl
