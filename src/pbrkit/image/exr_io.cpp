// OpenEXR reading and writing (image_io.h): one path for files and embedded images, with
// the headers checked by OpenEXRCore before the C++ API allocates from them.
#include "pbrkit/image/image_io.h"

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

const char* default_channel_name(int channels, int c) {
  static const char* kGrey[] = {"Y", "A"};
  static const char* kRgba[] = {"R", "G", "B", "A"};
  return channels <= 2 ? kGrey[c] : kRgba[c];
}

}  // namespace

namespace image_detail {

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

}  // namespace image_detail

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

}  // namespace pbrkit
