// Hostile files that once got past the loader's checks into tinygltf, which trusts them:
// each must now be a pbrkit::Error naming the file and the JSON path, not a crash or an
// exception of another type. (The malformed corpus in tests/data/gltf/malformed/ holds
// the older cases.)
#include <cstdint>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

using nlohmann::json;

// A GLB (glTF 2.0 section 4.4) of `gltf` and, when given, a BIN chunk of `bin`.
std::string glb(const json& gltf, const std::string* bin) {
  std::string text = gltf.dump();
  while (text.size() % 4 != 0) text.push_back(' ');
  std::string out;
  auto u32 = [&out](std::size_t v) {
    const auto le = std::uint32_t(v);
    out.append(reinterpret_cast<const char*>(&le), 4);
  };
  out += "glTF";
  u32(2);
  u32(12 + 8 + text.size() + (bin ? 8 + bin->size() : 0));
  u32(text.size());
  u32(0x4E4F534A);
  out += text;
  if (bin) {
    u32(bin->size());
    u32(0x004E4942);
    out += *bin;
  }
  return out;
}

std::filesystem::path write(const std::string& name, const std::string& bytes) {
  const auto path = test::scratch_dir() / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// The message load_scene throws for `path` (empty, with a test failure, when it loads).
std::string load_error(const std::filesystem::path& path) {
  try {
    load_scene(path.string());
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded";
  return "";
}

// An image in a bufferView that lies outside its 4-byte buffer.
json image_in_a_view(std::uint64_t offset, std::uint64_t length, const std::string& buffer_uri) {
  json buffer = {{"byteLength", 4}};
  if (!buffer_uri.empty()) buffer["uri"] = buffer_uri;
  return {{"asset", {{"version", "2.0"}}},
          {"buffers", {buffer}},
          {"bufferViews", {{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}}}},
          {"images", {{{"bufferView", 0}, {"mimeType", "image/png"}}}}};
}

TEST(GltfHostileInput, ImageViewFarOutsideTheBinChunk) {
  // tinygltf handed &buffer[byteOffset] to the image callback before any view was checked:
  // a segmentation fault.
  const std::string bin(4, '\0');
  const auto path = write("far_view.glb", glb(image_in_a_view(100000000, 8, ""), &bin));
  const std::string message = load_error(path);
  EXPECT_NE(message.find("far_view.glb"), std::string::npos) << message;
  EXPECT_NE(message.find("bufferViews[0]: byteOffset 100000000 + byteLength 8 exceeds the "
                         "buffer's 4 bytes"),
            std::string::npos)
      << message;
}

TEST(GltfHostileInput, ImageViewLongerThanADataUriBuffer) {
  // The same in a .gltf: 100,000 bytes were copied from a 4-byte buffer (a heap read
  // overflow that only valgrind or AddressSanitizer saw) before the view was refused.
  const auto path =
      write("long_view.gltf",
            image_in_a_view(2, 100000, "data:application/octet-stream;base64,AAAAAA==").dump());
  const std::string message = load_error(path);
  EXPECT_NE(message.find("bufferViews[0]: byteOffset 2 + byteLength 100000 exceeds the "
                         "buffer's 4 bytes"),
            std::string::npos)
      << message;
}

TEST(GltfHostileInput, GlbBufferOfZeroBytes) {
  // tinygltf copied the BIN chunk with data.at(0) into a 0-byte buffer: std::out_of_range
  // escaped as an "internal error". The buffer schema's minimum byteLength is 1.
  const std::string bin(4, '\0');
  const json gltf = {{"asset", {{"version", "2.0"}}}, {"buffers", {{{"byteLength", 0}}}}};
  const auto path = write("empty_buffer.glb", glb(gltf, &bin));
  const std::string message = load_error(path);
  EXPECT_NE(message.find("empty_buffer.glb: buffers[0].byteLength: must be at least 1"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace pbrkit
