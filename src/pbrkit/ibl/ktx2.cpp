// KTX 2.0 writer and reader (KTX File Format Specification 2.0, sections 3-4; the data
// format descriptor per the Khronos Data Format Specification 1.3, section 5).
#include "pbrkit/ibl/ktx2.h"

#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numeric>

#include "pbrkit/util/atomic_file.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

constexpr std::array<std::uint8_t, 12> kIdentifier = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32,
                                                      0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::size_t kHeaderSize = 80;      // identifier + 9 u32 + index (4 u32 + 2 u64)
constexpr std::size_t kLevelEntrySize = 24;  // byteOffset, byteLength, uncompressedByteLength
constexpr std::uint32_t kDfdBlockSize = 24 + 16 * 4;  // basic block, 4 samples

std::size_t align_up(std::size_t x, std::size_t a) {
  return (x + a - 1) / a * a;
}

void put32(std::string& out, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out[at + i] = char((v >> (8 * i)) & 0xFF);
}
void put64(std::string& out, std::size_t at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out[at + i] = char((v >> (8 * i)) & 0xFF);
}
void append32(std::string& out, std::uint32_t v) {
  out.resize(out.size() + 4);
  put32(out, out.size() - 4, v);
}
std::uint32_t get32(const std::string& in, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t(std::uint8_t(in[at + i])) << (8 * i);
  return v;
}
std::uint64_t get64(const std::string& in, std::size_t at) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= std::uint64_t(std::uint8_t(in[at + i])) << (8 * i);
  return v;
}

std::uint32_t float_bits(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

// The basic data format descriptor of an RGBA float format (KDFS 1.3, section 5.6):
// colour model RGBSDA, BT.709 primaries, linear transfer, straight alpha, one plane of
// `texel` bytes, four samples R, G, B, A of `bits` bits each, typed SIGNED | FLOAT with
// sampleLower = -1.0f and sampleUpper = 1.0f (the convention for float formats, section
// 5.18 / the KTX-Software vk2dfd tables).
std::string basic_dfd(Ktx2Format format) {
  const std::uint32_t texel = std::uint32_t(ktx2_texel_bytes(format));
  const std::uint32_t bits = texel * 2;  // 16 or 32 per channel
  std::string d;
  append32(d, 4 + kDfdBlockSize);           // dfdTotalSize
  append32(d, 0);                           // vendorId 0 (Khronos) | descriptorType 0 (basic) << 17
  append32(d, 2u | (kDfdBlockSize << 16));  // versionNumber 2 (KDFS 1.3) | descriptorBlockSize
  append32(d, 1u | (1u << 8) | (1u << 16) | (0u << 24));  // RGBSDA, BT709, LINEAR, flags 0
  append32(d, 0);      // texelBlockDimension0..3 = 1x1x1x1 (stored minus one)
  append32(d, texel);  // bytesPlane0
  append32(d, 0);      // bytesPlane4..7
  const std::uint32_t channel_ids[4] = {0, 1, 2, 15};  // R, G, B, A (KHR_DF_CHANNEL_RGBSDA_*)
  for (int c = 0; c < 4; ++c) {
    const std::uint32_t qualifiers = 0x80 | 0x40;  // KHR_DF_SAMPLE_DATATYPE_FLOAT | SIGNED
    append32(d, (bits * c) | ((bits - 1) << 16) | ((channel_ids[c] | qualifiers) << 24));
    append32(d, 0);  // samplePosition0..3
    append32(d, float_bits(-1.0f));
    append32(d, float_bits(1.0f));
  }
  return d;
}

std::uint32_t level_size(std::uint32_t size, int level) {
  return std::max<std::uint32_t>(1, size >> level);
}

}  // namespace

int ktx2_texel_bytes(Ktx2Format format) {
  return format == Ktx2Format::kRgba16Float ? 8 : 16;
}

