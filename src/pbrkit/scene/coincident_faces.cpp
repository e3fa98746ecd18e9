#include "pbrkit/scene/coincident_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

namespace pbrkit {

namespace {

// A world-space triangle and its plane, the normal's sign fixed (first clearly non-zero
// component positive) so that two faces in one plane facing opposite ways (a glass's base
// and the table under it) share it.
struct PlaneTriangle {
  std::array<glm::dvec3, 3> p;
  glm::dvec3 n{0.0};
  double d = 0.0;
  std::size_t index = 0;  ///< in its instance's mesh
};

bool plane_triangle(const Mesh& mesh, const glm::dmat4& m, std::size_t t, PlaneTriangle& out) {
  for (int k = 0; k < 3; ++k)
    out.p[std::size_t(k)] = glm::dvec3(
        m * glm::dvec4(glm::dvec3(mesh.positions[mesh.indices[3 * t + std::size_t(k)]]), 1.0));
  const glm::dvec3 c = glm::cross(out.p[1] - out.p[0], out.p[2] - out.p[0]);
  const double len = glm::length(c);
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  out.n = c / len;
  const glm::dvec3 a = glm::abs(out.n);
  const int lead = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
  if (out.n[lead] < 0.0) out.n = -out.n;
  out.d = glm::dot(out.n, out.p[0]);
  out.index = t;
  return true;
}

// Whether two triangles in one plane share an area wider than `eps`: the separating axis
// theorem in the plane, whose candidate axes are the edges' in-plane normals (touching
// along an edge or at a corner is not sharing an area).
bool overlap_in_plane(const PlaneTriangle& a, const PlaneTriangle& b, double eps) {
  for (const PlaneTriangle* t : {&a, &b})
    for (std::size_t k = 0; k < 3; ++k) {
      const glm::dvec3 edge = t->p[(k + 1) % 3] - t->p[k];
      const double len = glm::length(edge);
      if (!(len > 0.0)) continue;
      const glm::dvec3 axis = glm::cross(b.n, edge) / len;
      double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
      for (std::size_t j = 0; j < 3; ++j) {
        const double x = glm::dot(axis, a.p[j]), y = glm::dot(axis, b.p[j]);
        amin = std::min(amin, x);
        amax = std::max(amax, x);
        bmin = std::min(bmin, y);
        bmax = std::max(bmax, y);
      }
      if (amax <= bmin + eps || bmax <= amin + eps) return false;
    }
  return true;
}

struct DBounds {
  glm::dvec3 min{1e300}, max{-1e300};
  void extend(glm::dvec3 p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  bool overlaps(const DBounds& o, double eps) const {
    return min.x <= o.max.x + eps && o.min.x <= max.x + eps && min.y <= o.max.y + eps &&
           o.min.y <= max.y + eps && min.z <= o.max.z + eps && o.min.z <= max.z + eps;
  }
};

// The instances whose bounds may meet a query box, without comparing the box with every
// instance (a sweep along one axis, as in sort-and-sweep broad phases): the instances
// sorted by their bounds' lower end on the axis along which their centres spread most, so
// a query reads only those whose lower end lies within `reach` below its own range, where
// `reach` is the widest of them on that axis. The few much wider than most (a floor, a
// wall) would make that window the whole scene; they are kept apart and offered to every
// query.
class SweepCandidates {
 public:
  explicit SweepCandidates(const std::vector<DBounds>& bounds) {
    std::vector<std::size_t> valid;
    for (std::size_t i = 0; i < bounds.size(); ++i)
      if (bounds[i].min.x <= bounds[i].max.x) valid.push_back(i);
    if (valid.empty()) return;
    DBounds centres;
    for (const std::size_t i : valid) centres.extend(0.5 * (bounds[i].min + bounds[i].max));
    const glm::dvec3 spread = centres.max - centres.min;
    axis_ = spread.x >= spread.y && spread.x >= spread.z ? 0 : spread.y >= spread.z ? 1 : 2;
    // "Much wider": beyond 4 times the 90th percentile of the widths on the axis.
    std::vector<double> widths;
    widths.reserve(valid.size());
    for (const std::size_t i : valid) widths.push_back(bounds[i].max[axis_] - bounds[i].min[axis_]);
    const std::size_t k = valid.size() * 9 / 10;
    std::nth_element(widths.begin(), widths.begin() + std::ptrdiff_t(k), widths.end());
    const double wide = 4.0 * widths[k];
    for (const std::size_t i : valid) {
      const double w = bounds[i].max[axis_] - bounds[i].min[axis_];
      if (w > wide) {
        wide_.push_back(i);
      } else {
        sorted_.push_back({bounds[i].min[axis_], i});
        reach_ = std::max(reach_, w);
      }
    }
    std::sort(sorted_.begin(), sorted_.end());
  }

