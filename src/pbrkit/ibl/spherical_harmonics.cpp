// Irradiance spherical harmonics (Ramamoorthi & Hanrahan 2001).
#include "pbrkit/ibl/spherical_harmonics.h"

#include <vector>

#include "pbrkit/core/math.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

std::array<float, 9> sh_basis(glm::vec3 d) {
  // R&H 2001, eq. 3 (real SH, Cartesian form); Y_1-1 ~ y, Y_10 ~ z, Y_11 ~ x.
  const float x = d.x, y = d.y, z = d.z;
  return {0.282095f,
          0.488603f * y,
          0.488603f * z,
          0.488603f * x,
          1.092548f * x * y,
          1.092548f * y * z,
          0.315392f * (3.0f * z * z - 1.0f),
          1.092548f * x * z,
          0.546274f * (x * x - y * y)};
}

namespace {
// A_l of the clamped-cosine kernel (R&H 2001, eq. 8): pi, 2 pi / 3, pi / 4.
constexpr std::array<float, 9> kCosineLobe = {
    kPi,        2.0f * kPi / 3.0f, 2.0f * kPi / 3.0f, 2.0f * kPi / 3.0f, kPi / 4.0f,
    kPi / 4.0f, kPi / 4.0f,        kPi / 4.0f,        kPi / 4.0f};
}  // namespace

SH9 project_sh_irradiance(const Cubemap& cube, int level) {
  SH9 sh{};
  if (cube.mips.empty()) return sh;
  const int size = cube.size(level);
  // One partial sum per (face, row), added in a fixed order afterwards, so the result does
  // not depend on how TBB splits the work. Sums in double: 400k terms of mixed magnitude.
  const int rows = 6 * size;
  std::vector<std::array<glm::dvec3, 9>> partial(rows);
  // One task per row y of all six faces: the texel solid angles (4 atan2 each) are the same
  // on every face, so they are computed once per row.
  pbrkit::parallel_for(0, size, [&](int y) {
    std::vector<float> omega(static_cast<std::size_t>(size));
    for (int x = 0; x < size; ++x) omega[std::size_t(x)] = cube_texel_solid_angle(x, y, size);
    for (int face = 0; face < 6; ++face) {
      const Image& img = cube.mips[level][face];
      std::array<glm::dvec3, 9> acc{};
      for (int x = 0; x < size; ++x) {
        const glm::vec3 d = cube_direction(
            face, {(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size)});
        const glm::dvec3 L = glm::dvec3(img.rgb(x, y)) * double(omega[std::size_t(x)]);
        const std::array<float, 9> Y = sh_basis(d);
        for (int i = 0; i < 9; ++i) acc[i] += L * double(Y[i]);
      }
      partial[std::size_t(face) * size + y] = acc;
    }
  });
  std::array<glm::dvec3, 9> total{};
  for (const auto& p : partial)
    for (int i = 0; i < 9; ++i) total[i] += p[i];
  for (int i = 0; i < 9; ++i) sh[i] = glm::vec3(total[i] * double(kCosineLobe[i]));
  return sh;
}

glm::vec3 eval_sh_irradiance(const SH9& sh, glm::vec3 n) {
  const std::array<float, 9> Y = sh_basis(n);
  glm::vec3 E(0.0f);
  for (int i = 0; i < 9; ++i) E += sh[i] * Y[i];
  return E;
}

}  // namespace pbrkit
