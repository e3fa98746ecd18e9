#pragma once
// Private to the ibl module: the inline pieces of a cube lookup (face selection per the
// OpenGL 4.5 specification, table 8.19, and a bilinear fetch clamped within a face), shared
// by sample_cubemap() and the prefilter's inner loop so both read texels identically.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "pbrkit/image/image.h"

namespace pbrkit::detail {

/// The face a direction hits and its (sc/|ma|, tc/|ma|) in [-1, 1].
struct FaceHit {
  int face;
  float sc, tc;
};

/// The face that direction `d` (any length > 0) hits and where (table 8.19).
inline FaceHit cube_face_hit(glm::vec3 d) {
  const float ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  FaceHit h;
  float ma;
  if (ax >= ay && ax >= az) {
    h.face = d.x > 0.0f ? 0 : 1;
    ma = ax;
    h.sc = d.x > 0.0f ? -d.z : d.z;
    h.tc = -d.y;
  } else if (ay >= az) {
    h.face = d.y > 0.0f ? 2 : 3;
    ma = ay;
    h.sc = d.x;
    h.tc = d.y > 0.0f ? d.z : -d.z;
  } else {
    h.face = d.z > 0.0f ? 4 : 5;
    ma = az;
    h.sc = d.z > 0.0f ? d.x : -d.x;
    h.tc = -d.y;
  }
  const float inv = ma > 0.0f ? 1.0f / ma : 0.0f;
  h.sc *= inv;
  h.tc *= inv;
  return h;
}

/// Bilinear RGB lookup of a square face at (sc, tc) in [-1, 1]; texel centres at
/// (i + 0.5) / size, clamped at the face edges.
inline glm::vec3 bilinear(const Image& face, float sc, float tc) {
  const int size = face.width;
  const int ch = face.channels;
  const float half_size = 0.5f * float(size);
  const float x = std::clamp((sc + 1.0f) * half_size - 0.5f, 0.0f, float(size - 1));
  const float y = std::clamp((tc + 1.0f) * half_size - 0.5f, 0.0f, float(size - 1));
  const int x0 = int(x), y0 = int(y);
  const int x1 = std::min(x0 + 1, size - 1), y1 = std::min(y0 + 1, size - 1);
  const float fx = x - float(x0), fy = y - float(y0);
  const float* row0 = face.data.data() + std::size_t(y0) * size * ch;
  const float* row1 = face.data.data() + std::size_t(y1) * size * ch;
  const float* p00 = row0 + x0 * ch;
  const float* p10 = row0 + x1 * ch;
  const float* p01 = row1 + x0 * ch;
  const float* p11 = row1 + x1 * ch;
  const float w00 = (1.0f - fx) * (1.0f - fy), w10 = fx * (1.0f - fy);
  const float w01 = (1.0f - fx) * fy, w11 = fx * fy;
  return {w00 * p00[0] + w10 * p10[0] + w01 * p01[0] + w11 * p11[0],
          w00 * p00[1] + w10 * p10[1] + w01 * p01[1] + w11 * p11[1],
          w00 * p00[2] + w10 * p10[2] + w01 * p01[2] + w11 * p11[2]};
}

}  // namespace pbrkit::detail
