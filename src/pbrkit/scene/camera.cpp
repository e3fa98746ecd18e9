#include "pbrkit/scene/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/core/math.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

constexpr float kAutoYfov = 0.7853981633974483f;  // 45 degrees
constexpr float kAutoElevation = 20.0f * kPi / 180.0f;

// Image-plane half extents at unit distance in front of the camera (x right, y up).
glm::vec2 half_extent(const Camera& camera, float aspect) {
  const float a = camera.aspect_ratio.value_or(aspect);
  if (camera.type == Camera::Type::kOrthographic) return {camera.xmag, camera.ymag};
  const float t = std::tan(0.5f * camera.yfov);
  return {a * t, t};
}

}  // namespace

Camera auto_camera(const Bounds& bounds_in, float aspect) {
  Bounds bounds = bounds_in;
  if (bounds.empty()) {
    bounds.extend(glm::vec3(-1.0f));
    bounds.extend(glm::vec3(1.0f));
  }
  const glm::vec3 target = bounds.center();
  float radius = 0.5f * glm::length(bounds.extent());
  if (!(radius > 0.0f)) radius = 1.0f;
  // The smaller of the two half fields of view decides the distance at which the bounding
  // sphere touches the frustum: sin(half_fov) = radius / distance.
  const float half_y = 0.5f * kAutoYfov;
  const float half_x = std::atan(std::max(aspect, 1e-6f) * std::tan(half_y));
  const float half_min = std::min(half_x, half_y);
  const float distance = radius / std::sin(half_min);
  const glm::vec3 dir(0.0f, std::sin(kAutoElevation), std::cos(kAutoElevation));
  const glm::vec3 eye = target + distance * dir;

  Camera camera;
  camera.name = "auto";
  camera.type = Camera::Type::kPerspective;
  camera.yfov = kAutoYfov;
  camera.znear = std::max(1e-4f, 1e-3f * distance);
  camera.camera_to_world = glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
  return camera;
}

Camera select_camera(const Scene& scene, std::optional<int> index, float aspect) {
  if (index) {
    if (*index < 0 || *index >= int(scene.cameras.size()))
      fail("{}: camera {} does not exist (the scene has {} camera{})", scene.source, *index,
           scene.cameras.size(), scene.cameras.size() == 1 ? "" : "s");
    return scene.cameras[std::size_t(*index)];
  }
  if (!scene.cameras.empty()) return scene.cameras.front();
  return auto_camera(scene.world_bounds(), aspect);
}

glm::mat4 view_matrix(const Camera& camera) {
  return glm::inverse(camera.camera_to_world);
}

glm::mat4 projection_matrix(const Camera& camera, float aspect) {
  // glTF 2.0 specification, section 3.10.3 "Projection Matrices" (written row-major
  // there; glm is column-major, hence m[column][row]).
  glm::mat4 m(0.0f);
  const float n = camera.znear;
  if (camera.type == Camera::Type::kOrthographic) {
    const float f = camera.zfar.value_or(n + 1e6f);
    m[0][0] = 1.0f / camera.xmag;
    m[1][1] = 1.0f / camera.ymag;
    m[2][2] = 2.0f / (n - f);
    m[3][2] = (f + n) / (n - f);
    m[3][3] = 1.0f;
    return m;
  }
  const float a = camera.aspect_ratio.value_or(aspect);
  const float t = std::tan(0.5f * camera.yfov);
  m[0][0] = 1.0f / (a * t);
  m[1][1] = 1.0f / t;
  m[2][3] = -1.0f;
  if (camera.zfar) {
    const float f = *camera.zfar;
    m[2][2] = (f + n) / (n - f);
    m[3][2] = 2.0f * f * n / (n - f);
  } else {
    m[2][2] = -1.0f;
    m[3][2] = -2.0f * n;
  }
  return m;
}

Ray generate_ray(const Camera& camera, float aspect, glm::vec2 ndc) {
  const glm::vec2 h = half_extent(camera, aspect);
  const glm::mat4& m = camera.camera_to_world;
  Ray ray;
  if (camera.type == Camera::Type::kOrthographic) {
    ray.origin = glm::vec3(m * glm::vec4(ndc.x * h.x, ndc.y * h.y, 0.0f, 1.0f));
    ray.direction = glm::normalize(-glm::vec3(m[2]));
  } else {
    ray.origin = glm::vec3(m[3]);
    ray.direction = glm::normalize(glm::vec3(m * glm::vec4(ndc.x * h.x, ndc.y * h.y, -1.0f, 0.0f)));
  }
  return ray;
}

}  // namespace pbrkit
