// The diffuse irradiance cube by direct quadrature (see irradiance_cube.h).
#include "pbrkit/ibl/irradiance_cube.h"

#include "pbrkit/ibl/prefilter_kernels.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

Cubemap irradiance_cube(const Cubemap& source, int size) {
  if (size < 1) fail("irradiance cube size must be positive, got {}", size);
  // E(n) = sum over source texels of L(w) max(0, n.w) dOmega(w): a direct quadrature of the
  // cosine convolution over a 64 px level (or the finest one if smaller), which is smooth
  // enough that the texel-centre rule is accurate to ~1e-4 of E.
  int level = 0;
  while (level + 1 < source.levels() && source.size(level) > 64) ++level;
  const detail::QuadratureSource texels = detail::flatten_level(source, level);
  Cubemap out;
  out.mips.push_back(make_rgba_faces(size));
  pbrkit::parallel_for(0, 6 * size, [&](int r) {
    const int face = r / size, y = r % size;
    for (int x = 0; x < size; ++x) {
      const glm::vec3 n =
          cube_direction(face, {(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size)});
      out.mips[0][face].set_rgb(x, y, detail::cosine_sum(texels, n));
    }
  });
  return out;
}

}  // namespace pbrkit
