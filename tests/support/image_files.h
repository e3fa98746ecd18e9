#pragma once
// What format a file is, by its first bytes (the file's own signature, not our reader's
// opinion of it).
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>

namespace pbrkit::test {

/// The first `n` bytes of a file ("" when it is shorter or missing).
inline std::string first_bytes(const std::filesystem::path& path, std::size_t n) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(n, '\0');
  in.read(bytes.data(), std::streamsize(n));
  return in.gcount() == std::streamsize(n) ? bytes : std::string();
}

/// OpenEXR's magic number, 76 2f 31 01 (OpenEXR file layout, "Magic Number").
inline bool is_exr_file(const std::filesystem::path& path) {
  return first_bytes(path, 4) == std::string("\x76\x2f\x31\x01", 4);
}

/// PNG's signature, 89 50 4e 47 0d 0a 1a 0a (PNG specification, section 5.2).
inline bool is_png_file(const std::filesystem::path& path) {
  return first_bytes(path, 8) == std::string("\x89PNG\r\n\x1a\n", 8);
}

}  // namespace pbrkit::test
