#include "pbrkit/image/image_io.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/openexr.h>
#include <png.h>

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

#include "pbrkit/core/color.h"
#include "pbrkit/util/atomic_file.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit {
namespace {

enum class Format { kExr, kPng, kJpeg, kHdr, kUnknown };

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

// An in-memory OpenEXR input stream, so EXR files and embedded EXR images share one path.
// Reading past the end throws (OpenEXR turns that into a clean failure on truncated files).
class MemoryIStream : public Imf::IStream {
 public:
  MemoryIStream(const unsigned char* data, std::size_t size, const std::string& name)
      : Imf::IStream(name.c_str()), data_(data), size_(size) {}
  bool read(char c[], int n) override {
    // seekg() takes any 64-bit offset a corrupt file names, so pos_ may lie past the end;
    // compare without forming pos_ + n, which could wrap around (found by fuzz_image).
    if (n < 0 || pos_ > size_ || static_cast<std::size_t>(n) > size_ - pos_)
      throw std::runtime_error("unexpected end of file (truncated?)");
    std::memcpy(c, data_ + pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::size_t>(n);
    return pos_ < size_;
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = static_cast<std::size_t>(pos); }

 private:
  const unsigned char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

// Validates an EXR's headers before the C++ API opens it. OpenEXR's C++ classes
// (Imf::InputFile) allocate from the header's numbers while opening a file: a 173-byte
// file declaring a 16 M-pixel-wide data window made them allocate 2 GB for line buffers,
// a 352-byte one declaring a 1.7 GB attribute allocated that (both found by fuzz_image).
// OpenEXRCore, OpenEXR's C library made for untrusted input, parses the headers with
// bounds checks (strict mode: every attribute's size checked against its type and the
// file), and its answers are checked here against the pixel limit: the data window, the
// tile size, and the samples per line of all channels together (line buffers hold every
// channel, so a header with thousands of channels is refused as well).
thread_local std::string g_exr_core_error;

void check_exr_headers(const unsigned char* b, std::size_t n, const std::string& name,
                       const ImageReadOptions& options) {
  struct Source {
    const unsigned char* bytes;
    std::size_t size;
  } source{b, n};
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.user_data = &source;
  init.read_fn = [](exr_const_context_t, void* user, void* buffer, std::uint64_t size,
                    std::uint64_t offset, exr_stream_error_func_ptr_t) -> std::int64_t {
    const auto* src = static_cast<const Source*>(user);
    if (offset >= src->size) return 0;
    const std::uint64_t count = std::min<std::uint64_t>(size, src->size - offset);
    std::memcpy(buffer, src->bytes + offset, std::size_t(count));
    return std::int64_t(count);
  };
  init.size_fn = [](exr_const_context_t, void* user) -> std::int64_t {
    return std::int64_t(static_cast<const Source*>(user)->size);
  };
  init.error_handler_fn = [](exr_const_context_t, exr_result_t, const char* message) {
    g_exr_core_error = message ? message : "";
  };
  init.flags = EXR_CONTEXT_FLAG_STRICT_HEADER;
  g_exr_core_error.clear();
  exr_context_t context = nullptr;
  const exr_result_t started = exr_start_read(&context, name.c_str(), &init);
  struct Finish {
    exr_context_t& c;
    ~Finish() { exr_finish(&c); }
  } finish{context};
  if (started != EXR_ERR_SUCCESS)
    fail("{}: not a valid OpenEXR file: {}", name,
         g_exr_core_error.empty() ? exr_get_default_error_message(started) : g_exr_core_error);
  int parts = 0;
  if (exr_get_count(context, &parts) != EXR_ERR_SUCCESS || parts < 1)
    fail("{}: OpenEXR file has no parts", name);
  for (int part = 0; part < parts; ++part) {
    exr_attr_box2i_t dw{};
    if (exr_get_data_window(context, part, &dw) != EXR_ERR_SUCCESS)
      fail("{}: OpenEXR part {} has no data window", name, part);
    const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
    const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    check_size(name, w, h, options);
    std::uint32_t tx = 0, ty = 0;
    if (exr_get_tile_descriptor(context, part, &tx, &ty, nullptr, nullptr) == EXR_ERR_SUCCESS)
      check_size(name, tx, ty, options);
    const exr_attr_chlist_t* channels = nullptr;
    if (exr_get_channels(context, part, &channels) == EXR_ERR_SUCCESS && channels) {
      const auto samples_per_line = static_cast<unsigned long long>(w) *
                                    static_cast<unsigned long long>(channels->num_channels);
      if (samples_per_line > 4ull * options.max_pixels / static_cast<unsigned long long>(h))
        fail(
            "{}: image is too large ({} x {} pixels in {} channels; the limit is {} pixels of "
            "4 channels)",
            name, w, h, channels->num_channels, options.max_pixels);
    }
  }
}

// Order of channels inside a layer: R, G, B, A first (in that order), then the rest
// alphabetically; a lone Y is grey.
int channel_rank(const std::string& c) {
  static const std::array<const char*, 4> kOrder = {"R", "G", "B", "A"};
  for (int i = 0; i < 4; ++i)
    if (c == kOrder[i]) return i;
  return 4;
}

void split_channel(const std::string& full, std::string& layer, std::string& channel) {
  const auto dot = full.rfind('.');
  if (dot == std::string::npos) {
    layer.clear();
    channel = full;
  } else {
    layer = full.substr(0, dot);
    channel = full.substr(dot + 1);
  }
}

// Reads the named channels (full names) of an EXR into an interleaved float image.
Image read_exr_channels(Imf::InputFile& file, const std::vector<std::string>& names) {
  const Imath::Box2i dw = file.header().dataWindow();
  const int w = dw.max.x - dw.min.x + 1;
  const int h = dw.max.y - dw.min.y + 1;
  Image image(w, h, static_cast<int>(names.size()));
  Imf::FrameBuffer fb;
  const std::size_t xs = sizeof(float) * image.channels;
  for (std::size_t c = 0; c < names.size(); ++c)
    fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.data.data() + c, dw, xs, xs * w));
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  return image;
}

Image decode_exr(const unsigned char* bytes, std::size_t size, const std::string& name,
                 const ImageReadOptions& options) {
  try {
    check_exr_headers(bytes, size, name, options);
    MemoryIStream stream(bytes, size, name);
    Imf::InputFile file(stream);
    const Imath::Box2i dw = file.header().dataWindow();
    check_size(name, static_cast<long long>(dw.max.x) - dw.min.x + 1,
               static_cast<long long>(dw.max.y) - dw.min.y + 1, options);
    const Imf::ChannelList& channels = file.header().channels();
    auto has = [&](const char* c) { return channels.findChannel(c) != nullptr; };
    if (has("RY") || has("BY")) {
      // Luminance/chroma files with subsampled chroma: let RgbaInputFile reconstruct RGB.
      MemoryIStream stream2(bytes, size, name);
      Imf::RgbaInputFile rgba(stream2);
      const int w = dw.max.x - dw.min.x + 1;
      const int h = dw.max.y - dw.min.y + 1;
      std::vector<Imf::Rgba> pixels(std::size_t(w) * h);
      rgba.setFrameBuffer(pixels.data() - dw.min.x - std::ptrdiff_t(dw.min.y) * w, 1, w);
      rgba.readPixels(dw.min.y, dw.max.y);
      Image image(w, h, 4);
      for (std::size_t i = 0; i < pixels.size(); ++i) {
        image.data[4 * i + 0] = pixels[i].r;
        image.data[4 * i + 1] = pixels[i].g;
        image.data[4 * i + 2] = pixels[i].b;
        image.data[4 * i + 3] = pixels[i].a;
      }
      return image;
    }
    std::vector<std::string> names;
    if (has("R") && has("G") && has("B")) {
      names = {"R", "G", "B"};
      if (has("A")) names.push_back("A");
    } else if (has("Y")) {
      names = {"Y"};
      if (has("A")) names.push_back("A");
    } else {
      fail(
          "{}: EXR has no R,G,B or Y channels in its main layer (a multi-layer file is read "
          "with read_exr_layers)",
          name);
    }
    return read_exr_channels(file, names);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("{}: cannot read EXR: {}", name, e.what());
  }
}

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

const char* default_channel_name(int channels, int c) {
  static const char* kGrey[] = {"Y", "A"};
  static const char* kRgba[] = {"R", "G", "B", "A"};
  return channels <= 2 ? kGrey[c] : kRgba[c];
}

}  // namespace

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

