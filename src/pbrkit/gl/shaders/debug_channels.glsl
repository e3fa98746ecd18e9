// The raster view's debug channels (include/pbrkit/gl/debug_channels.h; the Khronos glTF
// Sample Viewer's debug outputs): DEBUG_CHANNEL, a compile-time constant of the surface
// program's permutation, selects what pbr_fragment.glsl writes.
//
// The material inputs (base colour ... emissive) replace the shaded colour at the end of
// main (debug_channel). The lobe channels (diffuse ... transmission) keep the shading and
// pass each term of it through lobe(): the selected lobe's terms stay, the others become 0.
// Every layer's attenuation of the layers under it is kept, so each channel is that lobe's
// share of the final radiance and the lobes of a pixel sum to its shaded colour less its
// emission (tests/gl/debug_channels_test.cpp checks both). Without DEBUG_CHANNEL every
// function here is the identity on the shading.
#include "bsdf.glsl"

#ifndef DEBUG_CHANNEL
#define DEBUG_CHANNEL 0
#endif
// DebugChannel's values.
#define DEBUG_NONE 0
#define DEBUG_BASE_COLOR 1
#define DEBUG_METALLIC 2
#define DEBUG_ROUGHNESS 3
#define DEBUG_NORMAL 4
#define DEBUG_OCCLUSION 5
#define DEBUG_EMISSIVE 6
#define DEBUG_DIFFUSE 7
#define DEBUG_SPECULAR 8
#define DEBUG_CLEARCOAT 9
#define DEBUG_SHEEN 10
#define DEBUG_TRANSMISSION 11

// A term of the shading that belongs to lobe `channel` (DEBUG_EMISSIVE for the emission):
// itself, unless a lobe channel shows another lobe.
vec3 lobe(int channel, vec3 value) {
#if DEBUG_CHANNEL >= DEBUG_DIFFUSE
  return channel == DEBUG_CHANNEL ? value : vec3(0.0);
#else
  return value;
#endif
}

// The diffuse lobe of a bound Brdf for a light: brdf_eval less its specular. The lambertian
// term is the only one of brdf_eval_diffuse_and_ms that reads base_color (the Fresnel
// weight and the compensation are the Brdf's fields, set by make_brdf), so the difference
// with the base colour zeroed is that term alone.
vec3 debug_diffuse_direct(Brdf b, sampler2D table, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
  vec3 diffuse_weight;
  brdf_specular_fresnel(b, dot(wo, normalize(wo + wi)), diffuse_weight);
  Brdf black = b;
  black.base_color = vec3(0.0);
  return brdf_eval_diffuse_and_ms(b, table, wo, wi, diffuse_weight) -
         brdf_eval_diffuse_and_ms(black, table, wo, wi, diffuse_weight);
}

// brdf_eval's share of the selected lobe: the diffuse, or the rest (the specular).
vec3 brdf_lobes(Brdf b, sampler2D table, vec3 wo, vec3 wi) {
#if DEBUG_CHANNEL == DEBUG_DIFFUSE
  return debug_diffuse_direct(b, table, wo, wi);
#elif DEBUG_CHANNEL == DEBUG_SPECULAR
  return brdf_eval(b, table, wo, wi) - debug_diffuse_direct(b, table, wo, wi);
#elif DEBUG_CHANNEL >= DEBUG_DIFFUSE
  return vec3(0.0);
#else
  return brdf_eval(b, table, wo, wi);
#endif
}

