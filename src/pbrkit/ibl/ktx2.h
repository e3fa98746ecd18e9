#pragma once
// KTX 2.0 textures (Khronos, "KTX File Format Specification", version 2.0): the glTF
// ecosystem's container, written and read here for uncompressed float RGBA 2D textures and
// cubemaps with mip chains (no supercompression). Cube faces are +X, -X, +Y, -Y, +Z, -Z
// (the same as cubemap.h); level 0 is the largest.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "pbrkit/ibl/cubemap.h"
#include "pbrkit/image/image.h"

namespace pbrkit {

/// The Vulkan formats supported (VkFormat enum values).
enum class Ktx2Format : std::uint32_t {
  kRgba16Float = 97,   ///< VK_FORMAT_R16G16B16A16_SFLOAT
  kRgba32Float = 109,  ///< VK_FORMAT_R32G32B32A32_SFLOAT
};
/// Bytes per texel: 8 or 16.
int ktx2_texel_bytes(Ktx2Format format);

/// An uncompressed KTX2 texture in memory: a 2D image or a cubemap, with its mip levels.
struct Ktx2Texture {
  Ktx2Format format = Ktx2Format::kRgba16Float;
  std::uint32_t width = 0, height = 0;
  std::uint32_t faces = 1;  ///< 1 (2D) or 6 (cubemap)
  /// levels[i]: the texel data of mip level i (level 0 largest), faces one after another,
  /// rows top to bottom (KTXorientation "rd"), little-endian.
  std::vector<std::vector<std::uint8_t>> levels;
  /// Key/value metadata (written sorted by key; values without the terminating NUL).
  std::vector<std::pair<std::string, std::string>> metadata;
};

/// Serialises a texture to the KTX 2.0 byte layout (identifier, header, index, level index,
/// basic data format descriptor, key/value data with KTXorientation, then the levels,
/// smallest first, each aligned to lcm(texel size, 4)).
std::string encode_ktx2(const Ktx2Texture& texture);
/// Parses and validates a KTX 2.0 file; throws pbrkit::Error naming `name` and the problem.
Ktx2Texture decode_ktx2(const std::string& bytes, const std::string& name);

/// Writes `texture` to `path` atomically (util/atomic_file.h).
void write_ktx2(const std::filesystem::path& path, const Ktx2Texture& texture);
/// Reads and decodes the .ktx2 file at `path` (see decode_ktx2()); throws pbrkit::Error
/// naming it.
Ktx2Texture read_ktx2(const std::filesystem::path& path);

/// Converts every level of a cubemap to a 6-face texture of `format` (channels as in
/// ktx2_from_image()).
Ktx2Texture ktx2_from_cubemap(const Cubemap& cube, Ktx2Format format);
/// The cubemap in a 6-face texture, every level, as 4-channel RGBA float images; throws
/// pbrkit::Error for a 2D texture.
Cubemap cubemap_from_ktx2(const Ktx2Texture& texture);
/// A single-level 2D texture of `format` from an image of any channel count (1 channel: grey;
/// otherwise missing channels 0, alpha 1).
Ktx2Texture ktx2_from_image(const Image& image, Ktx2Format format);
/// Mip `level` of a texture (its first face) as a 4-channel RGBA float image; throws
/// pbrkit::Error for a level it does not have.
Image image_from_ktx2(const Ktx2Texture& texture, int level = 0);

}  // namespace pbrkit
