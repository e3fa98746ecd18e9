#pragma once
// The dispersion end-to-end scene both renderers' tests draw (tests/pt and tests/gl
// dispersion_end_to_end_test.cpp): a straight edge of an emitter seen through a tilted,
// strongly dispersive glass slab, an orthographic camera looking down -Z, and the
// measurement of where the edge appears in each colour channel. Each test predicts the
// edge with its own renderer's refraction model.
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/image/image.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit::test::dispersive_slab {

inline constexpr int kWidth = 256, kHeight = 16;
inline constexpr float kHalfHeight = 0.125f;  // 64 pixels per unit: x in [-2, 2]
inline constexpr float kTilt = 1.0471976f;    // 60 degrees, about +Y
inline constexpr float kThickness = 1.0f;
inline constexpr float kIor = 1.5f;
inline constexpr float kDispersion = 20.0f;  // Abbe number 1: the channels' iors 1.25, 1.5, 1.75

/// One pixel in world units.
inline constexpr double kPixel = 2.0 * double(kHalfHeight) / kHeight;

// KHR_materials_dispersion README: n(lambda) = n_d + (n_d - 1) / V_d (523655 / lambda^2 -
// 1.5168), V_d = 20 / dispersion, at the channels' wavelengths (MODEL.md, "Dispersion").
inline double channel_ior(int c) {
  const double lambda[3] = {717.64, 587.57, 509.56};
  const double abbe = 20.0 / kDispersion;
  return kIor + (kIor - 1.0) / abbe * (523655.0 / (lambda[c] * lambda[c]) - 1.5168);
}

/// The camera ray d = (0, 0, -1) refracted into the slab in channel c: the slab's normal
/// n = (sin a, 0, cos a); Snell (vector form, eta = 1 / n_c): T = eta d + (eta cos_i -
/// cos_t) n, cos_t = sqrt(1 - eta^2 (1 - cos_i^2)). Returns T.x; `cos_t` is set.
inline double refracted_x(int c, double& cos_t) {
  const double eta = 1.0 / channel_ior(c);
  const double cos_i = std::cos(double(kTilt)), sin_i = std::sin(double(kTilt));
  cos_t = std::sqrt(1.0 - eta * eta * sin_i * sin_i);
  return (eta * cos_i - cos_t) * sin_i;
}

/// The scene: the emitter (x < 0, z = -20) and the slab, 10 wide and `kThickness` thick,
/// centred on the origin and turned by kTilt about +Y, so it covers the whole view.
inline Scene slab_scene(float dispersion) {
  Scene scene;
  scene.source = "test:dispersive slab";
  Material emitter;
  emitter.base_color_factor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  emitter.emissive_factor = glm::vec3(1.0f);
  scene.materials.push_back(emitter);
  add_mesh_instance(scene, make_quad({-40, -5, -20}, {40, 0, 0}, {0, 10, 0}), 0);

  Material glass;
  glass.base_color_factor = glm::vec4(1.0f);
  glass.metallic_factor = 0.0f;
  glass.roughness_factor = 0.0f;
  glass.ior = kIor;
  glass.transmission = TransmissionExtension{};
  glass.transmission->factor = 1.0f;
  glass.volume = VolumeExtension{};
  glass.volume->thickness_factor = kThickness;
  glass.dispersion = DispersionExtension{dispersion};
  scene.materials.push_back(glass);
  // make_prism's outline is (x, z): the slab's section, the rectangle spanned by the
  // tangent u = (cos a, -sin a) (half width 5) and the normal n = (sin a, cos a).
  const glm::vec2 u(std::cos(kTilt), -std::sin(kTilt)), n(std::sin(kTilt), std::cos(kTilt));
  const float w = 5.0f, h = 0.5f * kThickness;
  const std::vector<glm::vec2> outline = {-w * u - h * n, w * u - h * n, w * u + h * n,
                                          -w * u + h * n};
  add_mesh_instance(scene, make_prism(outline, 2.0f), 1,
                    glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -1.0f, 0.0f)));
  return scene;
}

/// Per channel, the world x where the row-averaged profile falls through half way between
/// its left (emitter, pixels 48..63, x in [-1.25, -1)) and right (dark, the last 16
/// pixels) levels, searched from pixel 64 on and interpolated between pixel centres.
inline glm::dvec3 measured_edges(const Image& image) {
  glm::dvec3 edge(0.0);
  for (int c = 0; c < 3; ++c) {
    std::vector<double> profile(std::size_t(image.width), 0.0);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) profile[std::size_t(x)] += image.rgb(x, y)[c];
    double left = 0.0, right = 0.0;
    for (int x = 0; x < 16; ++x) {
      left += profile[std::size_t(48 + x)] / 16.0;
      right += profile[std::size_t(image.width - 1 - x)] / 16.0;
    }
    const double half = 0.5 * (left + right);
    double px = -1.0;
    for (int x = 64; x + 1 < image.width; ++x) {
      const double a = profile[std::size_t(x)], b = profile[std::size_t(x + 1)];
      if (a >= half && b < half) {
        px = double(x) + 0.5 + (a - half) / (a - b);
        break;
      }
    }
    const double half_width = double(kHalfHeight) * kWidth / kHeight;
    edge[c] = (px / kWidth * 2.0 - 1.0) * half_width;
  }
  return edge;
}

}  // namespace pbrkit::test::dispersive_slab
