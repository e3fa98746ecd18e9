#pragma once
// Helpers for the GL image tests: which pixels see a sphere (analytically, through the
// same primary rays as the path tracer), and per-region means.
#include <cmath>
#include <optional>

#include <glm/glm.hpp>

#include "pbrkit/image/image.h"
#include "pbrkit/scene/camera.h"

namespace pbrkit::gl::testing {

/// The pixel centre's primary ray (scene/camera.h's convention).
inline Ray pixel_ray(const Camera& camera, int x, int y, int w, int h) {
  const glm::vec2 ndc((float(x) + 0.5f) / float(w) * 2.0f - 1.0f,
                      1.0f - (float(y) + 0.5f) / float(h) * 2.0f);
  return generate_ray(camera, float(w) / float(h), ndc);
}

/// Cosine between the view direction and the sphere normal at the first hit, if any.
inline std::optional<float> sphere_hit_cosine(const Ray& ray, glm::vec3 centre, float radius) {
  const glm::vec3 oc = ray.origin - centre;
  const float b = glm::dot(oc, ray.direction);
  const float c = glm::dot(oc, oc) - radius * radius;
  const float disc = b * b - c;
  if (disc <= 0.0f) return std::nullopt;
  const float t = -b - std::sqrt(disc);
  if (t <= 0.0f) return std::nullopt;
  const glm::vec3 n = glm::normalize(ray.origin + t * ray.direction - centre);
  return -glm::dot(n, ray.direction);
}

}  // namespace pbrkit::gl::testing
