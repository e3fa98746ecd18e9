// The surface's material inputs: the glTF factors times their textures, one function per
// extension, as the path tracer's shade_inputs (pt/shading.cpp) gathers them for its
// ShadingInputs (the Khronos glTF-Sample-Viewer's material_info.glsl is the model). The
// fragment shader (pbr_fragment.glsl) shades what material_inputs() returns; nothing here
// depends on a light, the environment or the frame behind the surface.
//
// Reads the varyings of pbr_vertex.glsl and the prelude's SLOT_<slot>, BINDING_<slot> and
// HAS_<slot> (surface_bindings.h, shader_permutations.h); needs brdf.glsl (BaseLayer) and
// the MATERIAL_* and HAS_COLOR_0 feature defines of pbr_fragment.glsl.
#include "brdf.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec4 vTangent;
in vec2 vTexcoord0;
in vec2 vTexcoord1;
#if HAS_COLOR_0
in vec4 vColor;
#endif

// Material (glTF metallic-roughness, factors times textures).
uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor;
uniform float uRoughnessFactor;
uniform vec3 uEmissive;  // factor x KHR_materials_emissive_strength
uniform float uNormalScale;
uniform float uOcclusionStrength;
uniform float uMetallicOverride;   // < 0: none (the viewer's override)
uniform float uRoughnessOverride;  // < 0: none
// Per texture slot (scene.h's TextureSlot): which TEXCOORD set, the KHR_texture_transform
// matrix.
uniform int uTexcoordSet[TEXTURE_SLOT_COUNT];
uniform mat3 uTextureTransform[TEXTURE_SLOT_COUNT];
layout(binding = BINDING_BASE_COLOR_TEXTURE) uniform sampler2D uBaseColorTexture;
layout(binding = BINDING_METALLIC_ROUGHNESS_TEXTURE) uniform sampler2D uMetallicRoughnessTexture;
layout(binding = BINDING_NORMAL_TEXTURE) uniform sampler2D uNormalTexture;
layout(binding = BINDING_OCCLUSION_TEXTURE) uniform sampler2D uOcclusionTexture;
layout(binding = BINDING_EMISSIVE_TEXTURE) uniform sampler2D uEmissiveTexture;
// The extensions' factors (the READMEs' defaults when absent) and textures: slot t >= 5 on
// its unit BINDING_<slot> (surface_bindings.h).
uniform float uIor;                  // KHR_materials_ior
uniform float uSpecularFactor;       // KHR_materials_specular
uniform vec3 uSpecularColorFactor;
uniform float uClearcoatFactor;      // KHR_materials_clearcoat
uniform float uClearcoatRoughnessFactor;
uniform float uClearcoatNormalScale;
uniform vec3 uSheenColorFactor;      // KHR_materials_sheen
uniform float uSheenRoughnessFactor;
uniform float uAnisotropyStrength;   // KHR_materials_anisotropy
uniform float uAnisotropyRotation;   // radians from the tangent
uniform float uIridescenceFactor;    // KHR_materials_iridescence
uniform float uIridescenceIor;
uniform float uIridescenceThicknessMinimum;  // nm
uniform float uIridescenceThicknessMaximum;
layout(binding = BINDING_SPECULAR_TEXTURE) uniform sampler2D uSpecularTexture;
layout(binding = BINDING_SPECULAR_COLOR_TEXTURE) uniform sampler2D uSpecularColorTexture;
layout(binding = BINDING_CLEARCOAT_TEXTURE) uniform sampler2D uClearcoatTexture;
layout(binding = BINDING_CLEARCOAT_ROUGHNESS_TEXTURE) uniform sampler2D uClearcoatRoughnessTexture;
layout(binding = BINDING_CLEARCOAT_NORMAL_TEXTURE) uniform sampler2D uClearcoatNormalTexture;
layout(binding = BINDING_SHEEN_COLOR_TEXTURE) uniform sampler2D uSheenColorTexture;
layout(binding = BINDING_SHEEN_ROUGHNESS_TEXTURE) uniform sampler2D uSheenRoughnessTexture;
layout(binding = BINDING_ANISOTROPY_TEXTURE) uniform sampler2D uAnisotropyTexture;
layout(binding = BINDING_IRIDESCENCE_TEXTURE) uniform sampler2D uIridescenceTexture;
layout(binding = BINDING_IRIDESCENCE_THICKNESS_TEXTURE) uniform sampler2D uIridescenceThicknessTexture;
// The transmission extensions' factors and textures.
uniform float uTransmissionFactor;          // KHR_materials_transmission
uniform float uThicknessFactor;             // KHR_materials_volume (object space)
uniform vec3 uAttenuationColor;
uniform float uAttenuationDistance;         // <= 0: infinite (none)
uniform float uDispersion;                  // KHR_materials_dispersion
uniform float uDiffuseTransmissionFactor;   // KHR_materials_diffuse_transmission
uniform vec3 uDiffuseTransmissionColorFactor;
layout(binding = BINDING_TRANSMISSION_TEXTURE) uniform sampler2D uTransmissionTexture;
layout(binding = BINDING_THICKNESS_TEXTURE) uniform sampler2D uThicknessTexture;
layout(binding = BINDING_DIFFUSE_TRANSMISSION_TEXTURE) uniform sampler2D uDiffuseTransmissionTexture;
layout(binding = BINDING_DIFFUSE_TRANSMISSION_COLOR_TEXTURE) uniform sampler2D uDiffuseTransmissionColorTexture;

