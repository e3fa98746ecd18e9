#pragma once
// Procedural meshes for built-in scenes and tests: UV spheres, quads, boxes, extruded
// polygons (prisms) and surfaces of revolution (a glass, a liquid) with normals, tangents
// and texture coordinates; and a checker texture for backdrops.
#include <vector>

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

/// A closed prism: the convex polygon `outline` (x, z pairs, either winding) extruded along
/// +Y from y = 0 to `height`, with flat side faces and caps. Faces point outwards.
Mesh make_prism(const std::vector<glm::vec2>& outline, float height);

/// A closed surface of revolution about +Y: the profile (radius, y) pairs, from a point on
/// the axis (radius 0) around the solid's section back to a point on the axis, turned
/// `segments` times. Each profile segment is flat across (its own normals: sharp edges at
/// the profile's corners) and smooth around; the outward normal of segment (a, b) is
/// (b.y - a.y, a.x - b.x) in the (radius, y) plane, so a profile that goes out along the
/// bottom, up the outside and in along the top gives outward faces. Positions repeat
/// exactly at the seam and on the axis, so the mesh welds closed (mesh_closure.h).
Mesh make_lathe(const std::vector<glm::vec2>& profile, int segments = 64);

/// A `size` x `size` checker of `checks` x `checks` squares alternating `a` and `b` (linear
/// RGB, the top-left square `a`), flagged sRGB (a base colour), repeating, with mips.
Texture make_checker_texture(int size, int checks, glm::vec3 a, glm::vec3 b);

/// Appends `mesh` to `scene` with `material` and one instance with `transform`;
/// returns the mesh index. A mesh whose material has a volume (thickness > 0) gets
/// Mesh::closed computed, as the glTF loader does.
int add_mesh_instance(Scene& scene, Mesh mesh, int material,
                      const glm::mat4& transform = glm::mat4(1.0f));

}  // namespace pbrkit
