#version 450
// The scene's surfaces: the material model of brdf.glsl lit by KHR_lights_punctual lights
// and split-sum IBL (ibl.glsl), with glTF's textures, emission, normal and occlusion maps
// (occlusion on indirect light only), alpha MASK / BLEND and double-sided materials.
//
// Features are compile-time constants (shader_permutations.h's SurfaceFeatures writes the
// #defines after surface_bindings.h's prelude, which names every texture slot, SLOT_<slot>,
// and every texture unit and buffer binding point, BINDING_<name>; the feature defaults
// below are only for tools that compile this file with the prelude alone): llvmpipe, the
// software rasteriser of CI and headless servers, runs both sides of a branch on a
// uniform with masked lanes, so an unused texture or IBL term would still cost its
// fetches. HAS_<slot> (HAS_BASE_COLOR_TEXTURE, ..., one per scene.h TextureSlot): the slot
// is bound; HAS_COLOR_0: the mesh has COLOR_0 (a varying fewer without: llvmpipe sets up
// and interpolates every varying of every small triangle); ALPHA_MODE 0 opaque, 1 mask,
// 2 blend; IBL, IRRADIANCE_SH, MULTISCATTER 0/1; GEOMETRY (G for lights) and FRESNEL as
// in brdf.glsl; LIGHTS: the punctual lights, 0 none, 1 every light for every fragment, 2
// the fragment's cluster's (light_clusters.h), 3 the same with spot lights among them;
// LIGHT_COUNT: with LIGHTS 1, the number of
// lights when compiled in (-1: uLightCount).
// The KHR_materials_* extensions, each its own permutation feature with its
// texture slots (HAS_SPECULAR_TEXTURE .. HAS_IRIDESCENCE_THICKNESS_TEXTURE): MATERIAL_SPECULAR (ior and
// specular), MATERIAL_ANISOTROPY, MATERIAL_IRIDESCENCE, MATERIAL_CLEARCOAT, MATERIAL_SHEEN,
// MATERIAL_UNLIT. Every input is computed as the path tracer's shade_inputs
// (pt/shading.cpp) computes it.
// The transmission features (transmission.glsl; HAS_TRANSMISSION_TEXTURE ..
// HAS_DIFFUSE_TRANSMISSION_COLOR_TEXTURE): MATERIAL_TRANSMISSION (the opaque
// frame, uTransmissionFrame, read through the surface), MATERIAL_VOLUME (a thickness > 0:
// refraction through the medium, Beer-Lambert), MATERIAL_DISPERSION (three iors),
// MATERIAL_DIFFUSE_TRANSMISSION (the irradiance at -n through the diffuse lobe). With
// MATERIAL_TRANSMISSION and MATERIAL_VOLUME the refraction goes through both interfaces
// (thick_refraction.glsl) where renderer.cpp has drawn the object's back faces, and with
// GLASS_REFLECTIONS its specular reflection reads the opaque frame where the mirror
// direction meets it on the screen (thick_refraction.glsl's reflected_frame). IBL_OCCLUDERS:
// the environment light is shadowed by the transmissive objects (occluders.glsl).
//
// main() reads as the shading's steps: the material's inputs (material_inputs.glsl, one
// function per extension), the material bound to the viewer (shading_at) and the
// transmission extensions' weights (transmission_weights), the punctual lights, the
// image-based light, the light transmitted from the frame behind, the output.
#ifndef MATERIAL_SPECULAR
#define MATERIAL_SPECULAR 0
#define MATERIAL_ANISOTROPY 0
#define MATERIAL_IRIDESCENCE 0
#define MATERIAL_CLEARCOAT 0
#define MATERIAL_SHEEN 0
#define MATERIAL_UNLIT 0
#endif
#ifndef MATERIAL_TRANSMISSION
#define MATERIAL_TRANSMISSION 0
#define MATERIAL_VOLUME 0
#define MATERIAL_DISPERSION 0
#define MATERIAL_DIFFUSE_TRANSMISSION 0
#endif
#ifndef HAS_COLOR_0
#define HAS_COLOR_0 1
#define ALPHA_MODE 0
#define IBL 1
#define IRRADIANCE_SH 1
#define MULTISCATTER 0
#define GEOMETRY 0
#define FRESNEL 0
#define LIGHTS 0
#define LIGHT_COUNT -1
#endif
#if MATERIAL_IRIDESCENCE
#define BRDF_IRIDESCENCE 1
#endif
#include "ibl.glsl"
#include "bsdf.glsl"
#include "debug_channels.glsl"
#include "material_inputs.glsl"
#if MATERIAL_ANISOTROPY
#include "anisotropy_ibl.glsl"
#endif
#if MATERIAL_TRANSMISSION || MATERIAL_DIFFUSE_TRANSMISSION
#include "transmission.glsl"
#endif
#if MATERIAL_TRANSMISSION && MATERIAL_VOLUME
#include "thick_refraction.glsl"
#endif
#ifndef IBL_OCCLUDERS
#define IBL_OCCLUDERS 0
#endif
#ifndef GLASS_REFLECTIONS
#define GLASS_REFLECTIONS 0
#endif
#if IBL_OCCLUDERS
#include "occluders.glsl"
flat in int vSlot;  // pbr_vertex.glsl's: a surface is not shadowed by itself
#endif