// pt/shading.cpp's ShadingInputs: what the lights, the environment and the transmitted
// light are shaded with. Unused members of a permutation keep the values that switch
// their lobe off (the compiler drops them).
struct MaterialInputs {
  vec4 base_color;  // alpha in .a
  vec3 emissive;
  float metallic;   // after uMetallicOverride
  float roughness;  // after uRoughnessOverride
  vec3 n_geom;      // the interpolated normal (the path tracer's hit.ns)
  float side;       // -1 where the viewer sees the back of the triangle, else 1
  vec3 n;           // the shading normal, on the viewer's side
  mat3 frame;       // the local shading frame: (tangent, bitangent, n)
  BaseLayer layer;  // the base layer with KHR_materials_ior, _specular, _anisotropy, _iridescence
  vec3 sheen_color;  // KHR_materials_sheen
  float sheen_roughness;
  float coat_weight;  // KHR_materials_clearcoat
  float coat_roughness;
  vec3 n_coat;  // the coat's shading normal
  float transmission;  // KHR_materials_transmission (transmission_weights clamps both)
  float diffuse_transmission;  // KHR_materials_diffuse_transmission
  vec3 dt_color;  // clamped to [0, 1]
  float thickness;  // KHR_materials_volume (object space; 0 thin-walled)
};

vec2 texcoord(int i) {
  vec2 uv = uTexcoordSet[i] == 1 ? vTexcoord1 : vTexcoord0;
  return (uTextureTransform[i] * vec3(uv, 1.0)).xy;
}

// pt/shading.cpp's map_normal: the tangent-space normal map `tex` around `n` (scale on x, y),
// the tangent re-orthogonalised against n; n without tangents or when degenerate.
vec3 map_normal(sampler2D tex, int slot, float scale, vec3 n) {
  vec3 t = vTangent.xyz - n * dot(n, vTangent.xyz);
  float tl = length(t);
  if (!(tl > 0.0)) return n;
  t /= tl;
  vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
  vec3 c = texture(tex, texcoord(slot)).xyz * 2.0 - 1.0;
  c.xy *= scale;
  vec3 mapped = t * c.x + b * c.y + n * c.z;
  float ml = length(mapped);
  return ml > 0.0 ? mapped / ml : n;
}

// The base colour and alpha: factor x COLOR_0 x texture (pt/shading.cpp's material_alpha
// reads the same alpha).
vec4 material_base_color() {
  vec4 base_color = uBaseColorFactor;
#if HAS_COLOR_0
  base_color *= vColor;
#endif
#if HAS_BASE_COLOR_TEXTURE
  base_color *= texture(uBaseColorTexture, texcoord(SLOT_BASE_COLOR_TEXTURE));
#endif
  return base_color;
}

// pt/shading.cpp's material_emission: factor x strength x texture.
vec3 material_emission() {
  vec3 emissive = uEmissive;
#if HAS_EMISSIVE_TEXTURE
  emissive *= texture(uEmissiveTexture, texcoord(SLOT_EMISSIVE_TEXTURE)).rgb;
#endif
  return emissive;
}

// The occlusion map's factor on indirect light: 1 + strength (texel - 1).
float material_occlusion() {
  float ao = 1.0;
#if HAS_OCCLUSION_TEXTURE
  ao = 1.0 + uOcclusionStrength * (texture(uOcclusionTexture, texcoord(SLOT_OCCLUSION_TEXTURE)).r - 1.0);
#endif
  return ao;
}

// glTF's metallic-roughness: metalness in B, roughness in G; then the viewer's overrides.
void metallic_roughness_inputs(inout MaterialInputs m) {
  float metallic = uMetallicFactor, roughness = uRoughnessFactor;
#if HAS_METALLIC_ROUGHNESS_TEXTURE
  vec4 mr = texture(uMetallicRoughnessTexture, texcoord(SLOT_METALLIC_ROUGHNESS_TEXTURE));
  roughness *= mr.g;
  metallic *= mr.b;
#endif
  if (uMetallicOverride >= 0.0) metallic = uMetallicOverride;
  if (uRoughnessOverride >= 0.0) roughness = uRoughnessOverride;
  m.metallic = metallic;
  m.roughness = roughness;
}

