#include "pbrkit/scene/primitives.h"

#include <cmath>
#include <cstdint>
#include <utility>

#include "pbrkit/core/math.h"
#include "pbrkit/scene/mesh_closure.h"

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
  // Every corner is lo or hi on each axis, exactly: lo + (hi - lo) need not round to hi
  // (-0.2 + 1.0 != 0.8 in float), and faces that meet at corners a bit apart leave the box
  // open to Mesh::closed's welding, which would render a volume on it thin-walled.
  for (glm::vec3& p : box.positions)
    for (int c = 0; c < 3; ++c)
      p[c] = std::fabs(p[c] - lo[c]) <= std::fabs(p[c] - hi[c]) ? lo[c] : hi[c];
  return box;
}

// Appends the triangle (a, b, c) of `mesh`, flipped if its face normal points against
// `outward`; a triangle with two equal corners (on an axis or a pole) is left out.
void add_triangle(Mesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                  glm::vec3 outward) {
  const glm::vec3 pa = mesh.positions[a], pb = mesh.positions[b], pc = mesh.positions[c];
  if (pa == pb || pb == pc || pc == pa) return;
  if (glm::dot(glm::cross(pb - pa, pc - pa), outward) < 0.0f) std::swap(b, c);
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

Mesh make_prism(const std::vector<glm::vec2>& outline, float height) {
  Mesh mesh;
  mesh.name = "prism";
  const std::size_t n = outline.size();
  glm::vec2 centre(0.0f);
  for (const glm::vec2& p : outline) centre += p / float(n);
  auto vertex = [&](glm::vec2 p, float y, glm::vec3 normal, glm::vec3 tangent, glm::vec2 uv) {
    mesh.positions.push_back({p.x, y, p.y});
    mesh.normals.push_back(normal);
    mesh.tangents.push_back(glm::vec4(tangent, 1.0f));
    mesh.texcoords0.push_back(uv);
    return std::uint32_t(mesh.positions.size() - 1);
  };
  // Side faces: one flat quad per outline edge, its normal away from the centre.
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec2 a = outline[i], b = outline[(i + 1) % n];
    const glm::vec2 mid = 0.5f * (a + b);
    glm::vec3 normal = glm::normalize(glm::vec3(b.y - a.y, 0.0f, a.x - b.x));
    if (glm::dot(glm::vec2(normal.x, normal.z), mid - centre) < 0.0f) normal = -normal;
    const glm::vec3 tangent = glm::normalize(glm::vec3(b.x - a.x, 0.0f, b.y - a.y));
    const std::uint32_t v0 = vertex(a, 0.0f, normal, tangent, {0, 1});
    const std::uint32_t v1 = vertex(b, 0.0f, normal, tangent, {1, 1});
    const std::uint32_t v2 = vertex(b, height, normal, tangent, {1, 0});
    const std::uint32_t v3 = vertex(a, height, normal, tangent, {0, 0});
    add_triangle(mesh, v0, v1, v2, normal);
    add_triangle(mesh, v0, v2, v3, normal);
  }
  // Caps: fans over the convex outline.
  for (const float y : {0.0f, height}) {
    const glm::vec3 normal(0.0f, y == 0.0f ? -1.0f : 1.0f, 0.0f);
    const auto first = std::uint32_t(mesh.positions.size());
    for (const glm::vec2& p : outline)
      vertex(p, y, normal, {1, 0, 0}, glm::vec2(0.5f) + 0.5f * (p - centre));
    for (std::uint32_t i = 1; i + 1 < n; ++i)
      add_triangle(mesh, first, first + i, first + i + 1, normal);
  }
  return mesh;
}

Mesh make_lathe(const std::vector<glm::vec2>& profile, int segments) {
  Mesh mesh;
  mesh.name = "lathe";
  // v runs along the profile's length.
  std::vector<float> length(profile.size(), 0.0f);
  for (std::size_t k = 1; k < profile.size(); ++k)
    length[k] = length[k - 1] + glm::distance(profile[k - 1], profile[k]);
  for (std::size_t k = 0; k + 1 < profile.size(); ++k) {
    const glm::vec2 a = profile[k], b = profile[k + 1];
    if (a == b) continue;
    // The segment's outward normal in the (radius, y) plane.
    const glm::vec2 n = glm::normalize(glm::vec2(b.y - a.y, a.x - b.x));
    const auto first = std::uint32_t(mesh.positions.size());
    for (int i = 0; i <= segments; ++i) {
      // The seam (i = segments) repeats i = 0 exactly.
      const float phi = i == segments ? 0.0f : 2.0f * kPi * float(i) / float(segments);
      const float s = std::sin(phi), c = std::cos(phi);
      for (const std::size_t end : {k, k + 1}) {
        const glm::vec2 p = profile[end];
        mesh.positions.push_back({p.x * s, p.y, p.x * c});
        mesh.normals.push_back({n.x * s, n.y, n.x * c});
        mesh.tangents.push_back({c, 0.0f, -s, 1.0f});
        mesh.texcoords0.push_back({float(i) / float(segments), 1.0f - length[end] / length.back()});
      }
    }
    for (int i = 0; i < segments; ++i) {
      const std::uint32_t a0 = first + 2 * std::uint32_t(i), b0 = a0 + 1, a1 = a0 + 2, b1 = a0 + 3;
      // The face normal of the quad's middle, for add_triangle's orientation check.
      const float phi = 2.0f * kPi * (float(i) + 0.5f) / float(segments);
      const glm::vec3 outward(n.x * std::sin(phi), n.y, n.x * std::cos(phi));
      add_triangle(mesh, a0, a1, b0, outward);
      add_triangle(mesh, a1, b1, b0, outward);
    }
  }
  return mesh;
}

Texture make_checker_texture(int size, int checks, glm::vec3 a, glm::vec3 b) {
  Image image(size, size, 4, 1.0f);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool first = ((x * checks / size) + (y * checks / size)) % 2 == 0;
      const glm::vec3 c = first ? a : b;
      float* texel = image.pixel(x, y);
      texel[0] = c.r;
      texel[1] = c.g;
      texel[2] = c.b;
    }
  Texture texture = Texture::from_linear(std::move(image), true);
  texture.name = "checker";
  return texture;
}

int add_mesh_instance(Scene& scene, Mesh mesh, int material, const glm::mat4& transform) {
  mesh.material = material;
  if (material >= 0 && std::size_t(material) < scene.materials.size()) {
    const Material& m = scene.materials[std::size_t(material)];
    if (m.volume && m.volume->thickness_factor > 0.0f) mesh.closed = count_edges(mesh).closed();
  }
  scene.meshes.push_back(std::move(mesh));
  const int index = int(scene.meshes.size()) - 1;
  scene.instances.push_back({index, transform, -1});
  return index;
}

}  // namespace pbrkit
