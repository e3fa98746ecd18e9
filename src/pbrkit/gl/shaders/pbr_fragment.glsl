#version 450
// The scene's surfaces: the material model of brdf.glsl lit by KHR_lights_punctual lights
// and split-sum IBL (ibl.glsl), with glTF's textures, emission, normal and occlusion maps
// (occlusion on indirect light only), alpha MASK / BLEND and double-sided materials.
//
// Every feature is a compile-time #define: shader_permutations.cpp's
// SurfaceFeatures::define_list() writes each one (MATERIAL_*, HAS_<slot>, LIGHTS, IBL, ...)
// and says what it selects, after surface_bindings.h's prelude, which names every texture
// slot (SLOT_<slot>) and every texture unit and buffer binding point (BINDING_<name>).
//
// main() reads as the shading's steps: the material's inputs (material_inputs.glsl, one
// function per extension), the material bound to the viewer (shading_at) and the
// transmission extensions' weights (transmission_weights), the punctual lights
// (surface_light_punctual.glsl), the image-based light and the light transmitted from the
// frame behind (surface_light_indirect.glsl), the output. The lights' files follow
// Filament's surface_light_punctual.fs and surface_light_indirect.fs.
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

#include "surface_light_punctual.glsl"
#include "surface_light_indirect.glsl"

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
