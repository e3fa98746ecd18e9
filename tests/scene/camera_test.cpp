// Camera conventions: generate_ray and projection_matrix must describe the same camera
// (both renderers rely on it), and auto_camera must frame the bounding sphere as
// documented in camera.h.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/camera.h"
#include "pbrkit/util/error.h"

namespace pbrkit {
namespace {

Camera perspective(std::optional<float> zfar, std::optional<float> aspect) {
  Camera c;
  c.yfov = 0.9f;
  c.znear = 0.1f;
  c.zfar = zfar;
  c.aspect_ratio = aspect;
  c.camera_to_world =
      glm::inverse(glm::lookAt(glm::vec3(1, 2, 5), glm::vec3(-0.5f, 0.3f, 0), glm::vec3(0, 1, 0)));
  return c;
}

// Points along each generated ray project back to the ndc the ray was generated for.
void expect_ray_matches_projection(const Camera& camera, float aspect) {
  const glm::mat4 pv = projection_matrix(camera, aspect) * view_matrix(camera);
  for (float x : {-0.9f, -0.3f, 0.0f, 0.55f, 1.0f}) {
    for (float y : {-1.0f, -0.2f, 0.4f, 0.8f}) {
      const Ray ray = generate_ray(camera, aspect, {x, y});
      EXPECT_NEAR(glm::length(ray.direction), 1.0f, 1e-5f);
      for (float t : {0.5f, 2.0f, 7.0f}) {
        const glm::vec4 clip = pv * glm::vec4(ray.origin + t * ray.direction, 1.0f);
        ASSERT_GT(clip.w, 0.0f);
        EXPECT_NEAR(clip.x / clip.w, x, 1e-4f) << "t=" << t;
        EXPECT_NEAR(clip.y / clip.w, y, 1e-4f) << "t=" << t;
        // In front of the near plane the depth lies in [-1, 1].
        EXPECT_GT(clip.z / clip.w, -1.0f);
        EXPECT_LT(clip.z / clip.w, 1.0f);
      }
    }
  }
}

TEST(Camera, GenerateRayAgreesWithPerspectiveProjection) {
  expect_ray_matches_projection(perspective(100.0f, std::nullopt), 1.5f);
  expect_ray_matches_projection(perspective(std::nullopt, std::nullopt), 0.75f);
  // A camera authored for 2:1 rendered square: the projection still agrees.
  expect_ray_matches_projection(perspective(50.0f, 2.0f), 1.0f);
}

// The image's aspect wins over the camera's aspectRatio and yfov is kept (as in three.js
// and Blender): the ray through the right edge's midpoint of a square image leaves at the
// same angle, yfov / 2, as the ray through the top edge's, whatever aspectRatio says.
TEST(Camera, ImageAspectWinsAndTheVerticalFieldOfViewIsKept) {
  for (std::optional<float> authored : {std::optional<float>(), std::optional<float>(2.0f)}) {
    const Camera c = perspective(std::nullopt, authored);
    const glm::vec3 forward = c.forward();
    const float right = std::acos(glm::dot(generate_ray(c, 1.0f, {1.0f, 0.0f}).direction, forward));
    const float top = std::acos(glm::dot(generate_ray(c, 1.0f, {0.0f, 1.0f}).direction, forward));
    EXPECT_NEAR(top, 0.45f, 1e-5f);
    EXPECT_NEAR(right, 0.45f, 1e-5f);
    // At 16:9 the horizontal half angle is atan(16/9 tan(yfov / 2)).
    const float wide =
        std::acos(glm::dot(generate_ray(c, 16.0f / 9.0f, {1.0f, 0.0f}).direction, forward));
    EXPECT_NEAR(wide, std::atan(16.0f / 9.0f * std::tan(0.45f)), 1e-5f);
  }
}

TEST(Camera, GenerateRayAgreesWithOrthographicProjection) {
  Camera c;
  c.type = Camera::Type::kOrthographic;
  c.xmag = 3.0f;
  c.ymag = 2.0f;
  c.znear = 0.1f;
  c.zfar = 20.0f;
  c.camera_to_world =
      glm::inverse(glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0)));
  expect_ray_matches_projection(c, 1.0f);
  expect_ray_matches_projection(c, 1.5f);
  // Orthographic rays are parallel, along the camera's -Z, from a plane through the eye;
  // the plane is 2 ymag tall and as wide as the image's aspect makes it (xmag = 3 is what
  // the camera was authored for: a 3:2 image).
  const Ray r = generate_ray(c, 1.5f, {1.0f, -1.0f});
  EXPECT_NEAR(r.origin.x, 3.0f, 1e-5f);
  EXPECT_NEAR(r.origin.y, -2.0f, 1e-5f);
  EXPECT_NEAR(r.direction.z, -1.0f, 1e-6f);
  EXPECT_NEAR(generate_ray(c, 1.0f, {1.0f, -1.0f}).origin.x, 2.0f, 1e-5f);
  EXPECT_FLOAT_EQ(*authored_aspect(c), 1.5f);
}

