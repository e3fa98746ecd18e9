// Transmission in real time: KHR_materials_transmission, _volume, _dispersion and
// _diffuse_transmission as the Khronos glTF Sample Viewer (ibl.glsl getIBLVolumeRefraction,
// punctual.glsl applyVolumeAttenuation) and Filament's screen-space refraction do. The
// renderer draws the opaque scene (and the background) first into a mip-mapped colour
// target; a transmissive surface then reads that frame where its refracted ray leaves the
// medium, projected to the screen, at a mip level that grows with roughness. What the
// path tracer integrates exactly (the rough dielectric BTDF, the paths inside the medium)
// is approximated by one refraction at the entry and a straight segment of the volume's
// thickness: docs/SPLIT_SUM_ERRORS.md measures where that differs from the truth.
#include "ibl.glsl"

// KHR_materials_dispersion (core/dispersion.h's dispersion_iors): the README's normative
// n(lambda) = max(n_d + (n_d - 1) / V_d (523655 / lambda^2 - 1.5168), 1), V_d = 20 /
// dispersion, at the wavelengths the R, G, B channels stand for (the path tracer's
// kChannelWavelengthR/G/B): those where the README's real-time sample, ior -/+ halfSpread
// with halfSpread = (ior - 1) 0.025 dispersion, is exact, so both renderers refract each
// channel with the same ior.
const vec3 kChannelWavelengthsNm = vec3(717.64, 587.57, 509.56);

vec3 dispersion_iors(float ior, float dispersion) {
  if (dispersion <= 0.0 || ior <= 1.0) return vec3(ior);
  float inv_abbe = dispersion / 20.0;
  vec3 n = ior + (ior - 1.0) * inv_abbe *
                     (523655.0 / (kChannelWavelengthsNm * kChannelWavelengthsNm) - 1.5168);
  n.g = ior;  // the d line itself
  return max(n, vec3(1.0));
}

// The Sample Viewer's applyIorToRoughness: the refracted lobe's blur scales with how far
// the interface bends light, none at ior 1 (a rough interface of ior 1 changes nothing),
// all of the roughness from ior 1.5 on.
float transmission_roughness(float roughness, float ior) {
  return roughness * clamp(ior * 2.0 - 2.0, 0.0, 1.0);
}

// The mip level of the opaque frame (`width` pixels wide) to read for a rough interface:
// the Sample Viewer's log2(width) * applyIorToRoughness(roughness, ior), so roughness 1
// reads the 1x1 level (the frame's mean).
float transmission_lod(float roughness, float ior, float width) {
  return log2(width) * transmission_roughness(roughness, ior);
}

// The Sample Viewer's getVolumeTransmissionRay: the view ray refracted into the medium
// (Snell, ior outside 1) and carried through the volume's thickness, which glTF gives in
// the mesh's object space: scaled per axis by the model matrix's column lengths. Zero for a
// thin wall (thickness 0) and under total internal reflection (ior < 1).
vec3 volume_transmission_ray(vec3 n, vec3 v, float thickness, float ior, vec3 model_scale) {
  if (thickness <= 0.0 || ior <= 0.0) return vec3(0.0);
  vec3 r = refract(-v, n, 1.0 / ior);
  if (dot(r, r) == 0.0) return vec3(0.0);
  return normalize(r) * thickness * model_scale;
}

// Beer-Lambert through `distance` of the medium (KHR_materials_volume: the transmittance
// is attenuationColor^(distance / attenuationDistance)); attenuation_distance <= 0 stands
// for the spec's default, infinity: nothing is absorbed.
vec3 volume_attenuation(float distance, vec3 attenuation_color, float attenuation_distance) {
  if (attenuation_distance <= 0.0 || distance <= 0.0) return vec3(1.0);
  return pow(max(attenuation_color, 0.0), vec3(distance / attenuation_distance));
}

// The screen position ([0, 1]^2, GL's row order: the colour target's texture coordinates)
// of the clip-space point `clip`; false when it is behind the camera or off the screen.
bool clip_to_screen(vec4 clip, out vec2 uv) {
  uv = vec2(0.0);
  if (clip.w <= 0.0) return false;
  uv = clip.xy / clip.w * 0.5 + 0.5;
  return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
}

// The same for world point p.
bool project_to_screen(mat4 view_projection, vec3 p, out vec2 uv) {
  return clip_to_screen(view_projection * vec4(p, 1.0), uv);
}

