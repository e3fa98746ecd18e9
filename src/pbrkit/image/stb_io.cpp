// PNG, JPEG and Radiance HDR decoding through stb_image (Debian's libstb holds the
// implementation), with the structure checks it lacks; headers read without decoding;
// 8/16-bit samples kept as stored; Radiance HDR writing (image_io.h).
#include "pbrkit/image/image_io.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <string_view>

#include "image_formats.h"
#include "pbrkit/core/color.h"
#include "pbrkit/util/atomic_file.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit {

using namespace image_detail;

namespace {

// Checks that the pixel data of a Radiance .hdr file is complete and well formed before
// stb_image decodes it: stb's run-length decoder loops forever on a zero run length, which
// is exactly what it reads past the end of a truncated file. Mirrors the format as stb reads
// it (Greg Ward's new-style RLE scanlines, or flat RGBE when the first scanline is not RLE).
void check_hdr_data(const unsigned char* b, std::size_t size, int width, int height,
                    const std::string& name) {
  const std::string_view text(reinterpret_cast<const char*>(b), size);
  const auto blank = text.find("\n\n");
  const auto eol = blank == std::string_view::npos ? blank : text.find('\n', blank + 2);
  if (eol == std::string_view::npos) fail("{}: Radiance HDR header is incomplete", name);
  std::size_t pos = eol + 1;
  auto truncated = [&] { fail("{}: Radiance HDR pixel data is truncated", name); };
  auto corrupt = [&] { fail("{}: Radiance HDR pixel data is corrupt (bad run length)", name); };
  const std::size_t w = static_cast<std::size_t>(width);
  for (int row = 0; row < height; ++row) {
    if (size - pos < 4) truncated();
    const bool rle = b[pos] == 2 && b[pos + 1] == 2 && !(b[pos + 2] & 0x80);
    if (row == 0 && (!rle || width < 8 || width >= 32768)) {
      // Flat RGBE: 4 bytes per pixel for the whole image.
      if ((size - pos) / 4 / w < static_cast<std::size_t>(height)) truncated();
      return;
    }
    if (!rle || ((std::size_t(b[pos + 2]) << 8) | b[pos + 3]) != w) corrupt();
    pos += 4;
    for (int k = 0; k < 4; ++k)
      for (std::size_t i = 0; i < w;) {
        if (pos >= size) truncated();
        std::size_t count = b[pos++];
        if (count > 128) {
          count -= 128;
          if (pos >= size) truncated();
          ++pos;
        } else {
          if (size - pos < count) truncated();
          pos += count;
        }
        if (count == 0 || count > w - i) corrupt();
        i += count;
      }
  }
}

// PNG, JPEG and Radiance HDR through stb_image (Debian's libstb holds the implementation).
// Checks a PNG's chunk structure before stb_image sees it: stb grows its IDAT buffer to a
// chunk's declared length before reading the chunk, so a 98-byte file declaring a 1.6 GB
// IDAT made it allocate that much (found by fuzz_image). Every chunk (4-byte big-endian
// length, type, data, CRC; PNG specification section 5.3) must lie inside the file, up to
// IEND.
void check_png_chunks(const unsigned char* b, std::size_t n, const std::string& name) {
  std::size_t pos = 8;  // after the signature
  while (true) {
    if (n - pos < 12) fail("{}: PNG is truncated (no IEND chunk)", name);
    const std::size_t length = std::size_t(b[pos]) << 24 | std::size_t(b[pos + 1]) << 16 |
                               std::size_t(b[pos + 2]) << 8 | std::size_t(b[pos + 3]);
    if (length > n - pos - 12)
      fail("{}: PNG chunk '{}' declares {} bytes, past the end of the file", name,
           std::string(reinterpret_cast<const char*>(b + pos + 4), 4), length);
    if (std::memcmp(b + pos + 4, "IEND", 4) == 0) return;
    pos += 12 + length;
  }
}

}  // namespace

namespace image_detail {

Image decode_stb(const unsigned char* bytes, std::size_t size, const std::string& name,
                 Format format, const ImageReadOptions& options, ImageReadReport& report) {
  if (size > static_cast<std::size_t>(INT32_MAX)) fail("{}: file is too large", name);
  const int len = static_cast<int>(size);
  if (format == Format::kPng) check_png_chunks(bytes, size, name);
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(bytes, len, &w, &h, &comp))
    fail("{}: cannot read image header: {}", name, stbi_failure_reason());
  check_size(name, w, h, options);
  Image image;
  auto decode_channel_count = [&](int channels) {
    // sRGB applies to colour channels only: grey (1, 2) or RGB (3, 4); never alpha.
    return channels == 2 || channels == 4 ? channels - 1 : channels;
  };
  if (format == Format::kHdr) {
    check_hdr_data(bytes, size, w, h, name);
    float* data = stbi_loadf_from_memory(bytes, len, &w, &h, &comp, 0);
    if (!data) fail("{}: cannot decode Radiance HDR: {}", name, stbi_failure_reason());
    image = Image(w, h, comp);
    std::copy(data, data + image.data.size(), image.data.begin());
    stbi_image_free(data);
    return image;
  }
  const bool is16 = stbi_is_16_bit_from_memory(bytes, len) != 0;
  std::vector<float> table;
  if (is16) {
    stbi_us* data = stbi_load_16_from_memory(bytes, len, &w, &h, &comp, 0);
    if (!data) fail("{}: cannot decode image: {}", name, stbi_failure_reason());
    image = Image(w, h, comp);
    for (std::size_t i = 0; i < image.data.size(); ++i) image.data[i] = data[i] / 65535.0f;
    stbi_image_free(data);
    if (options.decode_srgb) {
      const int colour = decode_channel_count(comp);
      for (std::size_t i = 0; i < image.data.size(); ++i)
        if (static_cast<int>(i % comp) < colour) image.data[i] = srgb_decode(image.data[i]);
    }
  } else {
    stbi_uc* data = stbi_load_from_memory(bytes, len, &w, &h, &comp, 0);
    if (!data) fail("{}: cannot decode image: {}", name, stbi_failure_reason());
    image = Image(w, h, comp);
    std::array<float, 256> linear, direct;
    for (int v = 0; v < 256; ++v) {
      direct[v] = v / 255.0f;
      linear[v] = options.decode_srgb ? srgb_decode(direct[v]) : direct[v];
    }
    const int colour = decode_channel_count(comp);
    for (std::size_t i = 0; i < image.data.size(); ++i)
      image.data[i] = static_cast<int>(i % comp) < colour ? linear[data[i]] : direct[data[i]];
    stbi_image_free(data);
  }
  report.srgb_decoded = options.decode_srgb;
  return image;
}

}  // namespace image_detail

