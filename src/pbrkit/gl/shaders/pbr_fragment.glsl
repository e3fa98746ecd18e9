#version 450
// The scene's surfaces: the material model of brdf.glsl lit by KHR_lights_punctual lights
// and split-sum IBL (ibl.glsl), with glTF's textures, emission, normal and occlusion maps
// (occlusion on indirect light only), alpha MASK / BLEND and double-sided materials.
//
// Features are compile-time constants (renderer.cpp's SurfaceFeatures writes the #defines;
// the defaults below are only for tools that compile this file alone): llvmpipe, the
// software rasteriser of CI and headless servers, runs both sides of a branch on a
// uniform with masked lanes, so an unused texture or IBL term would still cost its
// fetches. HAS_TEXTURE_0..4: baseColor, metallicRoughness, normal, occlusion, emissive
// bound; HAS_COLOR_0: the mesh has COLOR_0 (a varying fewer without: llvmpipe sets up
// and interpolates every varying of every small triangle); ALPHA_MODE 0 opaque, 1 mask,
// 2 blend; IBL, IRRADIANCE_SH, MULTISCATTER 0/1; GEOMETRY (G for lights) and FRESNEL as
// in brdf.glsl; LIGHT_COUNT punctual lights.
#ifndef HAS_TEXTURE_0
#define HAS_TEXTURE_0 0
#define HAS_TEXTURE_1 0
#define HAS_TEXTURE_2 0
#define HAS_TEXTURE_3 0
#define HAS_TEXTURE_4 0
#define HAS_COLOR_0 1
#define ALPHA_MODE 0
#define IBL 1
#define IRRADIANCE_SH 1
#define MULTISCATTER 0
#define GEOMETRY 0
#define FRESNEL 0
#define LIGHT_COUNT 0
#endif
#include "ibl.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec4 vTangent;
in vec2 vTexcoord0;
in vec2 vTexcoord1;
#if HAS_COLOR_0
in vec4 vColor;
#endif

layout(location = 0) out vec4 outColor;

uniform vec3 uCameraPosition;

// Material (glTF metallic-roughness, factors times textures).
uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor;
uniform float uRoughnessFactor;
uniform vec3 uEmissive;  // factor x KHR_materials_emissive_strength
uniform float uNormalScale;
uniform float uOcclusionStrength;
uniform float uAlphaCutoff;
// Per texture: which TEXCOORD set, the KHR_texture_transform matrix.
uniform int uTexcoordSet[5];
uniform mat3 uTextureTransform[5];
layout(binding = 0) uniform sampler2D uBaseColorTexture;
layout(binding = 1) uniform sampler2D uMetallicRoughnessTexture;
layout(binding = 2) uniform sampler2D uNormalTexture;
layout(binding = 3) uniform sampler2D uOcclusionTexture;
layout(binding = 4) uniform sampler2D uEmissiveTexture;

// Model.
layout(binding = 5) uniform sampler2D uEnergyDirect;  // EnergyTable of the direct G
layout(binding = 6) uniform sampler2D uEnergyIBL;     // EnergyTable of the IBL G (the LUT)
uniform float uMetallicOverride;   // < 0: none
uniform float uRoughnessOverride;  // < 0: none

// Lights (KHR_lights_punctual), world space.
const int kMaxLights = 16;
uniform int uLightType[kMaxLights];  // 0 point, 1 spot, 2 directional
uniform vec3 uLightPosition[kMaxLights];
uniform vec3 uLightDirection[kMaxLights];  // where the light points
uniform vec3 uLightRadiance[kMaxLights];   // colour x intensity
uniform float uLightRange[kMaxLights];     // <= 0: infinite
uniform vec2 uLightCone[kMaxLights];       // spot: (scale, offset) of the glTF cone falloff

// Image-based lighting.
uniform vec3 uSH[9];
uniform int uSpecularLevels;
uniform vec2 uIblRotation;  // world_to_env (equirect.glsl) for the baked cubes
uniform float uIblScale;
layout(binding = 7) uniform samplerCube uSpecularCube;
layout(binding = 8) uniform samplerCube uIrradianceCube;

vec2 texcoord(int i) {
  vec2 uv = uTexcoordSet[i] == 1 ? vTexcoord1 : vTexcoord0;
  return (uTextureTransform[i] * vec3(uv, 1.0)).xy;
}

// KHR_lights_punctual's recommended range window clamp(1 - (d/range)^4, 0, 1) over d^2
// (as the Khronos sample viewer and the path tracer's lights.cpp).
float range_attenuation(float d, float range) {
  if (range <= 0.0) return 1.0 / (d * d);
  float r = d / range;
  return clamp(1.0 - r * r * r * r, 0.0, 1.0) / (d * d);
}

