#pragma once
// Reading and writing images. Inputs: OpenEXR (all compressions, DWAB included, through
// OpenEXR), Radiance .hdr, PNG, JPEG. Outputs: EXR (half or float, linear, optionally
// several named layers) and PNG (8 or 16 bit, display-referred). Every write is atomic.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "pbrkit/image/image.h"

namespace pbrkit {

/// How values were cleaned on input (policy: negative, NaN or Inf samples are set to 0
/// and counted; read_image emits one warning naming the file when any count is non-zero).
struct ImageReadReport {
  std::size_t negative = 0;
  std::size_t nan = 0;
  std::size_t inf = 0;
  bool srgb_decoded = false;  ///< true when 8/16-bit PNG/JPEG values were decoded from sRGB
};

struct ImageReadOptions {
  /// Decode 8/16-bit PNG/JPEG from the sRGB transfer function to linear (colour images).
  /// Set false for data textures (normals, metallic-roughness).
  bool decode_srgb = true;
  /// Refuse images with more pixels than this (width * height); the error says the limit.
  std::size_t max_pixels = std::size_t(1) << 28;  // 268 M pixels (16384 x 16384)
  /// Warn (naming the file) when samples were cleaned. Off only for pbrkit's own shipped
  /// files, whose few cleaned samples are known and documented (data/env/LICENSE.md).
  bool warn_cleaned = true;
};

/// Reads an image from disk. Throws pbrkit::Error naming the file and the problem
/// (missing, unreadable, unsupported format, zero size, larger than max_pixels).
Image read_image(const std::filesystem::path& path, const ImageReadOptions& options = {},
                 ImageReadReport* report = nullptr);

/// Decodes an image from memory (PNG/JPEG/HDR/EXR recognised by content). `name` is used
/// in error messages (e.g. "model.glb: image 3").
Image decode_image(const void* bytes, std::size_t size, const std::string& name,
                   const ImageReadOptions& options = {}, ImageReadReport* report = nullptr);

/// What an image's header says, read without decoding it.
struct ImageHeader {
  int width = 0;
  int height = 0;
  int channels = 0;
  int bits = 8;  ///< bits per sample as decoded: 8 or 16 (PNG, JPEG), 32 (float: HDR)
};
/// Reads the size, channel count and sample depth of a PNG, JPEG or Radiance HDR from its
/// header alone (nothing is allocated for pixels). False for other formats (OpenEXR, whose
/// header decode_image checks itself) or an unreadable header.
bool read_image_header(const void* bytes, std::size_t size, ImageHeader& out);

/// An 8- or 16-bit image's samples exactly as stored (no transfer function applied), for
/// textures kept at their source's precision.
struct IntegerImage {
  int width = 0;
  int height = 0;
  int channels = 0;                ///< 1 grey, 2 grey-alpha, 3 RGB, 4 RGBA
  int bits = 8;                    ///< 8: samples in u8, 16: samples in u16
  std::vector<std::uint8_t> u8;    ///< width * height * channels, row-major, top row first
  std::vector<std::uint16_t> u16;  ///< the same for 16-bit sources
};
/// Decodes a PNG or JPEG to its stored 8/16-bit samples, with decode_image's checks (size
/// limit, PNG chunk structure). Returns false, decoding nothing, for float formats (OpenEXR,
/// Radiance HDR), which decode_image reads.
bool decode_integer_image(const void* bytes, std::size_t size, const std::string& name,
                          const ImageReadOptions& options, IntegerImage& out);

/// Applies the input policy in place: negative/NaN/Inf -> 0, counted into `report`.
void sanitize_image(Image& image, ImageReadReport& report);

enum class ExrPixelType { kHalf, kFloat };

/// One named layer of a multi-layer EXR. Channel names are `<layer>.<name>` (or just
/// `<name>` when the layer name is empty), e.g. "albedo.R".
struct ExrLayer {
  std::string name;                        ///< "" for the main RGBA layer
  std::vector<std::string> channel_names;  ///< one per image channel, e.g. {"R","G","B"}
  const Image* image = nullptr;
  ExrPixelType type = ExrPixelType::kHalf;
};

/// Writes a linear EXR (ZIP compressed). Atomic.
void write_exr(const std::filesystem::path& path, const Image& image,
               ExrPixelType type = ExrPixelType::kHalf);
/// String attributes of an EXR's header (name -> value), e.g. a render's counts.
using ExrAttributes = std::map<std::string, std::string>;

/// Writes a multi-layer EXR; all layers must have the same size; `attributes` are added to
/// its header as string attributes. Atomic.
void write_exr_layers(const std::filesystem::path& path, const std::vector<ExrLayer>& layers,
                      const ExrAttributes& attributes = {});
/// Reads every channel of an EXR: returns layer name -> image (channels in R,G,B,A order,
/// or alphabetical for other names). The main layer has the name "". With `attributes`,
/// the header's string attributes are put there.
std::vector<std::pair<std::string, Image>> read_exr_layers(const std::filesystem::path& path,
                                                           ExrAttributes* attributes = nullptr);

/// Writes a PNG from display-referred values in [0,1] (already tone-mapped and
/// sRGB-encoded; values are clamped and quantised with rounding). Atomic.
void write_png(const std::filesystem::path& path, const Image& display, int bits = 8);

/// Writes a Radiance .hdr (linear RGB). Atomic.
void write_hdr(const std::filesystem::path& path, const Image& image);

}  // namespace pbrkit
