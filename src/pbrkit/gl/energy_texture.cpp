#include "pbrkit/gl/energy_texture.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <epoxy/gl.h>

#include "pbrkit/core/anisotropic_energy.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/core/sheen.h"
#include "pbrkit/ibl/anisotropic_albedo.h"

namespace pbrkit::gl {

namespace {

// A coordinate t close to i / (n - 1) for which the table's own scaling t * (n - 1) gives
// exactly i, so EnergyTable's interpolation returns the stored node value with weight
// exactly 0 or 1 (the compensation lobe divides differences of E near 1, which would
// magnify a last-bit interpolation residue).
float node_coordinate(int i, int n) {
  const float scale = float(n - 1);
  float t = float(i) / scale;
  for (int k = 0; k < 16 && t * scale != float(i); ++k)
    t = std::nextafter(t, t * scale < float(i) ? 2.0f : -1.0f);
  return t;
}

// Each texel holds a node and its neighbour along x (clamped at the last node), so the
// GLSL's bilinear interpolation, which needs four nodes, reads two texels (one for the
// sheen table's single channel), not four: on llvmpipe each texelFetch is a full texture
// instruction, and the compensation reads these tables once per light.
GLuint create_rgba32f(int width, int height, const std::vector<float>& texels) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA32F, width, height);
  glTextureSubImage2D(texture, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, texels.data());
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

}  // namespace

unsigned create_energy_texture(GeometryModel model) {
  const EnergyTable& table = EnergyTable::get(model);
  constexpr int kMu = EnergyTable::kMuSize, kRough = EnergyTable::kRoughnessSize;
  static_assert(kMu >= kRough, "row kRough holds the averages, one per roughness node");
  // At a node the table's interpolation returns the node value (up to rounding).
  auto node = [&](int i, int j) {
    return table.AB(node_coordinate(std::min(i, kMu - 1), kMu),
                    node_coordinate(std::min(j, kRough - 1), kRough));
  };
  // Rows 0..kRough-1: (A, B) at node (i, j) and at (i + 1, j). Row kRough: (A_avg, B_avg)
  // at roughness node j (x = j) and at j + 1.
  std::vector<float> texels(std::size_t(kMu) * (kRough + 1) * 4, 0.0f);
  auto put = [&](int x, int y, glm::vec2 a, glm::vec2 b) {
    float* t = &texels[(std::size_t(y) * kMu + std::size_t(x)) * 4];
    t[0] = a.x, t[1] = a.y, t[2] = b.x, t[3] = b.y;
  };
  for (int j = 0; j < kRough; ++j) {
    for (int i = 0; i < kMu; ++i) put(i, j, node(i, j), node(i + 1, j));
    const float r0 = node_coordinate(j, kRough);
    const float r1 = node_coordinate(std::min(j + 1, kRough - 1), kRough);
    put(j, kRough, table.AB_avg(r0), table.AB_avg(r1));
  }
  return create_rgba32f(kMu, kRough + 1, texels);
}

unsigned create_sheen_lut_texture() {
  // SheenTable's nodes, read back through E and lobe_mean at each node (bilinear
  // interpolation at a node is the node's value), so the GLSL interpolates the C++ table's
  // own numbers. Rows 0..ny-1: texel (i, j) holds E's cell's four corners E(i, j),
  // E(i + 1, j), E(i, j + 1), E(i + 1, j + 1) (clamped at the last node). Rows ny..2 ny - 1:
  // texel (i, ny + j) holds the lobe's mean (along t, along n) at nodes (i, j) and (i + 1, j),
  // so a lookup reads rows ny + j and ny + j + 1. Rows 2 ny..3 ny - 1: E_max_avg's corners
  // as E's. Rows 3 ny..4 ny - 1: the second moments (tt, nn) at (i, j) and (i + 1, j), as
  // the mean's. Rows 4 ny..5 ny - 1: the second moment tn's corners as E's. One texture: the
  // sheen's image-based light needs no texture unit of its own.
  const int nx = SheenTable::kMuSize, ny = SheenTable::kRoughnessSize;
  const SheenTable& table = SheenTable::get();
  auto at = [&](int i, int j) {
    const float t = float(std::min(i, nx - 1)) / float(nx - 1);
    const float u = float(std::min(j, ny - 1)) / float(ny - 1);
    return glm::vec2(t * t, kMinSheenRoughness + (1.0f - kMinSheenRoughness) * u * u);
  };
  auto e = [&](int i, int j) { return table.E(at(i, j).x, at(i, j).y); };
  auto e_max = [&](int i, int j) { return table.E_max_avg(at(i, j).x, at(i, j).y); };
  auto mean = [&](int i, int j) { return table.lobe_mean(at(i, j).x, at(i, j).y); };
  auto second = [&](int i, int j) { return table.lobe_second_moments(at(i, j).x, at(i, j).y); };
  std::vector<float> texels(std::size_t(nx) * ny * 5 * 4);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      float* t = &texels[(std::size_t(j) * nx + std::size_t(i)) * 4];
      t[0] = e(i, j), t[1] = e(i + 1, j), t[2] = e(i, j + 1), t[3] = e(i + 1, j + 1);
      float* m = &texels[(std::size_t(ny + j) * nx + std::size_t(i)) * 4];
      const glm::vec2 m0 = mean(i, j), m1 = mean(i + 1, j);
      m[0] = m0.x, m[1] = m0.y, m[2] = m1.x, m[3] = m1.y;
      float* a = &texels[(std::size_t(2 * ny + j) * nx + std::size_t(i)) * 4];
      a[0] = e_max(i, j), a[1] = e_max(i + 1, j), a[2] = e_max(i, j + 1),
      a[3] = e_max(i + 1, j + 1);
      float* q = &texels[(std::size_t(3 * ny + j) * nx + std::size_t(i)) * 4];
      const glm::vec3 q0 = second(i, j), q1 = second(i + 1, j);
      q[0] = q0.x, q[1] = q0.y, q[2] = q1.x, q[3] = q1.y;
      float* c = &texels[(std::size_t(4 * ny + j) * nx + std::size_t(i)) * 4];
      c[0] = q0.z, c[1] = q1.z, c[2] = second(i, j + 1).z, c[3] = second(i + 1, j + 1).z;
    }
  return create_rgba32f(nx, 5 * ny, texels);
}