layout(location = 0) out vec4 outColor;

uniform vec3 uCameraPosition;
uniform float uAlphaCutoff;
uniform vec3 uModelScale;  // the model matrix's column lengths
// The opaque frame with its mip chain (renderer.cpp's transmission pass), and its size.
layout(binding = BINDING_TRANSMISSION_FRAME) uniform sampler2D uTransmissionFrame;
uniform vec2 uTransmissionFrameSize;
uniform mat4 uViewProjection;
#if MATERIAL_TRANSMISSION && MATERIAL_VOLUME
// The object's back faces (renderer.cpp's back-face pass; uBackFaces 0 where it has not run
// for this draw: a blended surface) and the opaque frame's depth.
layout(binding = BINDING_BACK_POSITION) uniform sampler2D uBackPosition;
layout(binding = BINDING_BACK_NORMAL) uniform sampler2D uBackNormal;
layout(binding = BINDING_FRAME_DEPTH) uniform sampler2D uTransmissionDepth;
uniform int uBackFaces;
uniform vec4 uBackFaceRect;  // where the pass ran: (min, max) texture coordinates
uniform mat4 uInverseViewProjection;
#endif

// Model.
layout(binding = BINDING_ENERGY_DIRECT) uniform sampler2D uEnergyDirect;  // EnergyTable of the direct G
layout(binding = BINDING_ENERGY_IBL) uniform sampler2D uEnergyIBL;     // EnergyTable of the IBL G (the LUT)
layout(binding = BINDING_ENERGY_COAT) uniform sampler2D uEnergyCoat;  // EnergyTable of the reference G (the coat's)
// The sheen's tables (core/sheen.h's SheenTable: E, E_max_avg and the lobe's moments;
// gl/energy_texture.h). The baker's Charlie-prefiltered cube is still bound but no longer
// read: the sheen's IBL averages the SH over the lobe (sheen_ibl, MODEL.md "Sheen maps").
layout(binding = BINDING_SHEEN_CUBE) uniform samplerCube uSheenCube;
layout(binding = BINDING_SHEEN_LUT) uniform sampler2D uSheenLut;
uniform int uSheenLevels;
#if MATERIAL_ANISOTROPY
// The anisotropic lobe's albedo (ibl/anisotropic_albedo.h; gl/energy_texture.h).
layout(binding = BINDING_ANISOTROPIC_ALBEDO) uniform sampler3D uAnisotropicAlbedo;
#endif