// bsdf_eval's share of the selected lobe. bsdf_eval = f_coat + A_coat (f_sheen + A_sheen
// f_base) is linear in each layer's reflection at fixed attenuations, and each reflection
// can be turned off without touching the attenuations: the coat's with its specular weight
// 0 (its Fresnel, hence its whole lobe, becomes 0; coat_weight still attenuates), the
// sheen's with its colour 0 (sheen_max, its attenuation, is kept). The base's attenuation
// A_coat A_sheen is bsdf_eval over a base of known f: a white Lambertian without specular,
// f = 1/pi.
vec3 bsdf_lobes(Bsdf s, sampler2D table, sampler2D coat_table, sampler2D sheen_lut, vec3 wo,
                vec3 wi) {
#if DEBUG_CHANNEL >= DEBUG_DIFFUSE
  Bsdf no_coat = s;
  no_coat.coat.spec_weight = 0.0;
  Bsdf base_only = no_coat;
  base_only.sheen_color = vec3(0.0);
#if DEBUG_CHANNEL == DEBUG_CLEARCOAT
  return bsdf_eval(s, table, coat_table, sheen_lut, wo, wi) -
         bsdf_eval(no_coat, table, coat_table, sheen_lut, wo, wi);
#elif DEBUG_CHANNEL == DEBUG_SHEEN
  return bsdf_eval(no_coat, table, coat_table, sheen_lut, wo, wi) -
         bsdf_eval(base_only, table, coat_table, sheen_lut, wo, wi);
#elif DEBUG_CHANNEL == DEBUG_DIFFUSE || DEBUG_CHANNEL == DEBUG_SPECULAR
  BaseLayer white = base_layer(vec3(1.0), 0.0, 1.0);
  white.specular = 0.0;
  Bsdf lambert = base_only;
  lambert.base = make_brdf(white, GEOMETRY_REFERENCE, false, FRESNEL_SCHLICK, table);
  vec3 attenuation = kPi * bsdf_eval(lambert, table, coat_table, sheen_lut, wo, wi);
  vec3 diffuse = attenuation * debug_diffuse_direct(s.base, table, wo, wi);
#if DEBUG_CHANNEL == DEBUG_DIFFUSE
  return diffuse;
#else
  return bsdf_eval(base_only, table, coat_table, sheen_lut, wo, wi) - diffuse;
#endif
#else
  return vec3(0.0);
#endif
#else
  return bsdf_eval(s, table, coat_table, sheen_lut, wo, wi);
#endif
}

// The split sum's share of the selected lobe, from `indirect` = ibl_shading(b, ...): its
// diffuse term is the difference with the base colour zeroed (as for a light), lit by the
// irradiance alone (no prefiltered light); the rest is the specular.
vec3 ibl_lobes(vec3 indirect, Brdf b, sampler2D ibl_table, float NdotV, vec3 irradiance) {
#if DEBUG_CHANNEL == DEBUG_DIFFUSE || DEBUG_CHANNEL == DEBUG_SPECULAR
  Brdf black = b;
  black.base_color = vec3(0.0);
  vec3 diffuse = ibl_shading(b, ibl_table, NdotV, vec3(0.0), irradiance) -
                 ibl_shading(black, ibl_table, NdotV, vec3(0.0), irradiance);
  return DEBUG_CHANNEL == DEBUG_DIFFUSE ? diffuse : indirect - diffuse;
#elif DEBUG_CHANNEL >= DEBUG_DIFFUSE
  return vec3(0.0);
#else
  return indirect;
#endif
}

// What the fragment writes: `shaded` (the lobe channels' too), or a material input raw.
// metallic and roughness are the material's after textures and the viewer's overrides,
// before the BRDF's clamps; n is the shading normal, world space, facing the viewer.
vec3 debug_channel(vec3 shaded, vec3 base_color, float metallic, float roughness, vec3 n,
                   float occlusion, vec3 emissive) {
#if DEBUG_CHANNEL == DEBUG_BASE_COLOR
  return base_color;
#elif DEBUG_CHANNEL == DEBUG_METALLIC
  return vec3(metallic);
#elif DEBUG_CHANNEL == DEBUG_ROUGHNESS
  return vec3(roughness);
#elif DEBUG_CHANNEL == DEBUG_NORMAL
  return n * 0.5 + 0.5;
#elif DEBUG_CHANNEL == DEBUG_OCCLUSION
  return vec3(occlusion);
#elif DEBUG_CHANNEL == DEBUG_EMISSIVE
  return emissive;
#else
  return shaded;
#endif
}
