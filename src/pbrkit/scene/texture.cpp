// Texture storage, filtering and mip chains, following the glTF sampler model (OpenGL
// semantics): texel centres at (i + 0.5) / size, uv origin at the top-left texel. Texels
// stay at the source's precision; 8-bit sRGB is decoded through a table, as GL_SRGB8_ALPHA8
// is decoded before filtering (OpenGL 4.6 section 8.24).
#include <algorithm>
#include <array>
#include <cmath>

#include "pbrkit/core/color.h"
#include "pbrkit/scene/scene.h"
#include "pbrkit/util/error.h"

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

// Colour channels of a `channels`-channel texel: grey or RGB; the last of 2 or 4 is alpha.
int colour_channels(int channels) {
  return channels == 2 || channels == 4 ? channels - 1 : channels;
}

// The 8-bit decode tables: the exact sRGB decode (IEC 61966-2-1) of every byte, and the
// plain unorm value byte / 255 (OpenGL's UNORM conversion).
const std::array<float, 256>& srgb8_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int v = 0; v < 256; ++v) t[std::size_t(v)] = srgb_decode(float(v) / 255.0f);
    return t;
  }();
  return table;
}

const std::array<float, 256>& unorm8_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int v = 0; v < 256; ++v) t[std::size_t(v)] = float(v) / 255.0f;
    return t;
  }();
  return table;
}

// The linear values of the `t.channels` samples starting at sample index `i`.
void read_samples(const Texture& t, std::size_t i, float* out) {
  const int colour = colour_channels(t.channels);
  switch (t.format) {
    case TexelFormat::kUnorm8: {
      const float* c = t.srgb ? srgb8_table().data() : unorm8_table().data();
      const float* a = unorm8_table().data();
      const std::uint8_t* p = t.texels8.data() + i;
      for (int k = 0; k < t.channels; ++k) out[k] = (k < colour ? c : a)[p[k]];
      return;
    }
    case TexelFormat::kUnorm16: {
      const std::uint16_t* p = t.texels16.data() + i;
      for (int k = 0; k < t.channels; ++k) {
        const float v = float(p[k]) / 65535.0f;
        out[k] = k < colour && t.srgb ? srgb_decode(v) : v;
      }
      return;
    }
    case TexelFormat::kFloat32:
    default:
      for (int k = 0; k < t.channels; ++k) out[k] = t.texels32[i + std::size_t(k)];
  }
}

// Stores linear `values` as the samples at index `i`, re-encoding to the texture's format
// (sRGB for colour channels of integer colour textures), rounded to nearest.
void write_samples(Texture& t, std::size_t i, const float* values) {
  const int colour = colour_channels(t.channels);
  for (int k = 0; k < t.channels; ++k) {
    float v = values[k];
    if (t.format == TexelFormat::kFloat32) {
      t.texels32[i + std::size_t(k)] = v;
      continue;
    }
    v = std::clamp(v, 0.0f, 1.0f);
    if (k < colour && t.srgb) v = std::clamp(srgb_encode(v), 0.0f, 1.0f);
    if (t.format == TexelFormat::kUnorm8)
      t.texels8[i + std::size_t(k)] = std::uint8_t(std::lround(v * 255.0f));
    else
      t.texels16[i + std::size_t(k)] = std::uint16_t(std::lround(v * 65535.0f));
  }
}

// RGBA from 1 (grey), 2 (grey, alpha), 3 (RGB) or 4 samples, as OpenGL expands luminance.
glm::vec4 expand(const float* v, int channels) {
  switch (channels) {
    case 1:
      return {v[0], v[0], v[0], 1.0f};
    case 2:
      return {v[0], v[0], v[0], v[1]};
    case 3:
      return {v[0], v[1], v[2], 1.0f};
    default:
      return {v[0], v[1], v[2], v[3]};
  }
}

std::size_t sample_index(const Texture& t, const TextureLevel& l, int x, int y) {
  return l.offset +
         (std::size_t(y) * std::size_t(l.width) + std::size_t(x)) * std::size_t(t.channels);
}

