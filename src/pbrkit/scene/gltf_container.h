#pragma once
// The binary glTF container (glTF 2.0 section 4.4), checked before any parser sees it.
#include <cstddef>
#include <string>

namespace pbrkit {

struct GlbChunks {
  const char* json = nullptr;
  std::size_t json_size = 0;
  const unsigned char* bin = nullptr;  ///< null when the file has no BIN chunk
  std::size_t bin_size = 0;
};

/// Validates the 12-byte header (magic, version 2, total length equal to `size`) and the
/// chunk headers (JSON first, lengths within the file, optional BIN second); throws
/// pbrkit::Error "<name>: <problem>" otherwise.
GlbChunks parse_glb(const char* data, std::size_t size, const std::string& name);

}  // namespace pbrkit