unsigned create_anisotropic_albedo_texture() {
  using Table = AnisotropicAlbedoTable;
  const Table& table = Table::get();
  constexpr int kDepth = Table::kR * (Table::kS - 1);
  std::vector<float> texels(std::size_t(Table::kMu) * Table::kPhi * kDepth * 2);
  for (int l = 0; l + 1 < Table::kS; ++l)
    for (int k = 0; k < Table::kR; ++k)
      for (int j = 0; j < Table::kPhi; ++j)
        for (int i = 0; i < Table::kMu; ++i) {
          float* t = &texels[((std::size_t(l * Table::kR + k) * Table::kPhi + std::size_t(j)) *
                                  Table::kMu +
                              std::size_t(i)) *
                             2];
          t[0] = table.node(i, j, k, l);
          t[1] = table.node(i, j, k, l + 1);
        }
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_3D, 1, &texture);
  glTextureStorage3D(texture, 1, GL_RG32F, Table::kMu, Table::kPhi, kDepth);
  glTextureSubImage3D(texture, 0, 0, 0, 0, Table::kMu, Table::kPhi, kDepth, GL_RG, GL_FLOAT,
                      texels.data());
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  return texture;
}

unsigned create_anisotropic_energy_texture() {
  using T = AnisotropicEnergyTable;
  const std::vector<float>& v = T::get().values();
  constexpr int kWidth = 2 * T::kMu, kDepth = T::kR * T::kS + 1;
  static_assert(kWidth >= T::kR && T::kPhi >= T::kS, "the last slice holds the averages");
  std::vector<float> texels(std::size_t(kWidth) * T::kPhi * kDepth * 4, 0.0f);
  auto texel = [&](int x, int y, int z) {
    return &texels[((std::size_t(z) * T::kPhi + std::size_t(y)) * kWidth + std::size_t(x)) * 4];
  };
  // A node's (E_ss, h, E_tot), its index clamped to the table.
  auto node = [&](int i, int j, int k, int l) {
    return &v[3 * T::index(std::min(i, T::kMu - 1), j, std::min(k, T::kR - 1), l)];
  };
  for (int l = 0; l < T::kS; ++l)
    for (int k = 0; k < T::kR; ++k)
      for (int j = 0; j < T::kPhi; ++j)
        for (int i = 0; i < T::kMu; ++i) {
          const float *n0 = node(i, j, k, l), *n1 = node(i + 1, j, k, l);
          float* a = texel(2 * i, j, l * T::kR + k);
          a[0] = n0[1], a[1] = n0[2], a[2] = n1[1], a[3] = n1[2];
          float* b = texel(2 * i + 1, j, l * T::kR + k);
          b[0] = n0[0], b[1] = n1[0];
        }
  // (E_ss_avg, E_tot_avg) of slice (k, l), at (l kR + k) after the nodes.
  auto average = [&](int k, int l) {
    return &v[3 * T::kNodes + 2 * (std::size_t(l) * T::kR + std::size_t(std::min(k, T::kR - 1)))];
  };
  for (int l = 0; l < T::kS; ++l)
    for (int k = 0; k < T::kR; ++k) {
      const float *a0 = average(k, l), *a1 = average(k + 1, l);
      float* t = texel(k, l, kDepth - 1);
      t[0] = a0[1], t[1] = a1[1], t[2] = a0[0], t[3] = a1[0];
    }
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_3D, 1, &texture);
  glTextureStorage3D(texture, 1, GL_RGBA32F, kWidth, T::kPhi, kDepth);
  glTextureSubImage3D(texture, 0, 0, 0, 0, kWidth, T::kPhi, kDepth, GL_RGBA, GL_FLOAT,
                      texels.data());
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  return texture;
}

}  // namespace pbrkit::gl
