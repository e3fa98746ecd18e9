#include "pbrkit/pt/shading.h"

#include <cmath>

namespace pbrkit {

namespace {

glm::vec4 lookup(const Scene& scene, const TextureRef& ref, const SurfaceHit& hit) {
  if (!ref.valid() || ref.texture >= int(scene.textures.size())) return glm::vec4(1.0f);
  const Texture& tex = scene.textures[std::size_t(ref.texture)];
  if (tex.mips.empty()) return glm::vec4(1.0f);
  return tex.sample(texture_uv(ref, hit), 0.0f);
}

}  // namespace

glm::vec2 texture_uv(const TextureRef& ref, const SurfaceHit& hit) {
  glm::vec2 uv = hit.uv[ref.texcoord == 1 ? 1 : 0];
  if (ref.transform) uv = glm::vec2(ref.transform->matrix() * glm::vec3(uv, 1.0f));
  return uv;
}

float material_alpha(const Scene& scene, const Material& m, const SurfaceHit& hit) {
  return m.base_color_factor.a * lookup(scene, m.base_color_texture, hit).a * hit.color.a;
}

glm::vec3 material_emission(const Scene& scene, const Material& m, const SurfaceHit& hit) {
  const glm::vec3 e = m.emissive_factor * m.emissive_strength;
  if (e == glm::vec3(0.0f)) return e;
  return e * glm::vec3(lookup(scene, m.emissive_texture, hit));
}

ShadingInputs shade_inputs(const Scene& scene, const Material& m, const SurfaceHit& hit) {
  ShadingInputs s;
  const glm::vec4 bc = lookup(scene, m.base_color_texture, hit);
  s.base_color = glm::vec3(m.base_color_factor) * glm::vec3(bc) * glm::vec3(hit.color);
  const glm::vec4 mr = lookup(scene, m.metallic_roughness_texture, hit);
  s.metallic = m.metallic_factor * mr.b;  // glTF: metalness in B, roughness in G
  s.roughness = m.roughness_factor * mr.g;
  // The shading normal goes to the viewer's side of the triangle: the back of a
  // double-sided surface, and meshes whose vertex normals disagree with their winding
  // (common in exported files), would otherwise be shaded from inside. As in the glTF
  // spec and the Khronos sample viewer, the whole normal-mapped normal is reversed (the
  // same rule as pbr_fragment.glsl), so both renderers agree.
  const float side = glm::dot(hit.ns, hit.ng) < 0.0f ? -1.0f : 1.0f;
  s.ns = side * hit.ns;
  if (m.normal_texture.valid() && hit.tangent != glm::vec4(0.0f)) {
    // Tangent-space normal map (glTF 2.0 section 3.9.3): n = normalize(T x + B y + N z)
    // with x, y scaled by normalTextureInfo.scale; B = cross(N, T) * w. The tangent is
    // re-orthogonalised against the interpolated normal (Gram-Schmidt).
    const glm::vec3 n = hit.ns;
    glm::vec3 t = glm::vec3(hit.tangent) - n * glm::dot(n, glm::vec3(hit.tangent));
    const float tl = glm::length(t);
    if (tl > 0.0f) {
      t /= tl;
      const glm::vec3 b = glm::cross(n, t) * (hit.tangent.w < 0.0f ? -1.0f : 1.0f);
      glm::vec3 c = glm::vec3(lookup(scene, m.normal_texture, hit)) * 2.0f - 1.0f;
      c.x *= m.normal_scale;
      c.y *= m.normal_scale;
      const glm::vec3 mapped = t * c.x + b * c.y + n * c.z;
      const float ml = glm::length(mapped);
      if (ml > 0.0f && std::isfinite(ml)) s.ns = side * mapped / ml;
    }
  }
  return s;
}

}  // namespace pbrkit