  /// The instances that may overlap `q` (widened by eps) on the sweep axis, ascending.
  std::vector<std::size_t> near(const DBounds& q, double eps) const {
    std::vector<std::size_t> out = wide_;
    const double lo = q.min[axis_] - reach_ - eps, hi = q.max[axis_] + eps;
    auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(lo, std::size_t(0)));
    for (; it != sorted_.end() && it->first <= hi; ++it) out.push_back(it->second);
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  int axis_ = 0;
  double reach_ = 0.0;
  std::vector<std::pair<double, std::size_t>> sorted_;  // (lower end on the axis, instance)
  std::vector<std::size_t> wide_;
};

bool transmissive(const Material& m) {
  return m.transmission.has_value() || m.diffuse_transmission.has_value() || m.volume.has_value();
}

}  // namespace

CoincidentFacesResult find_coincident_faces(const Scene& scene, std::size_t max_comparisons) {
  CoincidentFacesResult result;
  std::vector<std::size_t> glass;
  std::vector<bool> is_glass(scene.instances.size(), false);
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const int mesh = scene.instances[i].mesh;
    if (mesh >= 0 && std::size_t(mesh) < scene.meshes.size() &&
        transmissive(scene.material_of(scene.meshes[std::size_t(mesh)]))) {
      glass.push_back(i);
      is_glass[i] = true;
    }
  }
  result.transmissive = glass.size();
  if (glass.empty()) return result;

  // Each mesh's own bounds once, then each instance's world bounds from their corners.
  std::vector<DBounds> mesh_bounds(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    for (const glm::vec3& p : scene.meshes[m].positions) mesh_bounds[m].extend(glm::dvec3(p));
  std::vector<DBounds> bounds(scene.instances.size());
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    if (inst.mesh < 0 || std::size_t(inst.mesh) >= scene.meshes.size()) continue;
    const DBounds& b = mesh_bounds[std::size_t(inst.mesh)];
    if (b.min.x > b.max.x) continue;
    const glm::dmat4 m(inst.transform);
    for (int c = 0; c < 8; ++c)
      bounds[i].extend(
          glm::dvec3(m * glm::dvec4(c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y,
                                    c & 4 ? b.max.z : b.min.z, 1.0)));
  }

