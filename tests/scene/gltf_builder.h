#pragma once
// A small glTF writer for the scene tests: accessors over one binary buffer, meshes of
// positions and indices, nodes, written as a GLB (glTF 2.0 section 4.4) into the scratch
// folder. The tests edit `gltf` directly to make a file hostile.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "support/test_paths.h"

namespace pbrkit::test {

struct GltfBuilder {
  nlohmann::json gltf = {{"asset", {{"version", "2.0"}}}};
  std::string bin;

  /// An accessor over `count` elements of `data` (`bytes` bytes), in a bufferView of its own.
  int accessor(const void* data, std::size_t bytes, int component_type, const char* type,
               std::size_t count, bool normalized = false) {
    while (bin.size() % 4 != 0) bin.push_back('\0');
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    bin.append(static_cast<const char*>(data), bytes);
    gltf["bufferViews"].push_back(view);
    nlohmann::json a = {{"bufferView", gltf["bufferViews"].size() - 1},
                        {"componentType", component_type},
                        {"count", count},
                        {"type", type}};
    if (normalized) a["normalized"] = true;
    gltf["accessors"].push_back(a);
    return int(gltf["accessors"].size()) - 1;
  }
  int floats(const std::vector<glm::vec3>& v) {
    return accessor(v.data(), v.size() * sizeof(glm::vec3), 5126, "VEC3", v.size());
  }
  int floats(const std::vector<glm::vec4>& v) {
    return accessor(v.data(), v.size() * sizeof(glm::vec4), 5126, "VEC4", v.size());
  }

  /// A primitive of `positions` (with the bounds glTF requires) and `indices`.
  nlohmann::json primitive(const std::vector<glm::vec3>& positions,
                           const std::vector<std::uint32_t>& indices, int material = -1) {
    const int pos = floats(positions);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    gltf["accessors"][std::size_t(pos)]["min"] = {lo.x, lo.y, lo.z};
    gltf["accessors"][std::size_t(pos)]["max"] = {hi.x, hi.y, hi.z};
    const int idx = accessor(indices.data(), indices.size() * 4, 5125, "SCALAR", indices.size());
    nlohmann::json p = {{"attributes", {{"POSITION", pos}}}, {"indices", idx}};
    if (material >= 0) p["material"] = material;
    return p;
  }
  int mesh(const std::vector<nlohmann::json>& primitives) {
    gltf["meshes"].push_back({{"primitives", primitives}});
    return int(gltf["meshes"].size()) - 1;
  }
  int node(nlohmann::json n) {
    gltf["nodes"].push_back(std::move(n));
    const int i = int(gltf["nodes"].size()) - 1;
    gltf["scenes"][0]["nodes"].push_back(i);
    gltf["scene"] = 0;
    return i;
  }

  std::string glb() const {
    nlohmann::json g = gltf;
    std::string b = bin;
    while (b.size() % 4 != 0) b.push_back('\0');
    if (!b.empty()) g["buffers"] = {{{"byteLength", b.size()}}};
    std::string text = g.dump();
    while (text.size() % 4 != 0) text.push_back(' ');
    std::string out;
    auto u32 = [&out](std::size_t v) {
      const auto le = std::uint32_t(v);
      out.append(reinterpret_cast<const char*>(&le), 4);
    };
    out += "glTF";
    u32(2);
    u32(12 + 8 + text.size() + (b.empty() ? 0 : 8 + b.size()));
    u32(text.size());
    u32(0x4E4F534A);
    out += text;
    if (!b.empty()) {
      u32(b.size());
      u32(0x004E4942);
      out += b;
    }
    return out;
  }
  std::filesystem::path write(const std::string& name) const {
    const auto path = scratch_dir() / name;
    std::ofstream(path, std::ios::binary) << glb();
    return path;
  }
};

}  // namespace pbrkit::test
