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

}  // namespace

glm::vec2 image_plane_half_extent(const Camera& camera, float aspect) {
  // The vertical extent is the camera's; the horizontal one follows the image, as three.js
  // and Blender do, so a render at any size shows round spheres round.
  if (camera.type == Camera::Type::kOrthographic) return {aspect * camera.ymag, camera.ymag};
  const float t = std::tan(0.5f * camera.yfov);
  return {aspect * t, t};
}

std::optional<float> authored_aspect(const Camera& camera) {
  if (camera.type == Camera::Type::kOrthographic) return camera.xmag / camera.ymag;
  return camera.aspect_ratio;
}

ImageSize image_size(const Camera& camera, std::optional<int> width, std::optional<int> height,
                     int longer_side) {
  const auto clamp_size = [](double v) { return int(std::clamp(std::lround(v), 1L, 16384L)); };
  const double a = authored_aspect(camera).value_or(1.0f);
  if (width && height) return {*width, *height};
  if (width) return {*width, clamp_size(*width / a)};
  if (height) return {clamp_size(*height * a), *height};
  if (a >= 1.0) return {longer_side, clamp_size(longer_side / a)};
  return {clamp_size(longer_side * a), longer_side};
}

RenderView select_view(const Scene& scene, std::optional<int> camera_index,
                       std::optional<int> width, std::optional<int> height) {
  RenderView view;
  if (camera_index || !scene.cameras.empty()) {
    view.camera = select_camera(scene, camera_index, 1.0f);
    view.size = image_size(view.camera, width, height);
  } else {
    // The automatic camera is made for the image, so the size comes first.
    view.size = image_size(Camera{}, width, height);
    view.camera = auto_camera(scene.world_bounds(), view.size.aspect());
  }
  return view;
}

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
    const glm::vec2 h = image_plane_half_extent(camera, aspect);
    m[0][0] = 1.0f / h.x;
    m[1][1] = 1.0f / h.y;
    m[2][2] = 2.0f / (n - f);
    m[3][2] = (f + n) / (n - f);
    m[3][3] = 1.0f;
    return m;
  }
  const glm::vec2 h = image_plane_half_extent(camera, aspect);
  m[0][0] = 1.0f / h.x;
  m[1][1] = 1.0f / h.y;
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
  const glm::vec2 h = image_plane_half_extent(camera, aspect);
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
