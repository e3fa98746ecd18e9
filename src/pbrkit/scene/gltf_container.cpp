#include "pbrkit/scene/gltf_container.h"

#include <cstdint>
#include <cstring>

#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

std::uint32_t u32(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);  // GLB is little-endian, like every platform we build for
  return v;
}

}  // namespace

GlbChunks parse_glb(const char* data, std::size_t size, const std::string& name) {
  if (size < 12) fail("{}: truncated GLB: {} bytes, the header alone needs 12", name, size);
  if (std::memcmp(data, "glTF", 4) != 0) fail("{}: not a GLB file (wrong magic)", name);
  const std::uint32_t version = u32(data + 4);
  if (version != 2) fail("{}: unsupported GLB version {} (only 2 is supported)", name, version);
  const std::uint32_t length = u32(data + 8);
  if (length > size)
    fail("{}: truncated GLB: the header says {} bytes but the file has {}", name, length, size);
  if (length < size)
    fail("{}: GLB header length {} does not match the file size {}", name, length, size);
  if (size < 20) fail("{}: truncated GLB: no JSON chunk header", name);
  const std::uint32_t json_length = u32(data + 12);
  const std::uint32_t json_type = u32(data + 16);
  if (json_type != kChunkJson)
    fail("{}: the first GLB chunk is not JSON (type 0x{:08x})", name, json_type);
  if (json_length == 0) fail("{}: the GLB JSON chunk is empty", name);
  if (json_length > size - 20)
    fail("{}: GLB JSON chunk length {} exceeds the {} bytes left in the file", name, json_length,
         size - 20);
  GlbChunks chunks;
  chunks.json = data + 20;
  chunks.json_size = json_length;
  std::size_t offset = 20 + std::size_t(json_length);
  // Chunks are 4-byte aligned; tolerate a writer that forgot the JSON padding.
  if (offset % 4 != 0 && offset + (4 - offset % 4) <= size) offset += 4 - offset % 4;
  if (offset == size) return chunks;
  if (size - offset < 8) fail("{}: truncated GLB chunk header at byte {}", name, offset);
  const std::uint32_t bin_length = u32(data + offset);
  const std::uint32_t bin_type = u32(data + offset + 4);
  if (bin_length > size - offset - 8)
    fail("{}: GLB chunk length {} at byte {} exceeds the {} bytes left in the file", name,
         bin_length, offset, size - offset - 8);
  if (bin_type == kChunkBin) {
    chunks.bin = reinterpret_cast<const unsigned char*>(data + offset + 8);
    chunks.bin_size = bin_length;
  }
  return chunks;
}

}  // namespace pbrkit