  const SweepCandidates candidates(bounds);
  std::size_t work = 0;
  for (const std::size_t g : glass) {
    const Instance& gi = scene.instances[g];
    const Mesh& gm = scene.meshes[std::size_t(gi.mesh)];
    const DBounds& gb = bounds[g];
    // 1e-6 of the object's size, or of its distance from the origin where float positions
    // round more coarsely than that.
    const double eps =
        1e-6 * std::max(glm::length(gb.max - gb.min), glm::length(0.5 * (gb.max + gb.min)));
    if (work + gm.triangle_count() > max_comparisons) {
      result.incomplete = true;
      return result;
    }
    std::vector<PlaneTriangle> tris;
    tris.reserve(gm.triangle_count());
    const glm::dmat4 gmat(gi.transform);
    for (std::size_t t = 0; t < gm.triangle_count(); ++t) {
      PlaneTriangle tri;
      if (plane_triangle(gm, gmat, t, tri)) tris.push_back(tri);
    }
    std::sort(tris.begin(), tris.end(),
              [](const PlaneTriangle& a, const PlaneTriangle& b) { return a.d < b.d; });
    work += tris.size();
    for (const std::size_t o : candidates.near(gb, eps)) {
      if (++work > max_comparisons) {
        result.incomplete = true;
        return result;
      }
      // Two transmissive instances are one pair, found from the first of them.
      if (o == g || (is_glass[o] && o < g) || !bounds[o].overlaps(gb, eps)) continue;
      const Instance& oi = scene.instances[o];
      const Mesh& om = scene.meshes[std::size_t(oi.mesh)];
      const glm::dmat4 omat(oi.transform);
      std::vector<bool> matched(gm.triangle_count(), false);
      std::size_t count = 0;
      for (std::size_t t = 0; t < om.triangle_count(); ++t) {
        if (++work > max_comparisons) {
          result.incomplete = true;
          return result;
        }
        PlaneTriangle a;
        if (!plane_triangle(om, omat, t, a)) continue;
        DBounds ab;
        for (const glm::dvec3& p : a.p) ab.extend(p);
        if (!ab.overlaps(gb, eps)) continue;
        // The glass's triangles whose plane offsets are near this one's; a slightly
        // different normal moves the offset by up to its angle times the distance from
        // the origin, which the window allows.
        const double window = eps + 1e-6 * glm::length(a.p[0]);
        auto b = std::lower_bound(tris.begin(), tris.end(), a.d - window,
                                  [](const PlaneTriangle& x, double d) { return x.d < d; });
        for (; b != tris.end() && b->d <= a.d + window; ++b) {
          ++work;
          if (matched[b->index] || glm::dot(a.n, b->n) < 1.0 - 1e-6) continue;
          bool in_plane = true;
          for (const glm::dvec3& p : a.p) in_plane &= std::fabs(glm::dot(b->n, p) - b->d) <= eps;
          if (!in_plane || !overlap_in_plane(a, *b, eps)) continue;
          matched[b->index] = true;
          ++count;
        }
      }
      if (count > 0) result.pairs.push_back({g, o, count});
    }
    ++result.checked;
  }
  return result;
}

std::vector<std::string> coincident_face_warnings(const Scene& scene,
                                                  const CoincidentFacesResult& result) {
  auto mesh_name = [&](std::size_t i) {
    const std::string& mesh = scene.meshes[std::size_t(scene.instances[i].mesh)].name;
    return mesh.empty() ? std::string("(unnamed)") : fmt::format("'{}'", mesh);
  };
  // "nodes[3] ('glass') lies on nodes[0] ('table')", or, for two primitives of one node,
  // "nodes[3]: its primitive 'cup.0' lies on its primitive 'cup.1'".
  auto pair = [&](std::size_t a, std::size_t b) {
    const int na = scene.instances[a].node, nb = scene.instances[b].node;
    if (na >= 0 && na == nb)
      return fmt::format("nodes[{}]: its primitive {} lies on its primitive {}", na, mesh_name(a),
                         mesh_name(b));
    auto name = [&](std::size_t i, int node) {
      return node >= 0 ? fmt::format("nodes[{}] ({})", node, mesh_name(i))
                       : fmt::format("the mesh {}", mesh_name(i));
    };
    return fmt::format("{} lies on {}", name(a, na), name(b, nb));
  };
  std::vector<std::string> out;
  constexpr std::size_t kListed = 4;
  for (std::size_t k = 0; k < result.pairs.size() && k < kListed; ++k) {
    const CoincidentFaces& c = result.pairs[k];
    out.push_back(fmt::format(
        "{}: {} of its transmissive triangles {} a plane and an area with "
        "the other's faces, so which of the two a ray meets first there is decided by "
        "rounding and the path tracer's image there is arbitrary (a glass standing in a "
        "table's plane renders murky); move one off the other (a glass 1 mm above the table)",
        pair(c.transmissive, c.other), c.triangles, c.triangles == 1 ? "shares" : "share"));
  }
  if (result.pairs.size() > kListed)
    out.push_back(fmt::format("{} more pairs of objects share a plane and an area, as above",
                              result.pairs.size() - kListed));
  return out;
}

}  // namespace pbrkit
