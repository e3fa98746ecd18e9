#include "pbrkit/scene/mesh_attributes.h"

#include <cmath>

namespace pbrkit {

namespace {

template <typename T>
void unweld(std::vector<T>& values, const std::vector<std::uint32_t>& indices) {
  if (values.empty()) return;
  std::vector<T> out;
  out.reserve(indices.size());
  for (std::uint32_t i : indices) out.push_back(values[i]);
  values.swap(out);
}

// Any unit vector perpendicular to n (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited").
glm::vec3 perpendicular(glm::vec3 n) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  return {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
}

}  // namespace

void generate_flat_normals(Mesh& mesh) {
  unweld(mesh.positions, mesh.indices);
  unweld(mesh.tangents, mesh.indices);
  unweld(mesh.texcoords0, mesh.indices);
  unweld(mesh.texcoords1, mesh.indices);
  unweld(mesh.colors0, mesh.indices);
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0, 0, 1));
  for (std::size_t t = 0; t + 2 < mesh.positions.size(); t += 3) {
    const glm::vec3 n = glm::cross(mesh.positions[t + 1] - mesh.positions[t],
                                   mesh.positions[t + 2] - mesh.positions[t]);
    const float len = glm::length(n);
    const glm::vec3 unit = (len > 0.0f && std::isfinite(len)) ? n / len : glm::vec3(0, 0, 1);
    mesh.normals[t] = mesh.normals[t + 1] = mesh.normals[t + 2] = unit;
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = std::uint32_t(i);
}

void generate_tangents(Mesh& mesh, int texcoord_set) {
  const std::vector<glm::vec2>& uv = texcoord_set == 1 ? mesh.texcoords1 : mesh.texcoords0;
  const std::size_t n = mesh.positions.size();
  std::vector<glm::vec3> tan(n, glm::vec3(0.0f)), bitan(n, glm::vec3(0.0f));
  if (uv.size() == n) {
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
      const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0];
      const glm::vec3 e2 = mesh.positions[i2] - mesh.positions[i0];
      const glm::vec2 d1 = uv[i1] - uv[i0], d2 = uv[i2] - uv[i0];
      const float det = d1.x * d2.y - d2.x * d1.y;
      if (!(std::fabs(det) > 1e-20f)) continue;
      // Solve [e1 e2] = [dP/du dP/dv] [d1 d2] (Lengyel, "Computing Tangent Space Basis
      // Vectors for an Arbitrary Mesh", 2001); the unnormalised sum weights by UV area.
      const float r = 1.0f / det;
      const glm::vec3 sdir = (e1 * d2.y - e2 * d1.y) * r;
      const glm::vec3 tdir = (e2 * d1.x - e1 * d2.x) * r;
      if (!std::isfinite(sdir.x + sdir.y + sdir.z + tdir.x + tdir.y + tdir.z)) continue;
      for (std::uint32_t i : {i0, i1, i2}) {
        tan[i] += sdir;
        bitan[i] += tdir;
      }
    }
  }
  mesh.tangents.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 nrm = mesh.normals[i];
    glm::vec3 t = tan[i] - nrm * glm::dot(nrm, tan[i]);  // Gram-Schmidt
    const float len = glm::length(t);
    t = (len > 1e-20f && std::isfinite(len)) ? t / len : perpendicular(nrm);
    // glTF: bitangent = cross(normal, tangent.xyz) * tangent.w.
    const float w = glm::dot(glm::cross(nrm, t), bitan[i]) < 0.0f ? -1.0f : 1.0f;
    mesh.tangents[i] = glm::vec4(t, w);
  }
}

void ensure_tangents(Mesh& mesh, const Material& mat) {
  if (!mesh.tangents.empty()) return;
  const TextureRef* uv_source = mat.normal_texture.valid() ? &mat.normal_texture : nullptr;
  if (!uv_source && mat.clearcoat && mat.clearcoat->normal_texture.valid())
    uv_source = &mat.clearcoat->normal_texture;
  if (!uv_source && mat.anisotropy && mat.anisotropy->texture.valid())
    uv_source = &mat.anisotropy->texture;
  if (uv_source || mat.anisotropy) generate_tangents(mesh, uv_source ? uv_source->texcoord : 0);
}

}  // namespace pbrkit