Image read_image(const std::filesystem::path& path, const ImageReadOptions& options,
                 ImageReadReport* report) {
  const std::string bytes = read_file_bytes(path);
  return decode_image(bytes.data(), bytes.size(), path.string(), options, report);
}

void write_exr(const std::filesystem::path& path, const Image& image, ExrPixelType type) {
  ExrLayer layer;
  layer.image = &image;
  layer.type = type;
  for (int c = 0; c < image.channels && c < 4; ++c)
    layer.channel_names.push_back(default_channel_name(image.channels, c));
  write_exr_layers(path, {layer});
}

void write_exr_layers(const std::filesystem::path& path, const std::vector<ExrLayer>& layers,
                      const ExrAttributes& attributes) {
  const std::string name = path.string();
  if (layers.empty()) fail("{}: no layers to write", name);
  const Image* first = layers.front().image;
  if (!first) fail("{}: layer '{}' has no image", name, layers.front().name);
  const int w = first->width, h = first->height;
  if (w <= 0 || h <= 0) fail("{}: cannot write an empty image ({} x {})", name, w, h);
  Imf::Header header(w, h);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const auto& [key, value] : attributes) header.insert(key, Imf::StringAttribute(value));
  Imf::FrameBuffer fb;
  std::set<std::string> seen;
  // OpenEXR does not convert float slices to half channels on output: half layers are
  // converted here (round to nearest, Imath's half constructor), one plane per channel.
  std::vector<std::vector<half>> half_planes;
  for (const ExrLayer& layer : layers) {
    const Image* img = layer.image;
    if (!img) fail("{}: layer '{}' has no image", name, layer.name);
    if (img->width != w || img->height != h)
      fail("{}: layer '{}' is {} x {}, but the first layer is {} x {}", name, layer.name,
           img->width, img->height, w, h);
    if (static_cast<int>(layer.channel_names.size()) != img->channels)
      fail("{}: layer '{}' names {} channels but its image has {}", name, layer.name,
           layer.channel_names.size(), img->channels);
    const bool is_half = layer.type == ExrPixelType::kHalf;
    const std::size_t xs = sizeof(float) * img->channels;
    for (int c = 0; c < img->channels; ++c) {
      const std::string full =
          layer.name.empty() ? layer.channel_names[c] : layer.name + "." + layer.channel_names[c];
      if (!seen.insert(full).second) fail("{}: channel '{}' is written twice", name, full);
      header.channels().insert(full, Imf::Channel(is_half ? Imf::HALF : Imf::FLOAT));
      if (is_half) {
        std::vector<half>& plane = half_planes.emplace_back(std::size_t(w) * h);
        for (std::size_t i = 0; i < plane.size(); ++i)
          plane[i] = half(img->data[i * img->channels + c]);
        fb.insert(full, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(plane.data()), sizeof(half),
                                   sizeof(half) * w));
      } else {
        fb.insert(full,
                  Imf::Slice(Imf::FLOAT,
                             const_cast<char*>(reinterpret_cast<const char*>(img->data.data() + c)),
                             xs, xs * w));
      }
    }
  }
  write_file_atomically(path, [&](const std::filesystem::path& temp) {
    try {
      Imf::OutputFile file(temp.c_str(), header);
      file.setFrameBuffer(fb);
      file.writePixels(h);
    } catch (const std::exception& e) {
      fail("{}: cannot write EXR: {}", name, e.what());
    }
  });
}

