#include "pbrkit/scene/mesh_closure.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
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

std::uint64_t hash_of(const PositionKey& k) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the three words
  for (const std::uint32_t w : k.bits) h = (h ^ w) * 1099511628211ull;
  return h ^ (h >> 29);
}

}  // namespace

EdgeCount count_edges(const Mesh& mesh) {
  // Each vertex's welded id: the first vertex with its position, found in an
  // open-addressing table of vertex ids (linear probing, at most half full).
  const std::size_t n = mesh.positions.size();
  std::vector<PositionKey> keys(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = key_of(mesh.positions[i]);
  std::size_t capacity = 16;
  while (capacity < 2 * n) capacity *= 2;
  constexpr std::uint32_t kEmpty = 0xffffffffu;
  std::vector<std::uint32_t> table(capacity, kEmpty);
  std::vector<std::uint32_t> weld(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t slot = std::size_t(hash_of(keys[i])) & (capacity - 1);
    while (table[slot] != kEmpty && !(keys[table[slot]] == keys[i]))
      slot = (slot + 1) & (capacity - 1);
    if (table[slot] == kEmpty) table[slot] = std::uint32_t(i);
    weld[i] = table[slot];
  }

  // Undirected edges, stored once at their lower welded id (a compressed adjacency list:
  // a hash map of 3 edges per triangle cost 20x the whole glTF load of the mesh).
  const auto triangle = [&](std::size_t t) {
    return std::array<std::uint32_t, 3>{weld[mesh.indices[t]], weld[mesh.indices[t + 1]],
                                        weld[mesh.indices[t + 2]]};
  };
  const auto degenerate = [](const std::array<std::uint32_t, 3>& v) {
    return v[0] == v[1] || v[1] == v[2] || v[2] == v[0];
  };
  EdgeCount result;
  std::vector<std::uint32_t> start(mesh.positions.size() + 1, 0);
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const auto v = triangle(t);
    if (degenerate(v)) continue;
    ++result.triangles;
    for (int e = 0; e < 3; ++e) ++start[std::min(v[std::size_t(e)], v[std::size_t(e + 1) % 3]) + 1];
  }
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<std::uint32_t> other(start.back());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const auto v = triangle(t);
    if (degenerate(v)) continue;
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = v[std::size_t(e)], b = v[std::size_t(e + 1) % 3];
      other[fill[std::min(a, b)]++] = std::max(a, b);
    }
  }
  // Each vertex's few edges, sorted: a run of equal ends is one edge and its triangles.
  for (std::size_t vtx = 0; vtx + 1 < start.size(); ++vtx) {
    const auto first = other.begin() + start[vtx], last = other.begin() + start[vtx + 1];
    std::sort(first, last);
    for (auto run = first; run != last;) {
      const auto end = std::upper_bound(run, last, *run);
      result.unpaired += (end - run) != 2;
      run = end;
    }
  }
  return result;
}

}  // namespace pbrkit