TEST(Camera, PerspectiveMatrixIsTheSpecFormula) {
  Camera c;
  c.yfov = 1.0f;
  c.znear = 0.5f;
  c.zfar = 10.0f;
  const glm::mat4 p = projection_matrix(c, 2.0f);
  const float t = std::tan(0.5f);
  EXPECT_FLOAT_EQ(p[0][0], 1.0f / (2.0f * t));
  EXPECT_FLOAT_EQ(p[1][1], 1.0f / t);
  EXPECT_FLOAT_EQ(p[2][2], 10.5f / -9.5f);
  EXPECT_FLOAT_EQ(p[3][2], 2.0f * 10.0f * 0.5f / -9.5f);
  EXPECT_FLOAT_EQ(p[2][3], -1.0f);
  EXPECT_FLOAT_EQ(p[3][3], 0.0f);
  // The near plane maps to depth -1 and the far plane to +1.
  const glm::vec4 n = p * glm::vec4(0, 0, -0.5f, 1), f = p * glm::vec4(0, 0, -10.0f, 1);
  EXPECT_NEAR(n.z / n.w, -1.0f, 1e-6f);
  EXPECT_NEAR(f.z / f.w, 1.0f, 1e-5f);
}

TEST(Camera, ViewMatrixInvertsCameraToWorld) {
  const Camera c = perspective(10.0f, std::nullopt);
  const glm::mat4 id = view_matrix(c) * c.camera_to_world;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(id[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
}

TEST(Camera, AutoCameraFramesTheBoundingSphereAsDocumented) {
  Bounds b;
  b.extend({-1, 0, -2});
  b.extend({3, 2, 2});
  const glm::vec3 centre(1, 1, 0);
  const float radius = 0.5f * glm::length(glm::vec3(4, 2, 4));  // 3
  for (float aspect : {1.0f, 1.777f, 0.5f}) {
    const Camera c = auto_camera(b, aspect);
    EXPECT_EQ(c.type, Camera::Type::kPerspective);
    EXPECT_NEAR(c.yfov, 0.7853982f, 1e-6f);
    const glm::vec3 to_eye = c.position() - centre;
    const float d = glm::length(to_eye);
    // Direction from target to eye: (0, sin 20deg, cos 20deg).
    const float e = glm::radians(20.0f);
    EXPECT_NEAR(to_eye.x / d, 0.0f, 1e-5f);
    EXPECT_NEAR(to_eye.y / d, std::sin(e), 1e-5f);
    EXPECT_NEAR(to_eye.z / d, std::cos(e), 1e-5f);
    EXPECT_NEAR(glm::dot(c.forward(), -to_eye / d), 1.0f, 1e-5f);
    // The sphere touches the narrower half field of view exactly.
    const float half_y = 0.5f * c.yfov;
    const float half_x = std::atan(aspect * std::tan(half_y));
    EXPECT_NEAR(radius / d, std::sin(std::min(half_x, half_y)), 1e-4f);
    // Camera is upright: its right vector is horizontal.
    EXPECT_NEAR(glm::vec3(c.camera_to_world[0]).y, 0.0f, 1e-5f);
  }
}

TEST(Camera, SelectCamera) {
  Scene scene;
  scene.source = "test.gltf";
  Camera first;
  first.name = "first";
  Camera second;
  second.name = "second";
  scene.cameras = {first, second};
  EXPECT_EQ(select_camera(scene, std::nullopt, 1.0f).name, "first");
  EXPECT_EQ(select_camera(scene, 1, 1.0f).name, "second");
  try {
    select_camera(scene, 2, 1.0f);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2 cameras"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("test.gltf"), std::string::npos) << e.what();
  }
  EXPECT_THROW(select_camera(scene, -1, 1.0f), Error);
  scene.cameras.clear();
  EXPECT_EQ(select_camera(scene, std::nullopt, 1.0f).name, "auto");
}

}  // namespace
}  // namespace pbrkit