std::string encode_ktx2(const Ktx2Texture& t) {
  if (t.faces != 1 && t.faces != 6) fail("KTX2: face count must be 1 or 6, got {}", t.faces);
  if (t.levels.empty() || t.width == 0 || t.height == 0) fail("KTX2: empty texture");
  const std::size_t texel = std::size_t(ktx2_texel_bytes(t.format));
  const std::size_t n_levels = t.levels.size();
  for (std::size_t i = 0; i < n_levels; ++i) {
    const std::size_t expected =
        std::size_t(t.faces) * level_size(t.width, int(i)) * level_size(t.height, int(i)) * texel;
    if (t.levels[i].size() != expected)
      fail("KTX2: level {} has {} bytes, expected {}", i, t.levels[i].size(), expected);
  }
  // Key/value data: sorted by key, each entry {u32 length, key NUL value NUL, padding}.
  auto metadata = t.metadata;
  bool has_orientation = false;
  for (const auto& kv : metadata) has_orientation |= kv.first == "KTXorientation";
  if (!has_orientation) metadata.emplace_back("KTXorientation", "rd");
  std::sort(metadata.begin(), metadata.end());
  std::string kvd;
  for (const auto& [key, value] : metadata) {
    const std::string entry = key + '\0' + value + '\0';
    append32(kvd, std::uint32_t(entry.size()));
    kvd += entry;
    kvd.resize(align_up(kvd.size(), 4), '\0');
  }
  const std::string dfd = basic_dfd(t.format);

  const std::size_t level_index_at = kHeaderSize;
  const std::size_t dfd_at = level_index_at + kLevelEntrySize * n_levels;
  const std::size_t kvd_at = dfd_at + dfd.size();
  // Each level starts at a multiple of lcm(texel block size, 4) (spec section 3.9.7).
  const std::size_t level_align = std::lcm(texel, std::size_t(4));
  std::string out(kvd_at + kvd.size(), '\0');
  std::memcpy(out.data(), kIdentifier.data(), kIdentifier.size());
  put32(out, 12, std::uint32_t(t.format));                  // vkFormat
  put32(out, 16, std::uint32_t(texel / 4));                 // typeSize: 2 (half) or 4 (float)
  put32(out, 20, t.width);                                  // pixelWidth
  put32(out, 24, t.height);                                 // pixelHeight
  put32(out, 28, 0);                                        // pixelDepth (not 3D)
  put32(out, 32, 0);                                        // layerCount (not an array)
  put32(out, 36, t.faces);                                  // faceCount
  put32(out, 40, std::uint32_t(n_levels));                  // levelCount
  put32(out, 44, 0);                                        // supercompressionScheme: none
  put32(out, 48, std::uint32_t(dfd_at));                    // dfdByteOffset
  put32(out, 52, std::uint32_t(dfd.size()));                // dfdByteLength
  put32(out, 56, kvd.empty() ? 0 : std::uint32_t(kvd_at));  // kvdByteOffset
  put32(out, 60, std::uint32_t(kvd.size()));                // kvdByteLength
  put64(out, 64, 0);                                        // sgdByteOffset
  put64(out, 72, 0);                                        // sgdByteLength
  std::memcpy(out.data() + dfd_at, dfd.data(), dfd.size());
  std::memcpy(out.data() + kvd_at, kvd.data(), kvd.size());
  // Mip levels are stored smallest first; the level index lists level 0 first.
  for (std::size_t k = n_levels; k-- > 0;) {
    out.resize(align_up(out.size(), level_align), '\0');
    const std::size_t at = out.size();
    const auto& data = t.levels[k];
    out.append(reinterpret_cast<const char*>(data.data()), data.size());
    put64(out, level_index_at + kLevelEntrySize * k, at);
    put64(out, level_index_at + kLevelEntrySize * k + 8, data.size());
    put64(out, level_index_at + kLevelEntrySize * k + 16, data.size());
  }
  return out;
}

