// PNG writing through libpng (image_io.h): 8- or 16-bit, atomic.
#include "pbrkit/image/image_io.h"

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

#include "image_formats.h"
#include "pbrkit/core/color.h"
#include "pbrkit/util/atomic_file.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit {

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

}  // namespace pbrkit
