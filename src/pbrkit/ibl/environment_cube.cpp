// The bake's first stage: the environment resampled to a cube and its box-filtered mip chain
// (see environment_cube.h).
#include "pbrkit/ibl/environment_cube.h"

#include <algorithm>

#include "pbrkit/util/error.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

int cube_supersampling(int source_width, int face_size) {
  // Source texels per cube texel along one axis: the equator spans 4 faces. Two samples
  // per source texel (at least 2x2 per cube texel) so small bright sources are integrated,
  // not point-sampled; capped at 8x8.
  const int ratio = (source_width + 4 * face_size - 1) / (4 * face_size);
  return std::clamp(2 * ratio, 2, 8);
}

Cubemap resample_to_cube(const Environment& env, int face_size) {
  if (face_size < 1) fail("cube face size must be positive, got {}", face_size);
  Cubemap cube;
  cube.mips.push_back(make_rgba_faces(face_size));
  const int ss = cube_supersampling(env.map.width, face_size);
  const float inv = 1.0f / float(face_size * ss);
  const float weight = 1.0f / float(ss * ss);
  pbrkit::parallel_for(0, 6 * face_size, [&](int r) {
    const int face = r / face_size, y = r % face_size;
    Image& img = cube.mips[0][face];
    for (int x = 0; x < face_size; ++x) {
      // A box filter over the texel's (s, t) square: the texel's average radiance, up to
      // the small variation of the solid-angle element within one texel.
      glm::vec3 sum(0.0f);
      for (int j = 0; j < ss; ++j)
        for (int i = 0; i < ss; ++i) {
          const glm::vec2 st((float(x * ss + i) + 0.5f) * inv, (float(y * ss + j) + 0.5f) * inv);
          sum += env.eval(cube_direction(face, st));
        }
      img.set_rgb(x, y, sum * weight);
    }
  });
  return cube;
}

void build_mip_chain(Cubemap& cube, int min_size) {
  while (cube.size(cube.levels() - 1) / 2 >= std::max(min_size, 1)) {
    const int src_level = cube.levels() - 1;
    const int size = cube.size(src_level) / 2;
    cube.mips.push_back(make_rgba_faces(size));
    const auto& src = cube.mips[src_level];
    auto& dst = cube.mips.back();
    pbrkit::parallel_for(0, 6, [&](int face) {
      // 2x2 box filter. Texels of one face have nearly equal solid angles at these sizes;
      // the filtered importance sampling only needs a band-limited chain (Colbert &
      // Krivanek 2007, section 20.4).
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const glm::vec3 c = src[face].rgb(2 * x, 2 * y) + src[face].rgb(2 * x + 1, 2 * y) +
                              src[face].rgb(2 * x, 2 * y + 1) + src[face].rgb(2 * x + 1, 2 * y + 1);
          dst[face].set_rgb(x, y, 0.25f * c);
        }
    });
  }
}

}  // namespace pbrkit
