#include "pbrkit/scene/mesh_closure.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

namespace pbrkit {

namespace {

// A position's bit pattern, with -0 turned into +0 so that the two zeros weld.
struct PositionKey {
  std::array<std::uint32_t, 3> bits;
  bool operator==(const PositionKey&) const = default;
};

PositionKey key_of(glm::vec3 p) {
  PositionKey k;
  for (int c = 0; c < 3; ++c) {
    const float v = p[c] + 0.0f;  // -0 + 0 = +0 (round to nearest)
    std::memcpy(&k.bits[std::size_t(c)], &v, sizeof(float));
  }
  return k;
}

struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the three words
    for (const std::uint32_t w : k.bits) h = (h ^ w) * 1099511628211ull;
    return std::size_t(h);
  }
};

}  // namespace

EdgeCount count_edges(const Mesh& mesh) {
  // Each vertex's welded id: the first vertex with its position.
  std::unordered_map<PositionKey, std::uint32_t, PositionHash> first;
  first.reserve(mesh.positions.size());
  std::vector<std::uint32_t> weld(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    weld[i] = first.try_emplace(key_of(mesh.positions[i]), std::uint32_t(i)).first->second;

  // Undirected edges (lower id in the high word) and how many triangles use each.
  EdgeCount result;
  std::unordered_map<std::uint64_t, std::uint32_t> uses;
  uses.reserve(mesh.indices.size());
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t v[3] = {weld[mesh.indices[t]], weld[mesh.indices[t + 1]],
                                weld[mesh.indices[t + 2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;  // degenerate
    ++result.triangles;
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = v[e], b = v[(e + 1) % 3];
      ++uses[(std::uint64_t(std::min(a, b)) << 32) | std::max(a, b)];
    }
  }
  for (const auto& [edge, count] : uses) result.unpaired += count != 2;
  return result;
}

}  // namespace pbrkit