// Lights (KHR_lights_punctual), world space, in light_clusters.h's GpuLight layout.
struct PunctualLight {
  vec3 position;
  float range;  // <= 0: infinite
  vec3 direction;  // where the light points
  int type;  // 0 point, 1 spot, 2 directional
  vec3 radiance;  // colour x intensity
  float unused0;
  vec2 cone;  // spot: (scale, offset) of the glTF cone falloff
  vec2 unused1;
};
layout(std430, binding = BINDING_PUNCTUAL_LIGHTS) readonly buffer PunctualLights { PunctualLight uLights[]; };
uniform int uLightCount;
// Clustered shading (Olsson et al. 2012; light_clusters.h): the lights of cluster c are
// the entries uClusterRange[c].x ... (count uClusterRange[c].y) of the listed lights; the
// first uGlobalLightCount entries are the lights every fragment shades (no range, or
// directional). Cluster (x, y, z): pixel tile gl_FragCoord.xy / uClusterTile, slice
// floor(log(depth / uClusterDepth.x) * uClusterDepth.y) of the view depth
// dot(uViewDepth.xyz, p) + uViewDepth.w.
layout(std430, binding = BINDING_LIGHT_CLUSTER_RANGES) readonly buffer LightClusterRanges { uvec2 uClusterRange[]; };
// Entry k of the listed lights, what the clustered loop reads of its light
// (light_clusters.h's GpuListedLight), as bits: uListedLight[2k] its (position, range),
// uListedLight[2k + 1] its (radiance, type << 30 | index into uLights); a directional
// light's direction in place of the position. Whole words of four: llvmpipe reads a
// storage buffer at a varying index in a loop over the SIMD lanes per load (not per
// word), so the loop's cost is its number of loads.
layout(std430, binding = BINDING_LISTED_LIGHTS) readonly buffer ListedLights { uvec4 uListedLight[]; };
uniform int uGlobalLightCount;
uniform ivec3 uClusterGrid;
uniform float uClusterTile;
uniform vec2 uClusterDepth;
uniform vec4 uViewDepth;

// Image-based lighting.
uniform vec3 uSH[9];
uniform int uSpecularLevels;
uniform vec2 uIblRotation;  // world_to_env (equirect.glsl) for the baked cubes
uniform float uIblScale;
layout(binding = BINDING_SPECULAR_CUBE) uniform samplerCube uSpecularCube;
layout(binding = BINDING_IRRADIANCE_CUBE) uniform samplerCube uIrradianceCube;

// The environment's irradiance at world normal n (IRRADIANCE_SH: the nine terms, else the
// irradiance cube): what the diffuse lobe is lit by, and (occluders.glsl) the light a proxy
// hides and its sides send, so that those are what that lobe would have from the
// environment. With the proxies' terms written out the SH sums cost llvmpipe less than the
// cube's fetches; in a loop over the proxies they cost more (BENCHMARKS.md, "The proxies'
// terms written out").
vec3 environment_irradiance(vec3 n) {
#if IRRADIANCE_SH
  return max(eval_sh_irradiance(uSH, world_to_env(n, uIblRotation)), vec3(0.0));
#else
  return textureLod(uIrradianceCube, world_to_env(n, uIblRotation), 0.0).rgb;
#endif
}

// The sheen's image-based lighting: sheenColor times the sheen's directional albedo E(n.v)
// (the split sum's DG term for the README's Charlie visibility, ibl/sheen_lut.h) times the
// environment's order-2 SH averaged over the Charlie lobe itself (sheen.glsl's
// sheen_sh_radiance, from the lobe's tabulated first and second moments: where it gathers
// light, on the viewer's side of n, and how widely; MODEL.md "Sheen maps"). The Khronos
// Sample Viewer's getIBLRadianceCharlie looks its Charlie-prefiltered cube up along R
// instead, the other side of n, so its rims show the environment beside the object where
// the lobe back-scatters what lies behind the viewer (docs/SPLIT_SUM_ERRORS.md).
vec3 sheen_ibl(vec3 n, vec3 v, vec3 sheen_color, float sheen_roughness) {
  vec3 light = sheen_sh_radiance(uSheenLut, uSH, world_to_env(n, uIblRotation),
                                 world_to_env(v, uIblRotation), sheen_roughness);
  return max(light, vec3(0.0)) * sheen_color * sheen_E(uSheenLut, dot(n, v), sheen_roughness);
}

// KHR_lights_punctual's recommended range window clamp(1 - (d/range)^4, 0, 1) over d^2
// (as the Khronos sample viewer and the path tracer's lights.cpp).
float range_attenuation(float d, float range) {
  if (range <= 0.0) return 1.0 / (d * d);
  float r = d / range;
  return clamp(1.0 - r * r * r * r, 0.0, 1.0) / (d * d);
}

// The shading: what the lights, the environment and the frame behind the surface see of the
// material at this fragment, bound to the view direction once.
struct Shading {
  vec3 v;   // towards the viewer, world space
  vec3 wo;  // v in the material's local frame
  // Bound to wo once: the lights below share its albedo lookups (BoundBrdf / BoundBsdf).
  Brdf brdf;
#if MATERIAL_CLEARCOAT || MATERIAL_SHEEN
  Bsdf bsdf;
#endif
};

