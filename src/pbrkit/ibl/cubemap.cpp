// Cube face addressing in the OpenGL convention (OpenGL 4.5 specification, section 8.13,
// table 8.19), texel solid angles and filtered lookups. See cubemap.h.
#include "pbrkit/ibl/cubemap.h"

#include <algorithm>
#include <cmath>

#include "pbrkit/ibl/cube_lookup.h"

namespace pbrkit {

std::array<Image, 6> make_rgba_faces(int size) {
  std::array<Image, 6> faces;
  for (Image& f : faces) f = Image(size, size, 4, 1.0f);
  return faces;
}

glm::vec3 cube_face_point(int face, glm::vec2 st) {
  const float sc = 2.0f * st.x - 1.0f;
  const float tc = 2.0f * st.y - 1.0f;
  // Table 8.19 read backwards: for each face, the direction whose major axis is the face
  // axis and whose (sc, tc) are the given ones.
  glm::vec3 d;
  switch (face) {
    case 0:
      d = {1.0f, -tc, -sc};
      break;  // +X: sc = -rz, tc = -ry
    case 1:
      d = {-1.0f, -tc, sc};
      break;  // -X: sc = +rz, tc = -ry
    case 2:
      d = {sc, 1.0f, tc};
      break;  // +Y: sc = +rx, tc = +rz
    case 3:
      d = {sc, -1.0f, -tc};
      break;  // -Y: sc = +rx, tc = -rz
    case 4:
      d = {sc, -tc, 1.0f};
      break;  // +Z: sc = +rx, tc = -ry
    default:
      d = {-sc, -tc, -1.0f};
      break;  // -Z: sc = -rx, tc = -ry
  }
  return d;
}

glm::vec3 cube_direction(int face, glm::vec2 st) {
  return glm::normalize(cube_face_point(face, st));
}

CubeCoord cube_coord(glm::vec3 d) {
  const detail::FaceHit hit = detail::cube_face_hit(d);
  return {hit.face, {0.5f * (hit.sc + 1.0f), 0.5f * (hit.tc + 1.0f)}};
}

namespace {
// Integral of the solid-angle element of the projected unit cube face over [0,x]x[0,y]
// (the face at distance 1, coordinates in [-1,1]): atan(x y / sqrt(x^2 + y^2 + 1)).
double area_element(double x, double y) {
  return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0));
}
}  // namespace

float cube_texel_solid_angle(int x, int y, int size) {
  const double inv = 2.0 / size;
  const double x0 = x * inv - 1.0, x1 = (x + 1) * inv - 1.0;
  const double y0 = y * inv - 1.0, y1 = (y + 1) * inv - 1.0;
  return float(area_element(x0, y0) - area_element(x0, y1) - area_element(x1, y0) +
               area_element(x1, y1));
}

glm::vec3 sample_cubemap(const Cubemap& cube, glm::vec3 d, float lod) {
  if (cube.mips.empty()) return glm::vec3(0.0f);
  const detail::FaceHit hit = detail::cube_face_hit(d);
  const float max_lod = float(cube.levels() - 1);
  lod = std::clamp(lod, 0.0f, max_lod);
  const int l0 = std::min(int(lod), cube.levels() - 1);
  const float f = lod - float(l0);
  const glm::vec3 c0 = detail::bilinear(cube.mips[l0][hit.face], hit.sc, hit.tc);
  if (f <= 0.0f || l0 + 1 >= cube.levels()) return c0;
  const glm::vec3 c1 = detail::bilinear(cube.mips[l0 + 1][hit.face], hit.sc, hit.tc);
  return c0 + f * (c1 - c0);
}

}  // namespace pbrkit
