// EXT_meshopt_compression: a file whose vertex and index bufferViews are compressed with
// meshoptimizer's encoders (and whose fallback buffer has no uri) loads to the original
// data.
#include <fstream>

#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

struct Encoded {
  std::filesystem::path gltf;
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
};

Encoded write_meshopt_file(const std::string& filter_mode = "ATTRIBUTES") {
  Encoded e;
  e.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 2, 0.25f}};
  e.indices = {0, 1, 2, 0, 2, 3, 3, 2, 4};
  std::vector<unsigned char> vbuf(meshopt_encodeVertexBufferBound(e.positions.size(), 12));
  vbuf.resize(meshopt_encodeVertexBuffer(vbuf.data(), vbuf.size(), e.positions.data(),
                                         e.positions.size(), 12));
  std::vector<unsigned char> ibuf(
      meshopt_encodeIndexBufferBound(e.indices.size(), e.positions.size()));
  ibuf.resize(
      meshopt_encodeIndexBuffer(ibuf.data(), ibuf.size(), e.indices.data(), e.indices.size()));
  std::vector<unsigned char> blob = vbuf;
  while (blob.size() % 4) blob.push_back(0);
  const std::size_t ioffset = blob.size();
  blob.insert(blob.end(), ibuf.begin(), ibuf.end());

  const auto dir = test::scratch_dir();
  std::ofstream(dir / "compressed.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(blob.data()), std::streamsize(blob.size()));
  using nlohmann::json;
  const std::size_t vbytes = e.positions.size() * 12, ibytes = e.indices.size() * 4;
  json j = {{"asset", {{"version", "2.0"}}},
            {"extensionsUsed", {"EXT_meshopt_compression"}},
            {"extensionsRequired", {"EXT_meshopt_compression"}},
            {"buffers",
             {{{"uri", "compressed.bin"}, {"byteLength", blob.size()}},
              {{"byteLength", vbytes + ibytes},
               {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
            {"bufferViews",
             {{{"buffer", 1},
               {"byteOffset", 0},
               {"byteLength", vbytes},
               {"byteStride", 12},
               {"extensions",
                {{"EXT_meshopt_compression",
                  {{"buffer", 0},
                   {"byteLength", vbuf.size()},
                   {"byteStride", 12},
                   {"count", e.positions.size()},
                   {"mode", filter_mode}}}}}},
              {{"buffer", 1},
               {"byteOffset", vbytes},
               {"byteLength", ibytes},
               {"extensions",
                {{"EXT_meshopt_compression",
                  {{"buffer", 0},
                   {"byteOffset", ioffset},
                   {"byteLength", ibuf.size()},
                   {"byteStride", 4},
                   {"count", e.indices.size()},
                   {"mode", "TRIANGLES"}}}}}}}},
            {"accessors",
             {{{"bufferView", 0},
               {"componentType", 5126},
               {"type", "VEC3"},
               {"count", e.positions.size()},
               {"min", {0, 0, 0}},
               {"max", {1, 2, 0.25}}},
              {{"bufferView", 1},
               {"componentType", 5125},
               {"type", "SCALAR"},
               {"count", e.indices.size()}}}},
            {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"scenes", {{{"nodes", {0}}}}}};
  e.gltf = dir / "meshopt.gltf";
  std::ofstream(e.gltf) << j.dump(1);
  return e;
}

TEST(Meshopt, DecodesCompressedVerticesAndIndices) {
  const Encoded e = write_meshopt_file();
  const Scene s = load_scene(e.gltf.string());
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  // No normals in the file: flat normals unweld the triangles, so compare per corner.
  ASSERT_EQ(m.indices.size(), e.indices.size());
  for (std::size_t i = 0; i < e.indices.size(); ++i)
    EXPECT_EQ(m.positions[m.indices[i]], e.positions[e.indices[i]]) << i;
}

TEST(Meshopt, BadModeIsAClearError) {
  const Encoded e = write_meshopt_file("SPIRALS");
  try {
    load_scene(e.gltf.string());
    FAIL();
  } catch (const Error& err) {
    EXPECT_NE(
        std::string(err.what()).find("bufferViews[0].extensions.EXT_meshopt_compression.mode"),
        std::string::npos)
        << err.what();
  }
}

}  // namespace
}  // namespace pbrkit