// The shading normal goes to the viewer's side of the triangle (the back of a double-sided
// surface, or vertex normals against the winding), the whole normal-mapped normal reversed
// as the glTF spec and the Khronos sample viewer do: the same rule as the path tracer's
// shade_inputs. The triangle's normal comes from the derivatives of the (planar) position,
// turned towards the viewer `v`.
void shading_normal_inputs(inout MaterialInputs m, vec3 v) {
  vec3 ng = cross(dFdx(vPosition), dFdy(vPosition));
  if (dot(ng, v) < 0.0) ng = -ng;
  m.n_geom = normalize(vNormal);
  m.side = dot(m.n_geom, ng) < 0.0 ? -1.0 : 1.0;
  vec3 n = m.n_geom;
#if HAS_NORMAL_TEXTURE
  if (dot(vTangent.xyz, vTangent.xyz) > 0.0) n = map_normal(uNormalTexture, SLOT_NORMAL_TEXTURE, uNormalScale, m.n_geom);
#endif
  m.n = n * m.side;
}

// KHR_materials_ior and KHR_materials_specular.
void specular_inputs(inout BaseLayer layer) {
  layer.ior = uIor;
  layer.specular = uSpecularFactor;
  layer.specular_color = uSpecularColorFactor;
#if HAS_SPECULAR_TEXTURE
  layer.specular *= texture(uSpecularTexture, texcoord(SLOT_SPECULAR_TEXTURE)).a;
#endif
#if HAS_SPECULAR_COLOR_TEXTURE
  layer.specular_color *= texture(uSpecularColorTexture, texcoord(SLOT_SPECULAR_COLOR_TEXTURE)).rgb;
#endif
}