void main() {
  vec4 base_color = uBaseColorFactor;
#if HAS_COLOR_0
  base_color *= vColor;
#endif
#if HAS_TEXTURE_0
  base_color *= texture(uBaseColorTexture, texcoord(0));
#endif
#if ALPHA_MODE == 1
  if (base_color.a < uAlphaCutoff) discard;
#endif
  float metallic = uMetallicFactor, roughness = uRoughnessFactor;
#if HAS_TEXTURE_1
  vec4 mr = texture(uMetallicRoughnessTexture, texcoord(1));
  roughness *= mr.g;
  metallic *= mr.b;
#endif
  if (uMetallicOverride >= 0.0) metallic = uMetallicOverride;
  if (uRoughnessOverride >= 0.0) roughness = uRoughnessOverride;

  vec3 v = normalize(uCameraPosition - vPosition);
  // The shading normal goes to the viewer's side of the triangle (the back of a
  // double-sided surface, or vertex normals against the winding), the whole normal-mapped
  // normal reversed as the glTF spec and the Khronos sample viewer do: the same rule as
  // the path tracer's shade_inputs. The triangle's normal comes from the derivatives of
  // the (planar) position, turned towards the viewer.
  vec3 ng = cross(dFdx(vPosition), dFdy(vPosition));
  if (dot(ng, v) < 0.0) ng = -ng;
  vec3 n = normalize(vNormal);
  float side = dot(n, ng) < 0.0 ? -1.0 : 1.0;
#if HAS_TEXTURE_2
  if (dot(vTangent.xyz, vTangent.xyz) > 0.0) {
    vec3 t = normalize(vTangent.xyz - n * dot(n, vTangent.xyz));
    vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
    vec3 tn = texture(uNormalTexture, texcoord(2)).xyz * 2.0 - 1.0;
    tn.xy *= uNormalScale;
    n = normalize(mat3(t, b, n) * tn);
  }
#endif
  n *= side;
  mat3 frame = frame_from_normal(n);
  vec3 wo = to_local(frame, v);

  Brdf brdf = make_brdf(base_color.rgb, metallic, roughness, GEOMETRY, MULTISCATTER != 0, FRESNEL,
                        uEnergyDirect);
  vec3 color = vec3(0.0);
  for (int i = 0; i < LIGHT_COUNT && i < kMaxLights; ++i) {
    vec3 l;
    vec3 radiance = uLightRadiance[i];
    if (uLightType[i] == 2) {
      l = -uLightDirection[i];
    } else {
      vec3 to_light = uLightPosition[i] - vPosition;
      float d = length(to_light);
      l = to_light / d;
      radiance *= range_attenuation(d, uLightRange[i]);
      if (uLightType[i] == 1) {
        // Spot cone: smooth falloff between the cone angles (KHR_lights_punctual).
        float cd = dot(uLightDirection[i], -l);
        float a = clamp(cd * uLightCone[i].x + uLightCone[i].y, 0.0, 1.0);
        radiance *= a * a;
      }
    }
    vec3 wi = to_local(frame, l);
    if (wi.z <= 0.0) continue;
    color += brdf_eval(brdf, uEnergyDirect, wo, wi) * radiance * wi.z;
  }

#if IBL
  {
    float ao = 1.0;
#if HAS_TEXTURE_3
    ao = 1.0 + uOcclusionStrength * (texture(uOcclusionTexture, texcoord(3)).r - 1.0);
#endif
    vec3 r = reflect(-v, n);
    vec3 prefiltered = textureLod(uSpecularCube, world_to_env(r, uIblRotation),
                                  roughness_lod(brdf.roughness, uSpecularLevels)).rgb;
    vec3 n_env = world_to_env(n, uIblRotation);
#if IRRADIANCE_SH
    vec3 irradiance = max(eval_sh_irradiance(uSH, n_env), vec3(0.0));
#else
    vec3 irradiance = textureLod(uIrradianceCube, n_env, 0.0).rgb;
#endif
    Brdf ibl = make_brdf(base_color.rgb, metallic, roughness, GEOMETRY, MULTISCATTER != 0, FRESNEL,
                         uEnergyIBL);
    color += ao * uIblScale * ibl_shading(ibl, uEnergyIBL, dot(n, v), prefiltered, irradiance);
  }
#endif

  vec3 emissive = uEmissive;
#if HAS_TEXTURE_4
  emissive *= texture(uEmissiveTexture, texcoord(4)).rgb;
#endif
  color += emissive;
  outColor = vec4(color, ALPHA_MODE == 2 ? base_color.a : 1.0);
}
