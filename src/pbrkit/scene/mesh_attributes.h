#pragma once
// Attributes a glTF file may leave out and the loader must generate: flat normals (glTF
// 2.0 section 3.7.2.1) and tangents for normal mapping.
#include "pbrkit/scene/scene.h"

namespace pbrkit {

/// Gives every triangle its own three vertices with the face normal (the spec's "flat
/// normals"); other attributes are duplicated along. Degenerate triangles get +Z.
void generate_flat_normals(Mesh& mesh);

/// Per-vertex tangents from the UV layout of `texcoord_set` (0 or 1): each triangle's
/// dP/du is accumulated at its vertices, then Gram-Schmidt orthogonalised against the
/// normal, with handedness w = sign(dot(cross(N, T), dP/dv)). This matches MikkTSpace
/// (which glTF names) for well-behaved UV layouts but is not the full algorithm: it does
/// not split vertices at UV mirror seams. Requires normals; without UVs (or where they
/// are degenerate) an arbitrary tangent perpendicular to the normal is used.
void generate_tangents(Mesh& mesh, int texcoord_set = 0);

/// Generates tangents when the mesh has none and `material` needs a tangent frame: for its
/// normal maps (base and clearcoat) and for anisotropy, whose README requires one
/// (computed as for normal maps when TANGENT is absent).
void ensure_tangents(Mesh& mesh, const Material& material);

}  // namespace pbrkit