std::vector<std::pair<std::string, Image>> read_exr_layers(const std::filesystem::path& path,
                                                           ExrAttributes* attributes) {
  const std::string name = path.string();
  const std::string bytes = read_file_bytes(path);
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  if (detect_format(b, bytes.size()) != Format::kExr) fail("{}: not an OpenEXR file", name);
  std::vector<std::pair<std::string, Image>> result;
  ImageReadReport report;
  try {
    check_exr_headers(b, bytes.size(), name, ImageReadOptions{});
    MemoryIStream stream(b, bytes.size(), name);
    Imf::InputFile file(stream);
    const Imath::Box2i dw = file.header().dataWindow();
    check_size(name, static_cast<long long>(dw.max.x) - dw.min.x + 1,
               static_cast<long long>(dw.max.y) - dw.min.y + 1, ImageReadOptions{});
    if (attributes)
      for (auto it = file.header().begin(); it != file.header().end(); ++it)
        if (const auto* a = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
          (*attributes)[it.name()] = a->value();
    std::map<std::string, std::vector<std::string>> by_layer;  // layer -> channel names
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
      std::string layer, channel;
      split_channel(it.name(), layer, channel);
      by_layer[layer].push_back(channel);
    }
    for (auto& [layer, channels] : by_layer) {
      std::sort(channels.begin(), channels.end(), [](const std::string& a, const std::string& b) {
        const int ra = channel_rank(a), rb = channel_rank(b);
        return ra != rb ? ra < rb : a < b;
      });
      if (channels.size() > 4)
        fail("{}: layer '{}' has {} channels; at most 4 per layer are supported", name, layer,
             channels.size());
      std::vector<std::string> full;
      for (const auto& c : channels) full.push_back(layer.empty() ? c : layer + "." + c);
      Image image = read_exr_channels(file, full);
      sanitize_image(image, report);
      result.emplace_back(layer, std::move(image));
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("{}: cannot read EXR: {}", name, e.what());
  }
  warn_if_cleaned(name, report);
  return result;
}

namespace {

// libpng's classic API: one 8- or 16-bit image, straight alpha, rows top first. libpng
// reports errors by longjmp; the messages are collected and turned into a pbrkit::Error
// after the jump, once no libpng frame is live.
void write_png_file(const std::filesystem::path& temp, const std::string& name, int width,
                    int height, int channels, int bits, const void* samples) {
  struct Sink {
    std::FILE* file = nullptr;
    png_structp png = nullptr;
    png_infop info = nullptr;
    std::string error;
    ~Sink() {
      png_destroy_write_struct(&png, &info);
      if (file) std::fclose(file);
    }
  } sink;
  auto on_error = [](png_structp png, png_const_charp message) {
    static_cast<Sink*>(png_get_error_ptr(png))->error = message;
    png_longjmp(png, 1);
  };
  auto on_warning = [](png_structp, png_const_charp) {};
  sink.file = std::fopen(temp.c_str(), "wb");
  if (!sink.file) fail("{}: cannot write PNG: {}", name, std::strerror(errno));
  sink.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, on_error, on_warning);
  if (sink.png) sink.info = png_create_info_struct(sink.png);
  if (!sink.png || !sink.info) fail("{}: cannot write PNG: out of memory", name);
  static constexpr int kColorTypes[4] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                         PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
  const std::size_t row_bytes = std::size_t(width) * std::size_t(channels) * std::size_t(bits / 8);
  const auto* bytes = static_cast<const unsigned char*>(samples);
  if (setjmp(png_jmpbuf(sink.png)) == 0) {
    png_init_io(sink.png, sink.file);
    png_set_IHDR(sink.png, sink.info, png_uint_32(width), png_uint_32(height), bits,
                 kColorTypes[channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB_gAMA_and_cHRM(sink.png, sink.info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(sink.png, sink.info);
    // PNG stores 16-bit samples big-endian; ours are in the machine's order.
    if (bits == 16 && std::endian::native == std::endian::little) png_set_swap(sink.png);
    for (int y = 0; y < height; ++y) png_write_row(sink.png, bytes + std::size_t(y) * row_bytes);
    png_write_end(sink.png, nullptr);
  }
  if (!sink.error.empty()) fail("{}: cannot write PNG: {}", name, sink.error);
  const bool flushed = std::fflush(sink.file) == 0 && !std::ferror(sink.file);
  if (!flushed) fail("{}: cannot write PNG: {}", name, std::strerror(errno));
}

}  // namespace

void write_png(const std::filesystem::path& path, const Image& display, int bits) {
  const std::string name = path.string();
  if (bits != 8 && bits != 16) fail("{}: PNG bit depth must be 8 or 16, not {}", name, bits);
  if (display.empty() || display.width <= 0 || display.height <= 0)
    fail("{}: cannot write an empty image", name);
  if (display.channels < 1 || display.channels > 4)
    fail("{}: cannot write {} channels to PNG", name, display.channels);
  const float scale = bits == 8 ? 255.0f : 65535.0f;
  // Round to nearest after clamping to [0,1]; NaN becomes 0.
  auto quantise = [&](float v) {
    const float c = v > 0.0f ? std::min(v, 1.0f) : 0.0f;
    return static_cast<unsigned>(std::lround(c * scale));
  };
  std::vector<unsigned char> q8;
  std::vector<unsigned short> q16;
  if (bits == 8) {
    q8.resize(display.data.size());
    for (std::size_t i = 0; i < q8.size(); ++i)
      q8[i] = static_cast<unsigned char>(quantise(display.data[i]));
  } else {
    q16.resize(display.data.size());
    for (std::size_t i = 0; i < q16.size(); ++i)
      q16[i] = static_cast<unsigned short>(quantise(display.data[i]));
  }
  write_file_atomically(path, [&](const std::filesystem::path& temp) {
    // libpng (stb_image_write has 8-bit only). The samples are already sRGB-encoded; the
    // sRGB chunk says so, so that viewers do not apply another transfer curve.
    write_png_file(temp, name, display.width, display.height, display.channels, bits,
                   bits == 8 ? static_cast<const void*>(q8.data()) : q16.data());
  });
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
