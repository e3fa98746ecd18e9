#pragma once
// Camera conventions shared by the path tracer and the OpenGL renderer, so both produce
// the same image of a scene: glTF cameras (local -Z forward, +Y up), the GL projection
// matrices, primary-ray generation, and automatic framing when a file has no camera.
#include <optional>

#include <glm/glm.hpp>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

struct Ray {
  glm::vec3 origin;
  glm::vec3 direction;  ///< unit length
};

/// The automatic camera for a scene without one: perspective, yfov = 45 degrees (0.7854),
/// looking at the centre of the world bounding box from the +Z side, raised 20 degrees
/// above the horizon (direction from target to eye: (0, sin 20, cos 20)), at the distance
/// where the bounding sphere just fits the smaller of the two fields of view.
Camera auto_camera(const Bounds& bounds, float aspect);

/// `index` given: that glTF camera (Error if out of range, naming the count). Otherwise
/// the scene's first camera, or auto_camera when it has none.
Camera select_camera(const Scene& scene, std::optional<int> index, float aspect);

/// World-to-camera matrix (inverse of camera_to_world).
glm::mat4 view_matrix(const Camera& camera);
/// OpenGL clip-space projection per the glTF spec's projection formulas (infinite
/// perspective when zfar is absent). `aspect` is used when the camera has none.
glm::mat4 projection_matrix(const Camera& camera, float aspect);

/// Primary ray through `ndc` in [-1,1]^2 (x right, y up; pixel centres at
/// ((x + 0.5) / w * 2 - 1, 1 - (y + 0.5) / h * 2)). Same geometry as projection_matrix.
Ray generate_ray(const Camera& camera, float aspect, glm::vec2 ndc);

}  // namespace pbrkit
