// Texture filtering and mip chains, following the glTF sampler model (OpenGL semantics):
// texel centres at (i + 0.5) / size, uv origin at the top-left texel.
#include <algorithm>
#include <cmath>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

namespace {

int wrap_index(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::kClampToEdge:
      return std::clamp(i, 0, n - 1);
    case WrapMode::kMirroredRepeat: {
      const int period = 2 * n;
      int k = i % period;
      if (k < 0) k += period;
      return k < n ? k : period - 1 - k;
    }
    case WrapMode::kRepeat:
    default: {
      int k = i % n;
      return k < 0 ? k + n : k;
    }
  }
}

// Converts a texture coordinate to a (wrapped) continuous position without overflowing int
// for huge or non-finite coordinates.
float tame(float u) {
  if (!std::isfinite(u)) return 0.0f;
  // Repeat and mirror are periodic with period 2 in uv; keep the fractional part.
  if (std::fabs(u) > 1024.0f) u = std::fmod(u, 2.0f);
  return u;
}

glm::vec4 texel(const Image& image, int x, int y, const Sampler& s) {
  x = wrap_index(x, image.width, s.wrap_s);
  y = wrap_index(y, image.height, s.wrap_t);
  const float* p = image.pixel(x, y);
  return {p[0], p[1], p[2], p[3]};
}

glm::vec4 sample_level(const Image& image, glm::vec2 uv, FilterMode filter, const Sampler& s) {
  const float fx = tame(uv.x) * float(image.width);
  const float fy = tame(uv.y) * float(image.height);
  if (filter == FilterMode::kNearest)
    return texel(image, int(std::floor(fx)), int(std::floor(fy)), s);
  const float x = fx - 0.5f, y = fy - 0.5f;
  const float x0f = std::floor(x), y0f = std::floor(y);
  const float tx = x - x0f, ty = y - y0f;
  const int x0 = int(x0f), y0 = int(y0f);
  const glm::vec4 a = texel(image, x0, y0, s), b = texel(image, x0 + 1, y0, s);
  const glm::vec4 c = texel(image, x0, y0 + 1, s), d = texel(image, x0 + 1, y0 + 1, s);
  return (a * (1.0f - tx) + b * tx) * (1.0f - ty) + (c * (1.0f - tx) + d * tx) * ty;
}

}  // namespace

glm::vec4 Texture::sample(glm::vec2 uv, float lod) const {
  if (mips.empty()) return glm::vec4(1.0f);
  if (!(lod > 0.0f) || mips.size() == 1 || !sampler.min_mipmap) {
    const FilterMode filter = lod > 0.0f ? sampler.min : sampler.mag;
    return sample_level(mips[0], uv, filter, sampler);
  }
  const float max_level = float(mips.size() - 1);
  const float l = std::min(lod, max_level);
  const int l0 = int(std::floor(l));
  const int l1 = std::min(l0 + 1, int(mips.size()) - 1);
  const float t = l - float(l0);
  const glm::vec4 a = sample_level(mips[std::size_t(l0)], uv, sampler.min, sampler);
  if (t <= 0.0f || l1 == l0) return a;
  const glm::vec4 b = sample_level(mips[std::size_t(l1)], uv, sampler.min, sampler);
  return a * (1.0f - t) + b * t;
}

glm::mat3 TextureTransform::matrix() const {
  // KHR_texture_transform: uv' = T * R * S * uv, with the rotation that makes the
  // extension's example (offset [0,1], rotation pi/2, scale 0.5) select the lower-left
  // quadrant: u' = cos(r) u + sin(r) v, v' = -sin(r) u + cos(r) v. glm is column-major.
  const float c = std::cos(rotation), s = std::sin(rotation);
  const glm::mat3 t(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
  const glm::mat3 r(c, -s, 0, s, c, 0, 0, 0, 1);
  const glm::mat3 sc(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  return t * r * sc;
}

std::vector<Image> make_mip_chain(Image level0) {
  std::vector<Image> mips;
  mips.push_back(std::move(level0));
  // Box filter in linear space: each texel of level k+1 averages the (up to) 2x2 texels
  // it covers in level k (an odd last row/column is dropped, like the usual GPU box filter).
  while (mips.back().width > 1 || mips.back().height > 1) {
    const Image& src = mips.back();
    const int w = std::max(1, src.width / 2), h = std::max(1, src.height / 2);
    Image dst(w, h, src.channels);
    for (int y = 0; y < h; ++y) {
      const int y0 = std::min(2 * y, src.height - 1);
      const int y1 = (src.height == 1) ? y0 : std::min(2 * y + 1, src.height - 1);
      for (int x = 0; x < w; ++x) {
        const int x0 = std::min(2 * x, src.width - 1);
        const int x1 = (src.width == 1) ? x0 : std::min(2 * x + 1, src.width - 1);
        float* out = dst.pixel(x, y);
        for (int c = 0; c < src.channels; ++c)
          out[c] = 0.25f * (src.pixel(x0, y0)[c] + src.pixel(x1, y0)[c] + src.pixel(x0, y1)[c] +
                            src.pixel(x1, y1)[c]);
      }
    }
    mips.push_back(std::move(dst));
  }
  return mips;
}

}  // namespace pbrkit
