// The punctual lights (KHR_lights_punctual) at a fragment of the surface program
// (pbr_fragment.glsl), after Filament's surface_light_punctual.fs: the lights' buffers, the
// fragment's cluster (Olsson et al. 2012; light_clusters.h) and the loop that reflects, and
// with the transmission extensions transmits, each light towards the viewer. Included by
// pbr_fragment.glsl after its Shading and transmission_weights, which it reads.

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

// KHR_lights_punctual's recommended range window clamp(1 - (d/range)^4, 0, 1) over d^2
// (as the Khronos sample viewer and the path tracer's lights.cpp).
float range_attenuation(float d, float range) {
  if (range <= 0.0) return 1.0 / (d * d);
  float r = d / range;
  return clamp(1.0 - r * r * r * r, 0.0, 1.0) / (d * d);
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
    // need: docs/benchmarks_archive.md, "Many punctual lights".) The order is unchanged: the
    // global lights, then the cluster's (both ascending: the unclustered loop's order).
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