bool read_image_header(const void* bytes, std::size_t size, ImageHeader& out) {
  const auto* b = static_cast<const unsigned char*>(bytes);
  const Format format = detect_format(b, size);
  if (format != Format::kPng && format != Format::kJpeg && format != Format::kHdr) return false;
  if (format == Format::kPng) {
    // The IHDR chunk, which the PNG specification (section 11.2.2) puts first: width and
    // height (4 bytes each, big-endian), bit depth, colour type. Read here rather than by
    // stb_image, which refuses a header whose size it finds absurd without saying so.
    if (size < 26) return false;
    auto be32 = [&](std::size_t at) {
      return int(std::min<std::uint32_t>((std::uint32_t(b[at]) << 24) |
                                             (std::uint32_t(b[at + 1]) << 16) |
                                             (std::uint32_t(b[at + 2]) << 8) | b[at + 3],
                                         std::uint32_t(INT32_MAX)));
    };
    out.width = be32(16);
    out.height = be32(20);
    out.bits = b[24] == 16 ? 16 : 8;
    // Grey, RGB, palette (expanded to RGBA at most), grey-alpha, RGBA.
    const int channels[7] = {1, 0, 3, 4, 2, 0, 4};
    out.channels = b[25] < 7 && channels[b[25]] > 0 ? channels[b[25]] : 4;
    return true;
  }
  if (size > static_cast<std::size_t>(INT32_MAX)) return false;
  const int len = static_cast<int>(size);
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(b, len, &w, &h, &comp)) return false;
  out.width = w;
  out.height = h;
  out.channels = comp;
  out.bits = format == Format::kHdr ? 32 : stbi_is_16_bit_from_memory(b, len) ? 16 : 8;
  return true;
}

bool decode_integer_image(const void* bytes, std::size_t size, const std::string& name,
                          const ImageReadOptions& options, IntegerImage& out) {
  const auto* b = static_cast<const unsigned char*>(bytes);
  if (size == 0) fail("{}: empty file", name);
  const Format format = detect_format(b, size);
  if (format == Format::kUnknown)
    fail("{}: unknown image format (expected OpenEXR, Radiance HDR, PNG or JPEG)", name);
  if (format != Format::kPng && format != Format::kJpeg) return false;
  if (size > static_cast<std::size_t>(INT32_MAX)) fail("{}: file is too large", name);
  const int len = static_cast<int>(size);
  if (format == Format::kPng) check_png_chunks(b, size, name);
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(b, len, &w, &h, &comp))
    fail("{}: cannot read image header: {}", name, stbi_failure_reason());
  check_size(name, w, h, options);
  const bool is16 = stbi_is_16_bit_from_memory(b, len) != 0;
  void* data = is16 ? static_cast<void*>(stbi_load_16_from_memory(b, len, &w, &h, &comp, 0))
                    : static_cast<void*>(stbi_load_from_memory(b, len, &w, &h, &comp, 0));
  if (!data) fail("{}: cannot decode image: {}", name, stbi_failure_reason());
  if (comp < 1 || comp > 4) {
    stbi_image_free(data);
    fail("{}: unsupported channel count {}", name, comp);
  }
  out.width = w;
  out.height = h;
  out.channels = comp;
  out.bits = is16 ? 16 : 8;
  const std::size_t n = std::size_t(w) * std::size_t(h) * std::size_t(comp);
  out.u8.clear();
  out.u16.clear();
  if (is16) {
    const auto* p = static_cast<const std::uint16_t*>(data);
    out.u16.assign(p, p + n);
  } else {
    const auto* p = static_cast<const std::uint8_t*>(data);
    out.u8.assign(p, p + n);
  }
  stbi_image_free(data);
  return true;
}

void write_hdr(const std::filesystem::path& path, const Image& image) {
  const std::string name = path.string();
  if (image.empty() || image.width <= 0 || image.height <= 0)
    fail("{}: cannot write an empty image", name);
  if (image.channels < 1 || image.channels > 4)
    fail("{}: cannot write {} channels to HDR", name, image.channels);
  write_file_atomically(path, [&](const std::filesystem::path& temp) {
    if (!stbi_write_hdr(temp.c_str(), image.width, image.height, image.channels, image.data.data()))
      fail("{}: cannot write Radiance HDR", name);
  });
}

}  // namespace pbrkit
