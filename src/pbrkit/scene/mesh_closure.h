#pragma once
// Whether a mesh closes a volume, as KHR_materials_volume needs ("the mesh to which the
// material is attached defines the boundaries of a homogeneous medium and therefore must
// be manifold", README, Overview).
#include <cstddef>
#include <span>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

/// How close two positions must be to weld, relative to the diagonal of the bounding box
/// of the surface being checked. Exporters split vertices at UV seams and normal creases;
/// the copies keep the position up to rounding: a UV sphere whose seam is written as
/// (sin(2 pi), cos(2 pi)) puts it 2.4e-16 (double) or 1.7e-7 (float) of the radius away
/// from the first column. 1e-6 of the diagonal welds those and nothing a modeller would
/// call two vertices (1 um on a 1 m object).
inline constexpr double kWeldTolerance = 1e-6;

/// A surface's edges after welding vertices closer than kWeldTolerance times its bounding
/// box's diagonal. Triangles that are degenerate after welding (two corners at one
/// position) are skipped.
struct EdgeCount {
  std::size_t triangles = 0;  ///< triangles that are not degenerate after welding
  std::size_t unpaired = 0;   ///< edges not shared by exactly two of them (0 when closed)
  /// Every edge shared by exactly two triangles, and at least one triangle: what
  /// Mesh::closed holds for meshes whose material has a volume.
  bool closed() const { return triangles > 0 && unpaired == 0; }
};

/// The edges of one primitive.
EdgeCount count_edges(const Mesh& mesh);
/// The edges of the surface the primitives make together (a shell split across the
/// primitives of one glTF mesh), welded across primitives.
EdgeCount count_edges(std::span<const Mesh* const> meshes);

}  // namespace pbrkit
