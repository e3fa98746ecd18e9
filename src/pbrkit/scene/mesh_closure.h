#pragma once
// Whether a mesh closes a volume, as KHR_materials_volume needs ("the mesh to which the
// material is attached defines the boundaries of a homogeneous medium and therefore must
// be manifold", README, Overview).
#include <cstddef>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

/// A mesh's edges after welding vertices with bit-equal positions (a glTF exporter splits
/// vertices at UV seams and normal creases; the copies keep the position). Triangles that
/// are degenerate after welding (two corners at one position) are skipped.
struct EdgeCount {
  std::size_t triangles = 0;  ///< triangles that are not degenerate after welding
  std::size_t unpaired = 0;   ///< edges not shared by exactly two of them (0 when closed)
  /// Every edge shared by exactly two triangles, and at least one triangle: what
  /// Mesh::closed holds for meshes whose material has a volume.
  bool closed() const { return triangles > 0 && unpaired == 0; }
};

EdgeCount count_edges(const Mesh& mesh);

}  // namespace pbrkit
