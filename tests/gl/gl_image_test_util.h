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

/// Whether the rays of pixel (x, y) and of its eight neighbours all hit the sphere: the
/// pixel lies inside the silhouette. A path tracer's box filter averages over the whole
/// pixel, so on the silhouette its mean holds some of what lies behind the sphere, where a
/// rasteriser without MSAA shades the pixel's centre alone: a difference of the filters,
/// not of the shading, that comparisons of the two leave out.
inline bool interior_pixel(const Camera& camera, int x, int y, int width, int height,
                           glm::vec3 centre, float radius) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (!sphere_hit_cosine(pixel_ray(camera, x + dx, y + dy, width, height), centre, radius))
        return false;
  return true;
}

/// The sums of R+G+B over the pixels of two same-sized images where the sphere is seen
/// with n.v >= min_mu, inside its silhouette (interior_pixel), and their count: per-sphere
/// means of a render against a reference.
struct SphereSums {
  double a = 0.0, b = 0.0;
  int pixels = 0;
};
inline SphereSums sphere_sums(const Image& a, const Image& b, const Camera& camera,
                              glm::vec3 centre, float radius, float min_mu) {
  SphereSums s;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const auto mu = sphere_hit_cosine(pixel_ray(camera, x, y, a.width, a.height), centre, radius);
      if (!mu || *mu < min_mu) continue;
      if (!interior_pixel(camera, x, y, a.width, a.height, centre, radius)) continue;
      const glm::vec3 pa = a.rgb(x, y), pb = b.rgb(x, y);
      s.a += pa.r + pa.g + pa.b;
      s.b += pb.r + pb.g + pb.b;
      ++s.pixels;
    }
  return s;
}

}  // namespace pbrkit::gl::testing