// KHR_materials_anisotropy, pt/shading.cpp's anisotropy_direction: the texture's RG
// direction ((1, 0) without it) rotated by anisotropyRotation in the tangent frame, made
// normal to the shading normal; the local frame's +X, and the strength where it exists.
void anisotropy_inputs(inout MaterialInputs m) {
  if (vTangent != vec4(0.0)) {
    vec2 d = vec2(1.0, 0.0);
    float strength = uAnisotropyStrength;
#if HAS_ANISOTROPY_TEXTURE
    vec3 at = texture(uAnisotropyTexture, texcoord(SLOT_ANISOTROPY_TEXTURE)).rgb;
    d = at.rg * 2.0 - 1.0;
    strength *= at.b;
#endif
    vec2 cs = vec2(cos(uAnisotropyRotation), sin(uAnisotropyRotation));
    d = vec2(cs.x * d.x - cs.y * d.y, cs.y * d.x + cs.x * d.y);
    vec3 t = vTangent.xyz;
    vec3 b = cross(m.n_geom, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
    vec3 dir = t * d.x + b * d.y;
    dir -= m.n * dot(m.n, dir);
    float l = length(dir);
    if (l > 1e-6) {
      vec3 aniso_t = dir / l;
      m.frame = mat3(aniso_t, cross(m.n, aniso_t), m.n);
      m.layer.anisotropy = strength;
    }
  }
}

// KHR_materials_iridescence: without a thickness texture the film is the maximum thick
// (README).
void iridescence_inputs(inout BaseLayer layer) {
  layer.iridescence = uIridescenceFactor;
  layer.iridescence_ior = uIridescenceIor;
#if HAS_IRIDESCENCE_TEXTURE
  layer.iridescence *= texture(uIridescenceTexture, texcoord(SLOT_IRIDESCENCE_TEXTURE)).r;
#endif
  float thickness_g = 1.0;
#if HAS_IRIDESCENCE_THICKNESS_TEXTURE
  thickness_g = texture(uIridescenceThicknessTexture, texcoord(SLOT_IRIDESCENCE_THICKNESS_TEXTURE)).g;
#endif
  layer.iridescence_thickness = mix(uIridescenceThicknessMinimum, uIridescenceThicknessMaximum, thickness_g);
}

// KHR_materials_sheen.
void sheen_inputs(inout MaterialInputs m) {
  m.sheen_color = uSheenColorFactor;
  m.sheen_roughness = uSheenRoughnessFactor;
#if HAS_SHEEN_COLOR_TEXTURE
  m.sheen_color *= texture(uSheenColorTexture, texcoord(SLOT_SHEEN_COLOR_TEXTURE)).rgb;
#endif
#if HAS_SHEEN_ROUGHNESS_TEXTURE
  m.sheen_roughness *= texture(uSheenRoughnessTexture, texcoord(SLOT_SHEEN_ROUGHNESS_TEXTURE)).a;
#endif
}

// KHR_materials_transmission.
void transmission_inputs(inout MaterialInputs m) {
  m.transmission = uTransmissionFactor;
#if HAS_TRANSMISSION_TEXTURE
  m.transmission *= texture(uTransmissionTexture, texcoord(SLOT_TRANSMISSION_TEXTURE)).r;
#endif
}

// KHR_materials_diffuse_transmission.
void diffuse_transmission_inputs(inout MaterialInputs m) {
  m.diffuse_transmission = uDiffuseTransmissionFactor;
#if HAS_DIFFUSE_TRANSMISSION_TEXTURE
  m.diffuse_transmission *= texture(uDiffuseTransmissionTexture, texcoord(SLOT_DIFFUSE_TRANSMISSION_TEXTURE)).a;
#endif
  m.dt_color = uDiffuseTransmissionColorFactor;
#if HAS_DIFFUSE_TRANSMISSION_COLOR_TEXTURE
  m.dt_color *= texture(uDiffuseTransmissionColorTexture, texcoord(SLOT_DIFFUSE_TRANSMISSION_COLOR_TEXTURE)).rgb;
#endif
  m.dt_color = clamp(m.dt_color, 0.0, 1.0);
}

// KHR_materials_volume's thickness (its attenuation is read where the light crosses it).
void volume_inputs(inout MaterialInputs m) {
  m.thickness = uThicknessFactor;
#if HAS_THICKNESS_TEXTURE
  m.thickness *= texture(uThicknessTexture, texcoord(SLOT_THICKNESS_TEXTURE)).g;
#endif
}

// KHR_materials_clearcoat. The coat's own normal map; none means the interpolated normal,
// not the base's map (README).
void clearcoat_inputs(inout MaterialInputs m) {
  m.coat_weight = uClearcoatFactor;
  m.coat_roughness = uClearcoatRoughnessFactor;
#if HAS_CLEARCOAT_TEXTURE
  m.coat_weight *= texture(uClearcoatTexture, texcoord(SLOT_CLEARCOAT_TEXTURE)).r;
#endif
#if HAS_CLEARCOAT_ROUGHNESS_TEXTURE
  m.coat_roughness *= texture(uClearcoatRoughnessTexture, texcoord(SLOT_CLEARCOAT_ROUGHNESS_TEXTURE)).g;
#endif
  vec3 n_coat = m.n_geom;
#if HAS_CLEARCOAT_NORMAL_TEXTURE
  if (m.coat_weight > 0.0) n_coat = map_normal(uClearcoatNormalTexture, SLOT_CLEARCOAT_NORMAL_TEXTURE, uClearcoatNormalScale, m.n_geom);
#endif
  m.n_coat = n_coat * m.side;
}

// pt/shading.cpp's shade_inputs: every input of a lit surface seen from `v` (towards the
// viewer), with base_color and emissive as material_base_color() and material_emission()
// return them. The extensions a permutation leaves out keep the values that turn them off.
MaterialInputs material_inputs(vec4 base_color, vec3 emissive, vec3 v) {
  MaterialInputs m;
  m.base_color = base_color;
  m.emissive = emissive;
  metallic_roughness_inputs(m);
  shading_normal_inputs(m, v);
  m.layer = base_layer(base_color.rgb, m.metallic, m.roughness);
#if MATERIAL_SPECULAR
  specular_inputs(m.layer);
#endif
  m.frame = frame_from_normal(m.n);
#if MATERIAL_ANISOTROPY
  anisotropy_inputs(m);
#endif
#if MATERIAL_IRIDESCENCE
  iridescence_inputs(m.layer);
#endif
  m.sheen_color = vec3(0.0);
  m.sheen_roughness = 0.0;
#if MATERIAL_SHEEN
  sheen_inputs(m);
#endif
  m.coat_weight = 0.0;
  m.coat_roughness = 0.0;
  m.n_coat = m.n;
#if MATERIAL_CLEARCOAT
  clearcoat_inputs(m);
#endif
  m.transmission = 0.0;
  m.diffuse_transmission = 0.0;
  m.dt_color = vec3(1.0);
  m.thickness = 0.0;
#if MATERIAL_TRANSMISSION
  transmission_inputs(m);
#endif
#if MATERIAL_DIFFUSE_TRANSMISSION
  diffuse_transmission_inputs(m);
#endif
#if MATERIAL_VOLUME
  volume_inputs(m);
#endif
  return m;
}