// The mip chain's sizes (each level halves, rounding down, to 1x1) and offsets.
std::vector<TextureLevel> mip_layout(int width, int height, int channels) {
  std::vector<TextureLevel> levels;
  std::size_t offset = 0;
  while (true) {
    levels.push_back({width, height, offset});
    offset += std::size_t(width) * std::size_t(height) * std::size_t(channels);
    if (width == 1 && height == 1) break;
    width = std::max(1, width / 2);
    height = std::max(1, height / 2);
  }
  return levels;
}

std::size_t total_samples(const std::vector<TextureLevel>& levels, int channels) {
  const TextureLevel& last = levels.back();
  return last.offset + std::size_t(last.width) * std::size_t(last.height) * std::size_t(channels);
}

void check_shape(int width, int height, int channels, std::size_t samples) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4)
    fail("texture: invalid size {} x {} with {} channels", width, height, channels);
  if (samples != std::size_t(width) * std::size_t(height) * std::size_t(channels))
    fail("texture: {} samples for {} x {} x {}", samples, width, height, channels);
}

// Fills levels 1.. from level 0. Box filter in linear space: each texel of level k+1
// averages the (up to) 2x2 texels it covers in level k (an odd last row/column is dropped,
// like the usual GPU box filter), decoded from and re-encoded to the texture's format.
void build_mips(Texture& t) {
  float a[4], b[4], c[4], d[4], out[4];
  for (std::size_t k = 1; k < t.levels.size(); ++k) {
    const TextureLevel& src = t.levels[k - 1];
    const TextureLevel& dst = t.levels[k];
    for (int y = 0; y < dst.height; ++y) {
      const int y0 = std::min(2 * y, src.height - 1);
      const int y1 = (src.height == 1) ? y0 : std::min(2 * y + 1, src.height - 1);
      for (int x = 0; x < dst.width; ++x) {
        const int x0 = std::min(2 * x, src.width - 1);
        const int x1 = (src.width == 1) ? x0 : std::min(2 * x + 1, src.width - 1);
        read_samples(t, sample_index(t, src, x0, y0), a);
        read_samples(t, sample_index(t, src, x1, y0), b);
        read_samples(t, sample_index(t, src, x0, y1), c);
        read_samples(t, sample_index(t, src, x1, y1), d);
        for (int ch = 0; ch < t.channels; ++ch) out[ch] = 0.25f * (a[ch] + b[ch] + c[ch] + d[ch]);
        write_samples(t, sample_index(t, dst, x, y), out);
      }
    }
  }
}

glm::vec4 texel_wrapped(const Texture& t, const TextureLevel& l, int x, int y) {
  x = wrap_index(x, l.width, t.sampler.wrap_s);
  y = wrap_index(y, l.height, t.sampler.wrap_t);
  float v[4];
  read_samples(t, sample_index(t, l, x, y), v);
  return expand(v, t.channels);
}

glm::vec4 sample_level(const Texture& t, const TextureLevel& l, glm::vec2 uv, FilterMode filter) {
  const float fx = tame(uv.x) * float(l.width);
  const float fy = tame(uv.y) * float(l.height);
  if (filter == FilterMode::kNearest)
    return texel_wrapped(t, l, int(std::floor(fx)), int(std::floor(fy)));
  const float x = fx - 0.5f, y = fy - 0.5f;
  const float x0f = std::floor(x), y0f = std::floor(y);
  const float tx = x - x0f, ty = y - y0f;
  const int x0 = int(x0f), y0 = int(y0f);
  const glm::vec4 a = texel_wrapped(t, l, x0, y0), b = texel_wrapped(t, l, x0 + 1, y0);
  const glm::vec4 c = texel_wrapped(t, l, x0, y0 + 1), d = texel_wrapped(t, l, x0 + 1, y0 + 1);
  return (a * (1.0f - tx) + b * tx) * (1.0f - ty) + (c * (1.0f - tx) + d * tx) * ty;
}

}  // namespace

