#pragma once
// Procedural meshes for built-in scenes and tests: UV spheres, quads and boxes with
// normals, tangents and texture coordinates.
#include <glm/glm.hpp>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

/// A UV sphere centred at the origin: `segments` around +Y, `rings` from pole to pole.
/// Normals are the exact sphere normals; u runs with longitude, v from the north pole.
Mesh make_uv_sphere(float radius, int segments = 64, int rings = 32);

/// A quad with corner `origin` spanned by edges `edge_u` and `edge_v`; its normal is
/// normalize(cross(edge_u, edge_v)) (counter-clockwise winding seen from that side).
Mesh make_quad(glm::vec3 origin, glm::vec3 edge_u, glm::vec3 edge_v);

/// An axis-aligned box; faces point outwards, or inwards when `inward` (a closed room).
Mesh make_box(glm::vec3 min, glm::vec3 max, bool inward = false);

/// Appends `mesh` to `scene` with `material` and one instance with `transform`;
/// returns the mesh index.
int add_mesh_instance(Scene& scene, Mesh mesh, int material,
                      const glm::mat4& transform = glm::mat4(1.0f));

}  // namespace pbrkit