// What the camera would see through the surface at `position`: per channel (three iors
// with dispersion, else one), the opaque frame at the exit point of the refracted ray,
// attenuated along it; where the exit point leaves the screen, the environment (the
// specular cube at the same roughness) along the line from the camera through it, which
// is what the frame would have shown there without geometry.
struct TransmissionInputs {
  vec3 position;     // world
  vec3 n;            // shading normal, towards v
  vec3 v;            // towards the camera
  float roughness;   // perceptual
  vec3 iors;         // per channel
  float thickness;   // object space (0: thin walled)
  vec3 model_scale;  // the model matrix's column lengths
  vec3 attenuation_color;
  float attenuation_distance;  // <= 0: none
};

vec3 refracted_radiance(TransmissionInputs t, sampler2D frame, vec2 frame_size,
                        mat4 view_projection, vec3 camera, samplerCube env_cube,
                        vec2 env_rotation, int env_levels, float env_scale, bool dispersion) {
  vec3 result = vec3(0.0);
  int channels = dispersion ? 3 : 1;
  for (int c = 0; c < channels; ++c) {
    float ior = t.iors[c];
    vec3 ray = volume_transmission_ray(t.n, t.v, t.thickness, ior, t.model_scale);
    vec3 exit_point = t.position + ray;
    float rough = transmission_roughness(t.roughness, ior);
    vec2 uv;
    vec3 seen;
    if (project_to_screen(view_projection, exit_point, uv)) {
      seen = textureLod(frame, uv, log2(frame_size.x) * rough).rgb;
    } else {
      vec3 d = normalize(exit_point - camera);
      seen = env_scale * textureLod(env_cube, world_to_env(d, env_rotation),
                                    rough * float(env_levels - 1)).rgb;
    }
    seen *= volume_attenuation(length(ray), t.attenuation_color, t.attenuation_distance);
    if (dispersion)
      result[c] = seen[c];
    else
      result = seen;
  }
  return result;
}

// The base's diffuse lobe alone, which transmission replaces (the README's
// mix(diffuse_brdf, btdf, transmission)), under the dielectric's specular as the diffuse is.
// ibl_shading is linear in the irradiance and its lambertian term is the only one that
// reads base_color (the Fresnel and compensation terms were set by make_brdf): the
// difference with the base colour zeroed is that term alone, lit by `irradiance` (which
// may be negative: a difference of lightings).
vec3 ibl_diffuse(Brdf b, sampler2D ibl_table, float NdotV, vec3 irradiance) {
  Brdf black = b;
  black.base_color = vec3(0.0);
  return ibl_shading(b, ibl_table, NdotV, vec3(0.0), irradiance) -
         ibl_shading(black, ibl_table, NdotV, vec3(0.0), irradiance);
}

// The same for a light: brdf_eval's diffuse lobe (without its multiple-scattering
// specular), f(wo, wi) without the cosine; wi may be below the surface (the diffuse
// transmission's mirrored direction is passed by the caller).
vec3 brdf_eval_diffuse(Brdf b, sampler2D table, vec3 wo, vec3 wi) {
  vec3 h = normalize(wo + wi);
  vec3 diffuse_weight;
  brdf_specular_fresnel(b, dot(wo, h), diffuse_weight);
  Brdf black = b;
  black.base_color = vec3(0.0);
  return brdf_eval_diffuse_and_ms(b, table, wo, wi, diffuse_weight) -
         brdf_eval_diffuse_and_ms(black, table, wo, wi, diffuse_weight);
}

// A punctual light behind the surface seen through it (the Sample Viewer's
// getPunctualRadianceTransmission): the specular BTDF approximated by the GGX lobe around
// the straight-through direction, i.e. the base's specular lobe evaluated with the
// light's direction mirrored to the viewer's side (wi_mirrored, local frame, z > 0), at
// the roughness applyIorToRoughness gives (at least kMinRoughness, as every lobe), times
// what the dielectric does not reflect, 1 - F(v.h), and the dielectric's base colour.
// f(wo, wi) without the cosine; the caller multiplies by the transmission factor and by
// wi_mirrored.z (the Sample Viewer leaves the cosine out; with it the lobe is the
// mirrored BRDF lobe's value and a rough pane does not glow at grazing angles).
vec3 punctual_transmission(Brdf b, vec3 wo, vec3 wi_mirrored, float ior) {
  if (wo.z <= 0.0 || wi_mirrored.z <= 0.0) return vec3(0.0);
  float r = max(transmission_roughness(b.roughness, ior), kMinRoughness);
  float alpha = r * r;
  vec3 h = normalize(wo + wi_mirrored);
  float D = DistributionGGX(h, alpha);
  float G = SmithG2HeightCorrelated(wo, wi_mirrored, alpha);
  float c = 1.0 - saturate(dot(wo, h));
  float c2 = c * c;
  vec3 F = b.spec_weight * (b.F0_d + (b.F90_d - b.F0_d) * (c2 * c2 * c));
  return (1.0 - F) * (1.0 - b.metallic) * b.base_color * (D * G / (4.0 * wo.z * wi_mirrored.z));
}
