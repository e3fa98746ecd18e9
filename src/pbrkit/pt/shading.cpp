#include "pbrkit/pt/shading.h"

#include <cmath>

namespace pbrkit {

namespace {

// The ray-cone level of detail of `tex` at the hit (Akenine-Moller et al. 2021, eq. 34):
// lambda = Delta + log2(w / |n.d|), with Delta = 0.5 log2(t_a / p_a) the triangle's texel
// area t_a (uv area x texture size, KHR_texture_transform's scale included) over its world
// area p_a. 0 (level 0) without a footprint or for a degenerate triangle.
float texture_lod(const Texture& tex, const TextureRef& ref, const SurfaceHit& hit) {
  if (!(hit.footprint > 0.0f) || !(hit.area > 0.0f)) return 0.0f;
  float uv_area = hit.uv_area[ref.texcoord == 1 ? 1 : 0];
  if (ref.transform) uv_area *= std::abs(ref.transform->scale.x * ref.transform->scale.y);
  const float texel_area = uv_area * float(tex.width()) * float(tex.height());
  if (!(texel_area > 0.0f)) return 0.0f;
  const float lod = 0.5f * std::log2(texel_area / hit.area) + std::log2(hit.footprint);
  return std::isfinite(lod) ? lod : 0.0f;
}

glm::vec4 lookup(const Scene& scene, const TextureRef& ref, const SurfaceHit& hit) {
  if (!ref.valid() || ref.texture >= int(scene.textures.size())) return glm::vec4(1.0f);
  const Texture& tex = scene.textures[std::size_t(ref.texture)];
  if (tex.empty()) return glm::vec4(1.0f);
  return tex.sample(texture_uv(ref, hit), texture_lod(tex, ref, hit));
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

namespace {

// Tangent-space normal map (glTF 2.0 section 3.9.3): n = normalize(T x + B y + N z) with x, y
// scaled by the texture's scale; B = cross(N, T) * w. The tangent is re-orthogonalised
// against the interpolated normal `n` (Gram-Schmidt). Returns `n` when the mesh has no
// tangents or the result is degenerate.
glm::vec3 map_normal(const Scene& scene, const TextureRef& ref, float scale, const SurfaceHit& hit,
                     glm::vec3 n) {
  glm::vec3 t = glm::vec3(hit.tangent) - n * glm::dot(n, glm::vec3(hit.tangent));
  const float tl = glm::length(t);
  if (!(tl > 0.0f)) return n;
  t /= tl;
  const glm::vec3 b = glm::cross(n, t) * (hit.tangent.w < 0.0f ? -1.0f : 1.0f);
  glm::vec3 c = glm::vec3(lookup(scene, ref, hit)) * 2.0f - 1.0f;
  c.x *= scale;
  c.y *= scale;
  const glm::vec3 mapped = t * c.x + b * c.y + n * c.z;
  const float ml = glm::length(mapped);
  return ml > 0.0f && std::isfinite(ml) ? mapped / ml : n;
}

// KHR_materials_anisotropy: the direction (anisotropyTexture.rg remapped to [-1, 1], (1, 0)
// without it) rotated by anisotropyRotation in the tangent plane, T = normalize(TBN dir),
// made normal to the shading normal. 0 when the mesh has no tangents.
glm::vec3 anisotropy_direction(const Scene& scene, const AnisotropyExtension& a,
                               const SurfaceHit& hit, glm::vec3 ns) {
  if (hit.tangent == glm::vec4(0.0f)) return glm::vec3(0.0f);
  glm::vec2 d(1.0f, 0.0f);
  if (a.texture.valid()) d = glm::vec2(lookup(scene, a.texture, hit)) * 2.0f - 1.0f;
  const float c = std::cos(a.rotation), s = std::sin(a.rotation);
  d = glm::vec2(c * d.x - s * d.y, s * d.x + c * d.y);
  const glm::vec3 n = hit.ns;
  const glm::vec3 t = glm::vec3(hit.tangent);
  const glm::vec3 b = glm::cross(n, t) * (hit.tangent.w < 0.0f ? -1.0f : 1.0f);
  glm::vec3 dir = t * d.x + b * d.y;
  dir -= ns * glm::dot(ns, dir);
  const float l = glm::length(dir);
  return l > 1e-6f && std::isfinite(l) ? dir / l : glm::vec3(0.0f);
}

}  // namespace

ShadingInputs shade_inputs(const Scene& scene, const Material& m, const SurfaceHit& hit) {
  ShadingInputs s;
  BaseLayer& base = s.params.base;
  const glm::vec4 bc = lookup(scene, m.base_color_texture, hit);
  base.base_color = glm::vec3(m.base_color_factor) * glm::vec3(bc) * glm::vec3(hit.color);
  s.unlit = m.unlit;
  if (m.unlit) return s;
  const glm::vec4 mr = lookup(scene, m.metallic_roughness_texture, hit);
  base.metallic = m.metallic_factor * mr.b;  // glTF: metalness in B, roughness in G
  base.roughness = m.roughness_factor * mr.g;
  // The shading normal goes to the viewer's side of the triangle: the back of a
  // double-sided surface, and meshes whose vertex normals disagree with their winding
  // (common in exported files), would otherwise be shaded from inside. As in the glTF
  // spec and the Khronos sample viewer, the whole normal-mapped normal is reversed (the
  // same rule as pbr_fragment.glsl), so both renderers agree.
  const float side = glm::dot(hit.ns, hit.ng) < 0.0f ? -1.0f : 1.0f;
  s.ns = side * hit.ns;
  if (m.normal_texture.valid() && hit.tangent != glm::vec4(0.0f))
    s.ns = side * map_normal(scene, m.normal_texture, m.normal_scale, hit, hit.ns);

  // The extensions (their READMEs' "factor x texture channel" rules).
  base.ior = m.ior;
  if (m.specular) {
    base.specular = m.specular->factor * lookup(scene, m.specular->texture, hit).a;
    base.specular_color =
        m.specular->color_factor * glm::vec3(lookup(scene, m.specular->color_texture, hit));
  }
  if (m.anisotropy) {
    s.tangent = anisotropy_direction(scene, *m.anisotropy, hit, s.ns);
    if (s.tangent != glm::vec3(0.0f))
      base.anisotropy = m.anisotropy->strength * lookup(scene, m.anisotropy->texture, hit).b;
  }
  if (m.iridescence) {
    const IridescenceExtension& ir = *m.iridescence;
    base.iridescence = ir.factor * lookup(scene, ir.texture, hit).r;
    base.iridescence_ior = ir.ior;
    // Without a thickness texture the film is thickness_max thick (README).
    const float g =
        ir.thickness_texture.valid() ? lookup(scene, ir.thickness_texture, hit).g : 1.0f;
    base.iridescence_thickness = glm::mix(ir.thickness_min, ir.thickness_max, g);
  }
  if (m.sheen) {
    s.params.sheen.color =
        m.sheen->color_factor * glm::vec3(lookup(scene, m.sheen->color_texture, hit));
    s.params.sheen.roughness =
        m.sheen->roughness_factor * lookup(scene, m.sheen->roughness_texture, hit).a;
  }
  // KHR_materials_transmission, _volume, _diffuse_transmission. The ratio of iors across
  // the surface depends on the medium the ray is in: the integrator sets it (the material's
  // ior against vacuum here).
  s.params.transmission.eta = m.ior;
  if (m.transmission)
    s.params.transmission.weight =
        m.transmission->factor * lookup(scene, m.transmission->texture, hit).r;
  if (m.diffuse_transmission) {
    const DiffuseTransmissionExtension& d = *m.diffuse_transmission;
    s.params.diffuse_transmission.weight = d.factor * lookup(scene, d.texture, hit).a;
    s.params.diffuse_transmission.color =
        d.color_factor * glm::vec3(lookup(scene, d.color_texture, hit));
  }
  // Thin-walled unless a volume of non-zero thickness is behind the surface (volume
  // README); the integrator also makes open meshes thin. The volume is entered by either
  // kind of transmission: the volume README's "combined with an extension which allows
  // light to transmit through the surface", which the diffuse_transmission README's
  // translucent (volumetric) case is, its light then absorbed along its path inside.
  if (m.transmission || m.diffuse_transmission) {
    float thickness = 0.0f;
    if (m.volume)
      thickness =
          m.volume->thickness_factor * (m.volume->thickness_texture.valid()
                                            ? lookup(scene, m.volume->thickness_texture, hit).g
                                            : 1.0f);
    s.params.transmission.thin_walled = !(thickness > 0.0f);
  }
  if (m.clearcoat) {
    const ClearcoatExtension& cc = *m.clearcoat;
    s.params.coat.weight = cc.factor * lookup(scene, cc.texture, hit).r;
    s.params.coat.roughness = cc.roughness_factor * lookup(scene, cc.roughness_texture, hit).g;
    // The coat has its own normal map, and none means the geometry's (interpolated)
    // normal, not the base's normal map (clearcoat README).
    s.coat_normal = s.params.coat.weight > 0.0f && cc.normal_texture.valid()
                        ? side * map_normal(scene, cc.normal_texture, cc.normal_scale, hit, hit.ns)
                        : side * hit.ns;
  }
  return s;
}

}  // namespace pbrkit
