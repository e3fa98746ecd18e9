#pragma once
// Cubemaps in the OpenGL / Vulkan / KTX2 convention, so baked data uploads to GL as-is.
// Faces are ordered +X, -X, +Y, -Y, +Z, -Z. Within a face, (s, t) in [0,1]^2 follow the
// OpenGL 4.5 specification, table 8.19 (major axis ma, sc, tc; s = (sc/|ma| + 1)/2,
// t = (tc/|ma| + 1)/2). Image row y holds t = (y + 0.5) / size (row 0 is the first row
// glTexImage2D uploads), column x holds s = (x + 0.5) / size.
#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/image/image.h"

namespace pbrkit {

/// A cube texture with a mip chain (level 0 the largest), faces in the order above.
struct Cubemap {
  /// mips[level][face]; every face of a level is square with the same size and channels.
  std::vector<std::array<Image, 6>> mips;

  /// Number of mip levels (0 for an empty cube).
  int levels() const { return int(mips.size()); }
  /// Face size of `level` in texels (0 for an empty cube).
  int size(int level = 0) const { return mips.empty() ? 0 : mips[level][0].width; }
};

/// Six square RGBA faces of `size` px with every channel 1 (alpha 1), for a level whose RGB
/// the caller then writes.
std::array<Image, 6> make_rgba_faces(int size);

/// Unit direction through (s, t) of `face` (0..5 = +X, -X, +Y, -Y, +Z, -Z).
glm::vec3 cube_direction(int face, glm::vec2 st);
/// The point at (s, t) on `face` of the cube [-1, 1]^3 (cube_direction before normalising):
/// affine in s and t.
glm::vec3 cube_face_point(int face, glm::vec2 st);

/// A point on the cube: `face` (0..5) and (s, t) in [0, 1]^2 on it.
struct CubeCoord {
  int face;
  glm::vec2 st;
};
/// The face and (s, t) that direction `d` (any length > 0) hits; inverse of cube_direction.
CubeCoord cube_coord(glm::vec3 d);

/// Solid angle of texel (x, y) on a face of `size` texels (exact, via the area element
/// of the projected cube; sums to 4 pi over the cube).
float cube_texel_solid_angle(int x, int y, int size);

/// Bilinear lookup of `level` (clamped within the face; no cross-face filtering) and
/// linear interpolation between levels for fractional `lod`.
glm::vec3 sample_cubemap(const Cubemap& cube, glm::vec3 d, float lod = 0.0f);

}  // namespace pbrkit