// The weights the transmission extensions give the lobes. The diffuse lobe becomes
// mix(mix(diffuse, diffuse BTDF, DT), specular BTDF, T) (the transmission and
// diffuse_transmission READMEs): `transmission` T of it is the specular BTDF, `through` of
// it goes through, and the diffuse BTDF's light crosses the medium (attenuated over
// `thickness`, as the Sample Viewer's diffuse transmission does), `dt_weight` of it. The
// diffuse BTDF's colour is diffuseTransmissionColor alone (the README's normative
// diffuse_btdf(color = diffuseTransmissionColor), no baseColor): the diffuse lobe's
// functions read it from a copy of the Brdf whose base colour it is.
//
// Plain values (out parameters, not members of Shading), each the literal 0 where the
// permutation leaves its extension out. Mesa's GLSL compiler reassociates a chain of
// products such as `through * diffuse * radiance * cos` into (through diffuse)(radiance
// cos) (opt_rebalance_tree.cpp), but skips any chain that reads a struct member, so the
// same factor read from a struct is rounded otherwise in the last bit: keep the factors of
// such products plain variables (llvmpipe's images are compared bit for bit).
void transmission_weights(MaterialInputs m, out float transmission, out float thickness,
                          out float through, out vec3 dt_weight) {
  transmission = 0.0;
  thickness = 0.0;
  float diffuse_transmission = 0.0;
#if MATERIAL_TRANSMISSION
  transmission = saturate(m.transmission);
#endif
#if MATERIAL_DIFFUSE_TRANSMISSION
  diffuse_transmission = saturate(m.diffuse_transmission);
#endif
#if MATERIAL_VOLUME
  thickness = m.thickness;
#endif
  through = transmission + (1.0 - transmission) * diffuse_transmission;
#if MATERIAL_TRANSMISSION || MATERIAL_DIFFUSE_TRANSMISSION
  float mean_scale = (uModelScale.x + uModelScale.y + uModelScale.z) / 3.0;
  dt_weight = (1.0 - transmission) * diffuse_transmission *
              volume_attenuation(thickness * mean_scale, uAttenuationColor, uAttenuationDistance);
#else
  dt_weight = vec3(0.0);
#endif
}

// KHR_materials_unlit: the base colour as is, from every direction (the path tracer's
// integrator adds it to the emission and reflects nothing).
vec4 unlit_output(vec4 base_color, vec3 emissive) {
  vec4 color = vec4(base_color.rgb + emissive, ALPHA_MODE == 2 ? base_color.a : 1.0);
#if DEBUG_CHANNEL != DEBUG_NONE
  color.rgb = debug_channel(lobe(DEBUG_EMISSIVE, color.rgb), base_color.rgb, 0.0, 0.0,
                            normalize(vNormal), 1.0, emissive);
#endif
  return color;
}

// The material bound to the viewer `v`.
Shading shading_at(MaterialInputs m, vec3 v) {
  Shading s;
  s.v = v;
  s.wo = to_local(m.frame, v);
  s.brdf = brdf_at(make_brdf(m.layer, GEOMETRY, MULTISCATTER != 0, FRESNEL, uEnergyDirect),
                   uEnergyDirect, s.wo);
#if MATERIAL_CLEARCOAT || MATERIAL_SHEEN
  s.bsdf = bsdf_at(make_bsdf(s.brdf, m.coat_weight, m.coat_roughness, to_local(m.frame, m.n_coat),
                             m.sheen_color, m.sheen_roughness, uEnergyCoat),
                   uSheenLut, s.wo);
#endif
  return s;
}

// The number of punctual lights this fragment shades and, with LIGHTS 2 or 3, its cluster's
// (first entry, count) in the listed lights (with LIGHT_COUNT >= 0, punctual_lights' loop has
// the constant count instead).
int light_count(out uvec2 cluster) {
  cluster = uvec2(0u);
#if LIGHTS >= 2
  // The fragment's cluster: a slice of its own view depth, the tile of its pixel centre.
  float depth = max(dot(uViewDepth.xyz, vPosition) + uViewDepth.w, uClusterDepth.x);
  ivec3 cell = ivec3(ivec2(gl_FragCoord.xy / uClusterTile),
                     int(floor(log(depth / uClusterDepth.x) * uClusterDepth.y)));
  cell = clamp(cell, ivec3(0), uClusterGrid - 1);
  cluster = uClusterRange[cell.x + uClusterGrid.x * (cell.y + uClusterGrid.y * cell.z)];
  return uGlobalLightCount + int(cluster.y);
#elif LIGHTS == 1
  return uLightCount;
#else
  return 0;
#endif
}