Texture Texture::from_linear(Image level0, bool srgb) {
  check_shape(level0.width, level0.height, level0.channels, level0.data.size());
  Texture t;
  t.srgb = srgb;
  t.format = TexelFormat::kFloat32;
  t.channels = level0.channels;
  t.levels = mip_layout(level0.width, level0.height, level0.channels);
  t.texels32 = std::move(level0.data);
  t.texels32.resize(total_samples(t.levels, t.channels));
  t.texels32.shrink_to_fit();
  build_mips(t);
  return t;
}

Texture Texture::from_unorm8(int width, int height, int channels, std::vector<std::uint8_t> samples,
                             bool srgb) {
  check_shape(width, height, channels, samples.size());
  Texture t;
  t.srgb = srgb;
  t.format = TexelFormat::kUnorm8;
  t.channels = channels;
  t.levels = mip_layout(width, height, channels);
  t.texels8 = std::move(samples);
  t.texels8.resize(total_samples(t.levels, t.channels));
  t.texels8.shrink_to_fit();
  build_mips(t);
  return t;
}

Texture Texture::from_unorm16(int width, int height, int channels,
                              std::vector<std::uint16_t> samples, bool srgb) {
  check_shape(width, height, channels, samples.size());
  Texture t;
  t.srgb = srgb;
  t.format = TexelFormat::kUnorm16;
  t.channels = channels;
  t.levels = mip_layout(width, height, channels);
  t.texels16 = std::move(samples);
  t.texels16.resize(total_samples(t.levels, t.channels));
  t.texels16.shrink_to_fit();
  build_mips(t);
  return t;
}

std::size_t Texture::bytes() const {
  return texels8.capacity() * sizeof(std::uint8_t) + texels16.capacity() * sizeof(std::uint16_t) +
         texels32.capacity() * sizeof(float) + levels.capacity() * sizeof(TextureLevel);
}

glm::vec4 Texture::texel(int level, int x, int y) const {
  const TextureLevel& l = levels[std::size_t(level)];
  float v[4];
  read_samples(*this, sample_index(*this, l, x, y), v);
  return expand(v, channels);
}

Image Texture::level_image(int level) const {
  const TextureLevel& l = levels[std::size_t(level)];
  Image image(l.width, l.height, 4);
  for (int y = 0; y < l.height; ++y)
    for (int x = 0; x < l.width; ++x) {
      const glm::vec4 v = texel(level, x, y);
      float* p = image.pixel(x, y);
      for (int c = 0; c < 4; ++c) p[c] = v[c];
    }
  return image;
}

float Texture::min_alpha() const {
  if (levels.empty() || (channels != 2 && channels != 4)) return 1.0f;
  const TextureLevel& l = levels[0];
  float lowest = 1.0f, v[4];
  for (std::size_t i = 0; i < std::size_t(l.width) * std::size_t(l.height); ++i) {
    read_samples(*this, l.offset + i * std::size_t(channels), v);
    lowest = std::min(lowest, v[channels - 1]);
  }
  return lowest;
}

glm::vec4 Texture::sample(glm::vec2 uv, float lod) const {
  if (levels.empty()) return glm::vec4(1.0f);
  if (!(lod > 0.0f) || levels.size() == 1 || !sampler.min_mipmap) {
    const FilterMode filter = lod > 0.0f ? sampler.min : sampler.mag;
    return sample_level(*this, levels[0], uv, filter);
  }
  const float max_level = float(levels.size() - 1);
  const float l = std::min(lod, max_level);
  const int l0 = int(std::floor(l));
  const int l1 = std::min(l0 + 1, int(levels.size()) - 1);
  const float t = l - float(l0);
  const glm::vec4 a = sample_level(*this, levels[std::size_t(l0)], uv, sampler.min);
  if (t <= 0.0f || l1 == l0) return a;
  const glm::vec4 b = sample_level(*this, levels[std::size_t(l1)], uv, sampler.min);
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

}  // namespace pbrkit
