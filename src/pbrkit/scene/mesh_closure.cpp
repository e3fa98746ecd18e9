#include "pbrkit/scene/mesh_closure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace pbrkit {

namespace {

// Welds positions closer than `tolerance` (Euclidean) through a spatial hash with cells
// of that size: a position's match, if any, lies in its own cell or one of the 26 around
// it. Each position welds to the first earlier representative within reach, or becomes
// one; the work is O(n) for any distribution short of thousands of positions per cell.
class Welder {
 public:
  Welder(std::size_t n, glm::dvec3 origin, double tolerance)
      : origin_(origin), tolerance_(tolerance), inv_cell_(tolerance > 0.0 ? 1.0 / tolerance : 0.0) {
    std::size_t capacity = 16;
    while (capacity < 2 * n) capacity *= 2;
    table_.assign(capacity, kEmpty);
    cells_.reserve(n);
    positions_.reserve(n);
  }

  /// The welded id of `p` (the index of its representative among the positions given).
  std::uint32_t weld(glm::vec3 p) {
    const glm::dvec3 q(p);
    const Cell cell = cell_of(q);
    const auto id = std::uint32_t(positions_.size());
    positions_.push_back(q);
    cells_.push_back(cell);
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          if (tolerance_ <= 0.0 && (dx | dy | dz) != 0) continue;  // exact welding: one cell
          const Cell near{cell[0] + dx, cell[1] + dy, cell[2] + dz};
          for (std::size_t slot = slot_of(near); table_[slot] != kEmpty; slot = next(slot)) {
            const std::uint32_t r = table_[slot];
            if (cells_[r] == near && glm::length(positions_[r] - q) <= tolerance_) return r;
          }
        }
    std::size_t slot = slot_of(cell);
    while (table_[slot] != kEmpty) slot = next(slot);
    table_[slot] = id;
    return id;
  }

 private:
  using Cell = std::array<std::int64_t, 3>;
  static constexpr std::uint32_t kEmpty = 0xffffffffu;

  // Offsets from the bounding box's corner: at most 1 / kWeldTolerance cells per axis, so
  // the conversion never overflows.
  Cell cell_of(const glm::dvec3& q) const {
    Cell c{};
    for (int a = 0; a < 3; ++a)
      c[std::size_t(a)] = std::int64_t(std::floor((q[a] - origin_[a]) * inv_cell_));
    return c;
  }
  std::size_t slot_of(const Cell& c) const {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the three coordinates
    for (const std::int64_t v : c) h = (h ^ std::uint64_t(v)) * 1099511628211ull;
    return std::size_t(h ^ (h >> 29)) & (table_.size() - 1);
  }
  std::size_t next(std::size_t slot) const { return (slot + 1) & (table_.size() - 1); }

  glm::dvec3 origin_;
  double tolerance_;
  double inv_cell_;
  std::vector<std::uint32_t> table_;  // representatives, open addressing, at most half full
  std::vector<Cell> cells_;
  std::vector<glm::dvec3> positions_;
};

}  // namespace

EdgeCount count_edges(const Mesh& mesh) {
  const Mesh* const one[] = {&mesh};
  return count_edges(std::span<const Mesh* const>(one));
}

EdgeCount count_edges(std::span<const Mesh* const> meshes) {
  // The tolerance is relative to the whole surface's bounding box (in double: a float
  // diagonal of a box far from the origin loses the digits the tolerance needs).
  std::size_t n = 0;
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const Mesh* m : meshes) {
    n += m->positions.size();
    for (const glm::vec3& p : m->positions) {
      lo = glm::min(lo, glm::dvec3(p));
      hi = glm::max(hi, glm::dvec3(p));
    }
  }
  const double diagonal = n > 0 ? glm::length(hi - lo) : 0.0;
  const double tolerance = kWeldTolerance * diagonal;  // finite: float extents fit a double

  // Each vertex's welded id, over the primitives' vertices in order.
  Welder welder(n, n > 0 ? lo : glm::dvec3(0.0), tolerance);
  std::vector<std::uint32_t> weld;
  weld.reserve(n);
  for (const Mesh* m : meshes)
    for (const glm::vec3& p : m->positions) weld.push_back(welder.weld(p));

  // Each primitive's triangles in welded ids (indices were checked against its vertices
  // when it was loaded or built).
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::size_t base = 0;
  for (const Mesh* m : meshes) {
    for (std::size_t t = 0; t + 2 < m->indices.size(); t += 3) {
      const std::array<std::uint32_t, 3> v{weld[base + m->indices[t]],
                                           weld[base + m->indices[t + 1]],
                                           weld[base + m->indices[t + 2]]};
      if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;  // degenerate after welding
      triangles.push_back(v);
    }
    base += m->positions.size();
  }

  // Undirected edges, stored once at their lower welded id (a compressed adjacency list:
  // a hash map of 3 edges per triangle cost 20x the whole glTF load of the mesh).
  EdgeCount result;
  result.triangles = triangles.size();
  std::vector<std::uint32_t> start(n + 1, 0);
  for (const auto& v : triangles)
    for (int e = 0; e < 3; ++e) ++start[std::min(v[std::size_t(e)], v[std::size_t(e + 1) % 3]) + 1];
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<std::uint32_t> other(start.back());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (const auto& v : triangles)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = v[std::size_t(e)], b = v[std::size_t(e + 1) % 3];
      other[fill[std::min(a, b)]++] = std::max(a, b);
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
