#pragma once
// Primary rays for the path tracer's sample loop: scene/camera.h's generate_ray with the
// per-camera set-up (the aspect ratio and the tangent of half the field of view) done
// once per render instead of once per sample. The ray itself is computed with the same
// expressions, so it is bit-identical to generate_ray's (tests/pt/camera_rays_test.cpp).
#include <cmath>

#include <glm/glm.hpp>

#include "pbrkit/scene/camera.h"

namespace pbrkit {

/// A ray cone (Akenine-Moller et al., "Improved Shader and Texture Level of Detail Using
/// Ray Cones", JCGT 2021): the footprint's width at the ray's origin and its spread angle.
struct RayCone {
  float width = 0.0f;
  float spread = 0.0f;
};

class CameraRays {
 public:
  CameraRays(const Camera& camera, float aspect)
      : to_world_(camera.camera_to_world),
        orthographic_(camera.type == Camera::Type::kOrthographic) {
    half_ = image_plane_half_extent(camera, aspect);
    forward_ = glm::normalize(-glm::vec3(to_world_[2]));
  }

  /// The cone of one pixel of an image `height` pixels high (the paper's section 4.2): a
  /// pinhole's cones start as a point and spread by the angle a pixel subtends,
  /// atan(2 tan(yfov / 2) / height); an orthographic camera's are a pixel wide and parallel.
  RayCone pixel_cone(int height) const {
    const float pixel = 2.0f * half_.y / float(height);
    return orthographic_ ? RayCone{pixel, 0.0f} : RayCone{0.0f, std::atan(pixel)};
  }

  /// generate_ray(camera, aspect, ndc).
  Ray generate(glm::vec2 ndc) const {
    const glm::mat4& m = to_world_;
    const glm::vec2 h = half_;
    Ray ray;
    if (orthographic_) {
      ray.origin = glm::vec3(m * glm::vec4(ndc.x * h.x, ndc.y * h.y, 0.0f, 1.0f));
      ray.direction = forward_;
    } else {
      ray.origin = glm::vec3(m[3]);
      ray.direction =
          glm::normalize(glm::vec3(m * glm::vec4(ndc.x * h.x, ndc.y * h.y, -1.0f, 0.0f)));
    }
    return ray;
  }

 private:
  glm::mat4 to_world_;
  bool orthographic_;
  glm::vec2 half_{1.0f};
  glm::vec3 forward_{0.0f, 0.0f, -1.0f};  ///< orthographic direction
};

}  // namespace pbrkit
