#pragma once
// A UV sphere as three.js's SphereGeometry (src/geometries/SphereGeometry.js) writes it:
// each vertex computed in double from its own angles, so the seam (phi = 2 pi: sin is
// -2.4e-16, not 0) and the south pole (theta = pi: sin is 1.2e-16) miss the copies they
// should equal by rounding; stored as float like a Float32Array. The poles keep one vertex
// per column. Normals are the unit positions, as three.js writes them.
#include <cmath>
#include <cstdint>
#include <numbers>

#include "pbrkit/scene/scene.h"

namespace pbrkit::test {

inline Mesh threejs_sphere(double radius, int width_segments, int height_segments) {
  Mesh m;
  m.name = "threejs_sphere";
  const double pi = std::numbers::pi;
  for (int iy = 0; iy <= height_segments; ++iy) {
    const double v = double(iy) / height_segments;
    for (int ix = 0; ix <= width_segments; ++ix) {
      const double u = double(ix) / width_segments;
      const glm::dvec3 n(-std::cos(u * 2 * pi) * std::sin(v * pi), std::cos(v * pi),
                         std::sin(u * 2 * pi) * std::sin(v * pi));
      m.positions.push_back(glm::vec3(radius * n));
      m.normals.push_back(glm::vec3(glm::normalize(n)));
    }
  }
  const auto at = [&](int iy, int ix) { return std::uint32_t(iy * (width_segments + 1) + ix); };
  for (int iy = 0; iy < height_segments; ++iy)
    for (int ix = 0; ix < width_segments; ++ix) {
      const std::uint32_t a = at(iy, ix + 1), b = at(iy, ix), c = at(iy + 1, ix),
                          d = at(iy + 1, ix + 1);
      if (iy != 0) m.indices.insert(m.indices.end(), {a, b, d});
      if (iy != height_segments - 1) m.indices.insert(m.indices.end(), {b, c, d});
    }
  return m;
}

}  // namespace pbrkit::test
