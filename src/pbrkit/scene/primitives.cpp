#include "pbrkit/scene/primitives.h"

#include <cmath>

#include "pbrkit/core/math.h"

namespace pbrkit {

Mesh make_uv_sphere(float radius, int segments, int rings) {
  Mesh mesh;
  mesh.name = "sphere";
  for (int j = 0; j <= rings; ++j) {
    const float v = float(j) / float(rings);
    // The poles and the seam (u = 1) repeat positions exactly, so that welding equal
    // positions closes the sphere (mesh_closure.h; sin(float(pi)) is not 0).
    const float theta = v * kPi;
    const float sin_theta = j == 0 || j == rings ? 0.0f : std::sin(theta);
    const float cos_theta = j == 0 ? 1.0f : j == rings ? -1.0f : std::cos(theta);
    for (int i = 0; i <= segments; ++i) {
      const float u = float(i) / float(segments);
      const float phi = i == segments ? 0.0f : u * 2.0f * kPi;
      const glm::vec3 n(sin_theta * std::sin(phi), cos_theta, sin_theta * std::cos(phi));
      mesh.positions.push_back(radius * n);
      mesh.normals.push_back(n);
      // d(position)/d(phi) direction: the tangent follows increasing u.
      mesh.tangents.push_back(glm::vec4(std::cos(phi), 0.0f, -std::sin(phi), 1.0f));
      mesh.texcoords0.push_back({u, v});
    }
  }
  const int row = segments + 1;
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      const std::uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
      // Skip the degenerate triangles at the poles.
      if (j != 0) mesh.indices.insert(mesh.indices.end(), {a, c, b});
      if (j != rings - 1) mesh.indices.insert(mesh.indices.end(), {b, c, d});
    }
  }
  return mesh;
}

Mesh make_quad(glm::vec3 origin, glm::vec3 edge_u, glm::vec3 edge_v) {
  Mesh mesh;
  mesh.name = "quad";
  const glm::vec3 n = glm::normalize(glm::cross(edge_u, edge_v));
  const glm::vec3 t = glm::normalize(edge_u);
  const glm::vec3 corners[4] = {origin, origin + edge_u, origin + edge_u + edge_v, origin + edge_v};
  const glm::vec2 uvs[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  for (int i = 0; i < 4; ++i) {
    mesh.positions.push_back(corners[i]);
    mesh.normals.push_back(n);
    mesh.tangents.push_back(glm::vec4(t, 1.0f));
    mesh.texcoords0.push_back(uvs[i]);
  }
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

Mesh make_box(glm::vec3 lo, glm::vec3 hi, bool inward) {
  Mesh box;
  box.name = "box";
  const glm::vec3 d = hi - lo;
  // Six faces, each (origin, edge_u, edge_v) with cross(edge_u, edge_v) pointing outwards.
  const glm::vec3 faces[6][3] = {
      {{lo.x, lo.y, hi.z}, {d.x, 0, 0}, {0, d.y, 0}},   // +Z
      {{hi.x, lo.y, lo.z}, {-d.x, 0, 0}, {0, d.y, 0}},  // -Z
      {{hi.x, lo.y, hi.z}, {0, 0, -d.z}, {0, d.y, 0}},  // +X
      {{lo.x, lo.y, lo.z}, {0, 0, d.z}, {0, d.y, 0}},   // -X
      {{lo.x, hi.y, hi.z}, {d.x, 0, 0}, {0, 0, -d.z}},  // +Y
      {{lo.x, lo.y, lo.z}, {d.x, 0, 0}, {0, 0, d.z}},   // -Y
  };
  for (const auto& f : faces) {
    Mesh q = inward ? make_quad(f[0] + f[1], -f[1], f[2]) : make_quad(f[0], f[1], f[2]);
    const auto base = std::uint32_t(box.positions.size());
    box.positions.insert(box.positions.end(), q.positions.begin(), q.positions.end());
    box.normals.insert(box.normals.end(), q.normals.begin(), q.normals.end());
    box.tangents.insert(box.tangents.end(), q.tangents.begin(), q.tangents.end());
    box.texcoords0.insert(box.texcoords0.end(), q.texcoords0.begin(), q.texcoords0.end());
    for (auto i : q.indices) box.indices.push_back(base + i);
  }
  return box;
}

int add_mesh_instance(Scene& scene, Mesh mesh, int material, const glm::mat4& transform) {
  mesh.material = material;
  scene.meshes.push_back(std::move(mesh));
  const int index = int(scene.meshes.size()) - 1;
  scene.instances.push_back({index, transform, -1});
  return index;
}

}  // namespace pbrkit
