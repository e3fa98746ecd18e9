#include "pbrkit/gl/energy_texture.h"

#include <cmath>
#include <vector>

#include <epoxy/gl.h>

#include "pbrkit/core/energy.h"
#include "pbrkit/core/sheen.h"

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

}  // namespace

unsigned create_energy_texture(GeometryModel model) {
  const EnergyTable& table = EnergyTable::get(model);
  constexpr int kMu = EnergyTable::kMuSize, kRough = EnergyTable::kRoughnessSize;
  static_assert(kMu >= kRough, "row kRough holds the averages, one per roughness node");
  std::vector<float> texels(std::size_t(kMu) * (kRough + 1) * 2, 0.0f);
  for (int j = 0; j < kRough; ++j) {
    const float r = node_coordinate(j, kRough);
    for (int i = 0; i < kMu; ++i) {
      // At a node the table's interpolation returns the node value (up to rounding).
      const glm::vec2 ab = table.AB(node_coordinate(i, kMu), r);
      texels[(std::size_t(j) * kMu + i) * 2 + 0] = ab.x;
      texels[(std::size_t(j) * kMu + i) * 2 + 1] = ab.y;
    }
    const glm::vec2 avg = table.AB_avg(r);
    texels[(std::size_t(kRough) * kMu + j) * 2 + 0] = avg.x;
    texels[(std::size_t(kRough) * kMu + j) * 2 + 1] = avg.y;
  }
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RG32F, kMu, kRough + 1);
  glTextureSubImage2D(texture, 0, 0, 0, kMu, kRough + 1, GL_RG, GL_FLOAT, texels.data());
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

unsigned create_sheen_lut_texture() {
  // SheenTable's nodes, read back through E at each node (bilinear interpolation at a node
  // is the node's value), so the GLSL interpolates the C++ table's own numbers.
  const int nx = SheenTable::kMuSize, ny = SheenTable::kRoughnessSize;
  std::vector<float> texels(std::size_t(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const float t = float(i) / float(nx - 1), u = float(j) / float(ny - 1);
      texels[std::size_t(j) * nx + i] =
          SheenTable::get().E(t * t, kMinSheenRoughness + (1.0f - kMinSheenRoughness) * u * u);
    }
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_R32F, nx, ny);
  glTextureSubImage2D(texture, 0, 0, 0, nx, ny, GL_RED, GL_FLOAT, texels.data());
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

}  // namespace pbrkit::gl