Ktx2Texture decode_ktx2(const std::string& in, const std::string& name) {
  if (in.size() < kHeaderSize || std::memcmp(in.data(), kIdentifier.data(), 12) != 0)
    fail("{}: not a KTX 2.0 file (missing the KTX 20 identifier)", name);
  Ktx2Texture t;
  const std::uint32_t vk_format = get32(in, 12);
  if (vk_format != 97 && vk_format != 109)
    fail(
        "{}: unsupported vkFormat {} (pbrkit reads R16G16B16A16_SFLOAT (97) and "
        "R32G32B32A32_SFLOAT (109))",
        name, vk_format);
  t.format = Ktx2Format(vk_format);
  const std::size_t texel = std::size_t(ktx2_texel_bytes(t.format));
  if (get32(in, 16) != texel / 4)
    fail("{}: typeSize {} does not match the format", name, get32(in, 16));
  t.width = get32(in, 20);
  t.height = get32(in, 24);
  const std::uint32_t depth = get32(in, 28), layers = get32(in, 32);
  t.faces = get32(in, 36);
  std::uint32_t n_levels = get32(in, 40);
  if (t.width == 0 || t.height == 0 || t.width > 65536 || t.height > 65536)
    fail("{}: invalid size {}x{}", name, t.width, t.height);
  if (depth != 0 || layers > 1) fail("{}: 3D and array textures are not supported", name);
  if (t.faces != 1 && t.faces != 6) fail("{}: faceCount must be 1 or 6, got {}", name, t.faces);
  if (t.faces == 6 && t.width != t.height) fail("{}: cubemap faces must be square", name);
  if (get32(in, 44) != 0) fail("{}: supercompressed KTX2 files are not supported", name);
  if (n_levels == 0) n_levels = 1;  // 0 = "generate mips at load": one level is stored
  if (n_levels > 32) fail("{}: levelCount {} is too large", name, n_levels);
  if (kHeaderSize + kLevelEntrySize * n_levels > in.size()) fail("{}: truncated level index", name);
  // Key/value data.
  const std::size_t kvd_at = get32(in, 56), kvd_len = get32(in, 60);
  if (kvd_at + kvd_len > in.size()) fail("{}: key/value data lies outside the file", name);
  for (std::size_t p = kvd_at; p + 4 <= kvd_at + kvd_len;) {
    const std::size_t len = get32(in, p);
    if (p + 4 + len > kvd_at + kvd_len) fail("{}: malformed key/value data", name);
    const std::string entry = in.substr(p + 4, len);
    const std::size_t nul = entry.find('\0');
    if (nul == std::string::npos) fail("{}: key/value entry without a NUL", name);
    std::string value = entry.substr(nul + 1);
    if (!value.empty() && value.back() == '\0') value.pop_back();
    t.metadata.emplace_back(entry.substr(0, nul), value);
    p = align_up(p + 4 + len, 4);
  }
  for (const auto& [key, value] : t.metadata)
    if (key == "KTXorientation" && value.substr(0, 2) != "rd")
      fail("{}: KTXorientation '{}' is not supported (pbrkit reads 'rd')", name, value);
  for (std::uint32_t i = 0; i < n_levels; ++i) {
    const std::size_t at = kHeaderSize + kLevelEntrySize * i;
    const std::uint64_t offset = get64(in, at), length = get64(in, at + 8);
    const std::uint64_t expected =
        std::uint64_t(t.faces) * level_size(t.width, int(i)) * level_size(t.height, int(i)) * texel;
    if (length != expected)
      fail("{}: level {} has {} bytes, expected {} for {}x{}", name, i, length, expected,
           level_size(t.width, int(i)), level_size(t.height, int(i)));
    if (get64(in, at + 16) != length) fail("{}: level {} uncompressed length mismatch", name, i);
    if (offset > in.size() || length > in.size() - offset)
      fail("{}: level {} lies outside the file (truncated?)", name, i);
    t.levels.emplace_back(in.begin() + std::ptrdiff_t(offset),
                          in.begin() + std::ptrdiff_t(offset + length));
  }
  return t;
}