// The punctual lights (KHR_lights_punctual) reflected, and with the transmission
// extensions transmitted (transmission_weights), towards the viewer.
vec3 punctual_lights(MaterialInputs m, Shading s, float transmission, float thickness,
                     float through, vec3 dt_weight) {
  vec3 color = vec3(0.0);
  uvec2 cluster;
#if LIGHTS == 1 && LIGHT_COUNT >= 0
  const int count = LIGHT_COUNT;
#else
  int count = light_count(cluster);
#endif
#if LIGHTS >= 2
  int next = 0;
  for (;;) {
    // The next light of the cluster that reaches this fragment: lights beyond their range
    // are passed over in this inner loop, which reads only their (position, range), kept
    // beside the cluster's indices; the whole light is read and its BRDF evaluated only for
    // the lights that reach the fragment. (A GPU skips a branch's body where a whole warp
    // is beyond a light either way; llvmpipe masks the lanes of a branch and runs its body
    // all the same, so there the loop over the listed lights cost a whole light's read and
    // BRDF per listed light, where it now costs one per light the SIMD group's fragments
    // need: BENCHMARKS.md "Many punctual lights".) The order is unchanged: the global
    // lights, then the cluster's (both ascending: the unclustered loop's order).
    int found = -1;  // the entry of the next light that reaches the fragment; none yet
    float d = 0.0;
    vec3 to_light = vec3(0.0);
    vec4 sphere = vec4(0.0);
    while (found < 0 && next < count) {
      int entry = next < uGlobalLightCount ? next : int(cluster.x) + (next - uGlobalLightCount);
      sphere = uintBitsToFloat(uListedLight[2 * entry]);
      to_light = sphere.xyz - vPosition;
      d = length(to_light);
      // Beyond its range a light adds exactly 0 (the window below); a directional light has
      // no range (0), so it always passes.
      if (!(sphere.w > 0.0 && d >= sphere.w)) found = entry;
      ++next;
    }
    if (found < 0) break;
    // The light itself: a point or directional light's whole state is beside the entry (a
    // directional light's direction where a point light's position is); a spot light's
    // direction and cone are read from uLights, in the permutation that has spot lights
    // (LIGHTS 3: the branch's loads cost llvmpipe a loop over the lanes even where no lane
    // takes it).
    uvec4 listed = uListedLight[2 * found + 1];
    PunctualLight light;
    light.position = sphere.xyz;
    light.range = sphere.w;
    light.radiance = uintBitsToFloat(listed.xyz);
    light.type = int(listed.w >> 30);
    light.direction = sphere.xyz;
    light.cone = vec2(0.0);
#if LIGHTS == 3
    if (light.type == 1) {
      uint index = listed.w & 0x3fffffffu;
      light.direction = uLights[index].direction;
      light.cone = uLights[index].cone;
    }
#endif
#else
  for (int k = 0; k < count; ++k) {
    PunctualLight light = uLights[k];
    vec3 to_light = light.position - vPosition;
    float d = length(to_light);
    // Beyond its range a light adds exactly 0 (the window below): move on.
    if (light.type != 2 && light.range > 0.0 && d >= light.range) continue;
#endif
    vec3 l;
    vec3 radiance = light.radiance;
    if (light.type == 2) {
      l = -light.direction;
    } else {
      l = to_light / d;
      radiance *= range_attenuation(d, light.range);
      if (light.type == 1) {
        // Spot cone: smooth falloff between the cone angles (KHR_lights_punctual).
        float cd = dot(light.direction, -l);
        float a = clamp(cd * light.cone.x + light.cone.y, 0.0, 1.0);
        radiance *= a * a;
      }
    }
    vec3 wi = to_local(m.frame, l);
#if MATERIAL_TRANSMISSION || MATERIAL_DIFFUSE_TRANSMISSION
    if (wi.z < 0.0) {
      // A light behind the surface reaches the viewer through the diffuse BTDF: the
      // diffuse lobe mirrored to the other side (KHR_materials_diffuse_transmission).
      vec3 wi_m = vec3(wi.xy, -wi.z);
      Brdf brdf_dt = s.brdf;
      brdf_dt.base_color = m.dt_color;
      color += lobe(DEBUG_DIFFUSE, dt_weight * brdf_eval_diffuse(brdf_dt, uEnergyDirect, s.wo, wi_m) * radiance * wi_m.z);
#if MATERIAL_TRANSMISSION
      // The specular BTDF (transmission.glsl's punctual_transmission), attenuated through
      // the medium along the refracted ray (the Sample Viewer's applyVolumeAttenuation).
      vec3 ray = volume_transmission_ray(m.n, s.v, thickness, uIor, uModelScale);
      color += lobe(DEBUG_TRANSMISSION,
                    transmission * punctual_transmission(s.brdf, s.wo, wi_m, uIor) * radiance * wi_m.z *
                        volume_attenuation(length(ray), uAttenuationColor, uAttenuationDistance));
#endif
      continue;
    }
    if (wi.z > 0.0) color -= lobe(DEBUG_DIFFUSE, through * brdf_eval_diffuse(s.brdf, uEnergyDirect, s.wo, wi) * radiance * wi.z);
#endif
    if (wi.z <= 0.0) continue;
#if MATERIAL_CLEARCOAT || MATERIAL_SHEEN
    color += bsdf_lobes(s.bsdf, uEnergyDirect, uEnergyCoat, uSheenLut, s.wo, wi) * radiance * wi.z;
#else
    color += brdf_lobes(s.brdf, uEnergyDirect, s.wo, wi) * radiance * wi.z;
#endif
  }
  return color;
}

// The environment's light reflected (and with diffuse transmission, transmitted) towards
// the viewer: the split sum's lobes under the sheen and the coat, times the occlusion
// (`through`, `dt_weight`: transmission_weights).
vec3 image_based_light(MaterialInputs m, Shading s, float through, vec3 dt_weight) {
  vec3 n = m.n, v = s.v, wo = s.wo;
  float ao = material_occlusion();
#if IBL_OCCLUDERS
  vec3 bounce;
  vec3 visibility = occluder_visibility(vPosition, n, vSlot, bounce);
#else
  const vec3 visibility = vec3(1.0);
#endif
  vec3 prefiltered;
#if MATERIAL_ANISOTROPY
  // The anisotropic lobe's own radiance (anisotropy_ibl.glsl: taps along the stretched
  // lobe), divided by the isotropic table's albedo E = A + B that ibl_shading multiplies
  // back (through F0 A + B), so the single scattering is the lobe's and the
  // multiple-scattering and diffuse terms keep the table's, as in the path tracer.
  if (m.layer.anisotropy > 0.0) {
#if GEOMETRY == 0 && MULTISCATTER
    vec2 ab_aniso = s.brdf.ab_o;  // the IBL's table is the bound Brdf's (see below)
#else
    vec2 ab_aniso = energy_AB(uEnergyIBL, max(wo.z, 1e-4), s.brdf.table_roughness);
#endif
    prefiltered = anisotropic_ibl_radiance(uSpecularCube, uSpecularLevels, uAnisotropicAlbedo,
                                           m.frame, uIblRotation, wo, s.brdf.alpha_x,
                                           s.brdf.alpha_y) /
                  max(ab_aniso.x + ab_aniso.y, 1e-4);
  } else
#endif
    prefiltered = textureLod(uSpecularCube, world_to_env(reflect(-v, n), uIblRotation),
                             roughness_lod(s.brdf.roughness, uSpecularLevels)).rgb;
#if OCCLUDER_BOUNCE
  // The opaque proxies' light in the place of the environment's they hide: visibility L +
  // bounce in all, written as L + bounce / visibility under the visibility applied below
  // (the lobes from the prefiltered and the irradiance terms are linear in them). The
  // reflected part takes the change's cosine-weighted mean, as a rough lobe would see it.
  vec3 unshadowed_bounce = bounce / max(visibility, vec3(1e-4));
  prefiltered = max(prefiltered + unshadowed_bounce, vec3(0.0));
#endif
#if MATERIAL_TRANSMISSION && MATERIAL_VOLUME && GLASS_REFLECTIONS
  {
    // Where the mirror direction meets the opaque frame on the screen, the surface reflects
    // the frame (a wall, the floor) rather than the environment behind it; the frame's
    // colour is final radiance, already shadowed and scaled, so the scale and visibility
    // applied below are divided out of it.
    vec3 seen;
    if (uIblScale > 0.0 &&
        reflected_frame(vPosition, reflect(-v, n), uViewProjection, uInverseViewProjection,
                        uTransmissionDepth, uTransmissionFrame,
                        log2(uTransmissionFrameSize.x) * clamp(m.roughness, 0.0, 1.0), seen))
      prefiltered = seen / (uIblScale * max(visibility, vec3(1e-4)));
  }
#endif
  vec3 irradiance = environment_irradiance(n);
#if OCCLUDER_BOUNCE
  irradiance = max(irradiance + kPi * unshadowed_bounce, vec3(0.0));
#endif
#if GEOMETRY == 0 && MULTISCATTER
  // reference: the IBL's energy table is the punctual lights' (both height-correlated
  // Smith), so the bound Brdf is the IBL's too and brdf_at has looked up (A, B) at n.v
  // already (two of the compensation's fetches and a make_brdf fewer per fragment).
  Brdf ibl = s.brdf;
  vec3 indirect = wo.z >= 1e-4 ? ibl_shading_ab(ibl, uEnergyIBL, wo.z, ibl.ab_o, prefiltered, irradiance)
                               : ibl_shading(ibl, uEnergyIBL, wo.z, prefiltered, irradiance);
#else
  Brdf ibl = make_brdf(m.layer, GEOMETRY, MULTISCATTER != 0, FRESNEL, uEnergyIBL);
  vec3 indirect = ibl_shading(ibl, uEnergyIBL, dot(n, v), prefiltered, irradiance);
#endif
  indirect = ibl_lobes(indirect, ibl, uEnergyIBL, dot(n, v), irradiance);
#if MATERIAL_TRANSMISSION || MATERIAL_DIFFUSE_TRANSMISSION
  {
    // The diffuse lobe's environment light: E(n) for the part that stays, dt E(-n) for the
    // diffuse BTDF; the specular BTDF's light is the frame's (transmitted_light).
    vec3 irradiance_back = environment_irradiance(-n);
    Brdf ibl_dt = ibl;
    ibl_dt.base_color = m.dt_color;
    indirect += lobe(DEBUG_DIFFUSE, ibl_diffuse(ibl_dt, uEnergyIBL, dot(n, v), dt_weight * irradiance_back) -
                                        ibl_diffuse(ibl, uEnergyIBL, dot(n, v), through * irradiance));
  }
#endif
#if MATERIAL_SHEEN
  {
    // The base under the sheen, scaled as bsdf.h's min(1 - c E(n.v), 1 - c E(n.l)) scales
    // it under a uniform environment: by 1 - c E_max_avg(n.v), the light's side averaged
    // over a cosine lobe (core/sheen.h; the README's one-sided 1 - c E(n.v) left the base
    // up to 20% brighter than the path tracer's at normal incidence).
    float sr = clamp(m.sheen_roughness, kMinSheenRoughness, 1.0);
    vec3 sc = clamp(m.sheen_color, 0.0, 1.0);
    indirect = lobe(DEBUG_SHEEN, sheen_ibl(n, v, sc, sr)) +
               (1.0 - max3(sc) * sheen_E_max_avg(uSheenLut, dot(n, v), sr)) * indirect;
  }
#endif
#if MATERIAL_CLEARCOAT
  {
    float cw = saturate(m.coat_weight);
    float ncv = dot(m.n_coat, v);
    float cr = clamp(m.coat_roughness, kMinRoughness, 1.0);
    vec3 coat_prefiltered = textureLod(uSpecularCube, world_to_env(reflect(-v, m.n_coat), uIblRotation),
                                       roughness_lod(cr, uSpecularLevels)).rgb;
    indirect = lobe(DEBUG_CLEARCOAT, coat_ibl(cw, cr, uEnergyCoat, ncv, coat_prefiltered)) +
               (1.0 - cw * coat_fresnel(abs(ncv))) * indirect;
  }
#endif
  return ao * visibility * uIblScale * indirect;
}

#if MATERIAL_TRANSMISSION
// KHR_materials_transmission: the specular BTDF's light is what the opaque frame shows
// through the surface (transmission.glsl), through the diffuse lobe's slot under the
// dielectric's specular and base colour, then under the sheen and the coat.
vec3 transmitted_light(MaterialInputs m, Shading s, float transmission, float thickness) {
  vec3 n = m.n, v = s.v;
  TransmissionInputs t;
  t.position = vPosition;
  t.n = n;
  t.v = v;
  // The material's perceptual roughness, as the Sample Viewer's getIBLVolumeRefraction reads
  // it: a smooth surface reads the frame's level 0 alone (kMinRoughness bounds the GGX
  // lobes, not this blur), so a frame whose transmissive surfaces are all smooth needs no
  // mip chain (renderer.cpp).
  t.roughness = clamp(m.roughness, 0.0, 1.0);
#if MATERIAL_DISPERSION
  t.iors = dispersion_iors(uIor, uDispersion);
#else
  t.iors = vec3(uIor);
#endif
  t.thickness = thickness;
  t.model_scale = uModelScale;
  t.attenuation_color = uAttenuationColor;
  t.attenuation_distance = uAttenuationDistance;
#if MATERIAL_VOLUME
  vec3 seen = thick_refracted_radiance(
      t, uBackFaces != 0, uTransmissionFrame, uTransmissionDepth, uTransmissionFrameSize,
      uBackPosition, uBackNormal, uBackFaceRect, gl_FragCoord.xy / uTransmissionFrameSize,
      uViewProjection, uInverseViewProjection, uSpecularCube, uIblRotation, uSpecularLevels,
      IBL != 0 ? uIblScale : 0.0, MATERIAL_DISPERSION != 0);
#else
  vec3 seen = refracted_radiance(t, uTransmissionFrame, uTransmissionFrameSize, uViewProjection,
                                 uCameraPosition, uSpecularCube, uIblRotation, uSpecularLevels,
                                 IBL != 0 ? uIblScale : 0.0, MATERIAL_DISPERSION != 0);
#endif
  Brdf tb = make_brdf(m.layer, GEOMETRY, MULTISCATTER != 0, FRESNEL, uEnergyIBL);
  vec3 transmitted = ibl_diffuse(tb, uEnergyIBL, dot(n, v), kPi * transmission * seen);
#if MATERIAL_SHEEN
  transmitted *= 1.0 - max3(clamp(m.sheen_color, 0.0, 1.0)) *
                           sheen_E(uSheenLut, dot(n, v), clamp(m.sheen_roughness, kMinSheenRoughness, 1.0));
#endif
#if MATERIAL_CLEARCOAT
  transmitted *= 1.0 - saturate(m.coat_weight) * coat_fresnel(abs(dot(m.n_coat, v)));
#endif
  return lobe(DEBUG_TRANSMISSION, transmitted);
}
#endif

// The fragment's colour: the light reflected and transmitted plus the emission, or with
// DEBUG_CHANNEL the selected input or lobe; the alpha for BLEND.
vec4 surface_output(MaterialInputs m, vec3 color) {
  color += lobe(DEBUG_EMISSIVE, m.emissive);
#if DEBUG_CHANNEL != DEBUG_NONE
  color = debug_channel(color, m.base_color.rgb, m.metallic, m.roughness, m.n, material_occlusion(),
                        m.emissive);
#endif
  return vec4(color, ALPHA_MODE == 2 ? m.base_color.a : 1.0);
}

void main() {
  vec4 base_color = material_base_color();
#if ALPHA_MODE == 1
  if (base_color.a < uAlphaCutoff) discard;
#endif
  vec3 emissive = material_emission();
#if MATERIAL_UNLIT
  outColor = unlit_output(base_color, emissive);
#else
  vec3 v = normalize(uCameraPosition - vPosition);
  MaterialInputs m = material_inputs(base_color, emissive, v);
  Shading s = shading_at(m, v);
  float transmission, thickness, through;
  vec3 dt_weight;
  transmission_weights(m, transmission, thickness, through, dt_weight);
  vec3 color = punctual_lights(m, s, transmission, thickness, through, dt_weight);
#if IBL
  color += image_based_light(m, s, through, dt_weight);
#endif
#if MATERIAL_TRANSMISSION
  color += transmitted_light(m, s, transmission, thickness);
#endif
  outColor = surface_output(m, color);
#endif
}
