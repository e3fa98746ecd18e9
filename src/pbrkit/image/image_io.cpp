#include "pbrkit/image/image_io.h"

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

namespace image_detail {

// Formats are recognised by their magic bytes, never by the file name, so a mislabelled
// file is still read correctly and garbage is rejected before any decoder sees it.
Format detect_format(const unsigned char* b, std::size_t n) {
  if (n >= 4 && b[0] == 0x76 && b[1] == 0x2f && b[2] == 0x31 && b[3] == 0x01) return Format::kExr;
  if (n >= 8 && std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0) return Format::kPng;
  if (n >= 3 && b[0] == 0xff && b[1] == 0xd8 && b[2] == 0xff) return Format::kJpeg;
  if (n >= 6 && (std::memcmp(b, "#?RADIANCE", std::min<std::size_t>(n, 10)) == 0 ||
                 std::memcmp(b, "#?RGBE", 6) == 0))
    return Format::kHdr;
  return Format::kUnknown;
}

void check_size(const std::string& name, long long w, long long h,
                const ImageReadOptions& options) {
  if (w <= 0 || h <= 0) fail("{}: image has zero size ({} x {})", name, w, h);
  if (static_cast<unsigned long long>(w) * static_cast<unsigned long long>(h) > options.max_pixels)
    fail("{}: image is too large ({} x {} pixels; the limit is {} pixels)", name, w, h,
         options.max_pixels);
}

std::string read_file_bytes(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) fail("{}: file not found", path.string());
  if (fs::is_directory(path, ec)) fail("{}: is a directory, not an image", path.string());
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open for reading", path.string());
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail("{}: read error", path.string());
  return bytes;
}

void warn_if_cleaned(const std::string& name, const ImageReadReport& r) {
  if (r.negative + r.nan + r.inf == 0) return;
  warn("{}: set {} negative, {} NaN and {} infinite sample(s) to 0", name, r.negative, r.nan,
       r.inf);
}

}  // namespace image_detail

using namespace image_detail;

void sanitize_image(Image& image, ImageReadReport& report) {
  for (float& v : image.data) {
    if (std::isnan(v)) {
      ++report.nan;
      v = 0.0f;
    } else if (std::isinf(v)) {
      ++report.inf;
      v = 0.0f;
    } else if (v < 0.0f) {
      ++report.negative;
      v = 0.0f;
    }
  }
}

Image decode_image(const void* bytes, std::size_t size, const std::string& name,
                   const ImageReadOptions& options, ImageReadReport* report) {
  const auto* b = static_cast<const unsigned char*>(bytes);
  if (size == 0) fail("{}: empty file", name);
  ImageReadReport local;
  Image image;
  switch (detect_format(b, size)) {
    case Format::kExr:
      image = decode_exr(b, size, name, options);
      break;
    case Format::kPng:
      image = decode_stb(b, size, name, Format::kPng, options, local);
      break;
    case Format::kJpeg:
      image = decode_stb(b, size, name, Format::kJpeg, options, local);
      break;
    case Format::kHdr:
      image = decode_stb(b, size, name, Format::kHdr, options, local);
      break;
    case Format::kUnknown:
      fail("{}: unknown image format (expected OpenEXR, Radiance HDR, PNG or JPEG)", name);
  }
  if (image.channels < 1 || image.channels > 4)
    fail("{}: unsupported channel count {}", name, image.channels);
  sanitize_image(image, local);
  if (options.warn_cleaned) warn_if_cleaned(name, local);
  if (report) {
    report->negative += local.negative;
    report->nan += local.nan;
    report->inf += local.inf;
    report->srgb_decoded = local.srgb_decoded;
  }
  return image;
}

Image read_image(const std::filesystem::path& path, const ImageReadOptions& options,
                 ImageReadReport* report) {
  const std::string bytes = read_file_bytes(path);
  return decode_image(bytes.data(), bytes.size(), path.string(), options, report);
}

}  // namespace pbrkit