void write_ktx2(const std::filesystem::path& path, const Ktx2Texture& texture) {
  write_bytes_atomically(path, encode_ktx2(texture));
}

Ktx2Texture read_ktx2(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) fail("{}: cannot open for reading", path.string());
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return decode_ktx2(bytes, path.string());
}

namespace {

void encode_texels(const Image& img, Ktx2Format format, std::vector<std::uint8_t>& out) {
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float* p = img.pixel(x, y);
      float rgba[4] = {0.0f, 0.0f, 0.0f, 1.0f};
      for (int c = 0; c < std::min(img.channels, 4); ++c) rgba[c] = p[c];
      if (img.channels == 1) rgba[1] = rgba[2] = rgba[0];
      for (float v : rgba) {
        if (format == Ktx2Format::kRgba16Float) {
          const std::uint16_t h = Imath::half(v).bits();
          out.push_back(std::uint8_t(h & 0xFF));
          out.push_back(std::uint8_t(h >> 8));
        } else {
          const std::uint32_t u = float_bits(v);
          for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t((u >> (8 * i)) & 0xFF));
        }
      }
    }
}

Image decode_texels(const std::uint8_t* data, int w, int h, Ktx2Format format) {
  Image img(w, h, 4);
  for (std::size_t i = 0; i < img.data.size(); ++i) {
    if (format == Ktx2Format::kRgba16Float) {
      Imath::half half;
      half.setBits(std::uint16_t(data[2 * i] | (data[2 * i + 1] << 8)));
      img.data[i] = float(half);
    } else {
      std::uint32_t u = 0;
      for (int k = 0; k < 4; ++k) u |= std::uint32_t(data[4 * i + k]) << (8 * k);
      std::memcpy(&img.data[i], &u, 4);
    }
  }
  return img;
}

}  // namespace

Ktx2Texture ktx2_from_cubemap(const Cubemap& cube, Ktx2Format format) {
  Ktx2Texture t;
  t.format = format;
  t.width = t.height = std::uint32_t(cube.size(0));
  t.faces = 6;
  for (const auto& level : cube.mips) {
    std::vector<std::uint8_t> bytes;
    for (const Image& face : level) encode_texels(face, format, bytes);
    t.levels.push_back(std::move(bytes));
  }
  return t;
}

Cubemap cubemap_from_ktx2(const Ktx2Texture& t) {
  if (t.faces != 6) fail("KTX2: expected a cubemap (6 faces), got {} face(s)", t.faces);
  Cubemap cube;
  const std::size_t texel = std::size_t(ktx2_texel_bytes(t.format));
  for (std::size_t i = 0; i < t.levels.size(); ++i) {
    const int size = int(level_size(t.width, int(i)));
    std::array<Image, 6> faces;
    for (int f = 0; f < 6; ++f)
      faces[f] = decode_texels(t.levels[i].data() + std::size_t(f) * size * size * texel, size,
                               size, t.format);
    cube.mips.push_back(std::move(faces));
  }
  return cube;
}

Ktx2Texture ktx2_from_image(const Image& image, Ktx2Format format) {
  Ktx2Texture t;
  t.format = format;
  t.width = std::uint32_t(image.width);
  t.height = std::uint32_t(image.height);
  t.faces = 1;
  t.levels.emplace_back();
  encode_texels(image, format, t.levels.back());
  return t;
}

Image image_from_ktx2(const Ktx2Texture& t, int level) {
  if (level < 0 || std::size_t(level) >= t.levels.size())
    fail("KTX2: level {} does not exist ({} levels)", level, t.levels.size());
  return decode_texels(t.levels[level].data(), int(level_size(t.width, level)),
                       int(level_size(t.height, level)), t.format);
}

}  // namespace pbrkit
