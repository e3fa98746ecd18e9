// Split-sum image-based lighting (Karis 2013) with the baker's maps (ibl/bake.h):
//   integral f L cos ~= prefiltered(R, roughness) (F0 A + B) + kd baseColor E(n) / pi
// and, with compensation, the multiple-scattering form of Fdez-Aguera 2019 written with
// the same Kulla-Conty quantities as the C++ Brdf (so a white furnace gives exactly 1).
#include "brdf.glsl"
#include "equirect.glsl"

// SH9 irradiance (ibl/bake.h's SH9 convention: irradiance coefficients, cosine lobe folded
// in, 1/pi not; Ramamoorthi & Hanrahan 2001), real SH basis in the order
// (0,0), (1,-1), (1,0), (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2).
vec3 eval_sh_irradiance(vec3 sh[9], vec3 n) {
  return sh[0] * 0.282095 + sh[1] * (0.488603 * n.y) + sh[2] * (0.488603 * n.z) +
         sh[3] * (0.488603 * n.x) + sh[4] * (1.092548 * n.x * n.y) +
         sh[5] * (1.092548 * n.y * n.z) + sh[6] * (0.315392 * (3.0 * n.z * n.z - 1.0)) +
         sh[7] * (1.092548 * n.x * n.z) + sh[8] * (0.546274 * (n.x * n.x - n.y * n.y));
}

// ibl/bake.h roughness_lod for RoughnessMapping::kLinear: roughness = level / (levels - 1).
float roughness_lod(float roughness, int levels) { return roughness * float(levels - 1); }

// Specular and diffuse IBL for one shading point. `prefiltered` is the specular cube at
// R and the roughness's mip, `irradiance` E(n) (not divided by pi). `ibl_table` is the
// EnergyTable of the IBL G (k = alpha/2 for classic), the split-sum LUT.
vec3 ibl_shading(Brdf b, sampler2D ibl_table, float NdotV, vec3 prefiltered, vec3 irradiance) {
  float mu = max(NdotV, 1e-4);
  vec2 ab = energy_AB(ibl_table, mu, b.roughness);
  vec3 FssEss = b.F0 * ab.x + ab.y;  // single-scattering specular albedo
  vec3 lambert = (1.0 - b.metallic) * b.base_color;
  if (!b.multiscatter) {
    // kd = (1 - F)(1 - metallic) with F at n.v (the split-sum's n = v assumption).
    vec3 kd = 1.0 - brdf_fresnel(b, mu);
    return prefiltered * FssEss + kd * lambert * irradiance * kInvPi;
  }
  // Compensated: the multiple-scattering lobe integrates to Fms (1 - E(mu_o)) against the
  // cosine-weighted irradiance, and the diffuse lobe to (1 - Es(mu_o)) of it (the same
  // normalisations as Brdf::eval_diffuse_and_ms), so a white furnace returns 1.
  vec2 ab_avg = energy_AB_avg(ibl_table, b.roughness);
  float E_avg = ab_avg.x + ab_avg.y;
  vec3 Fms = multiscatter_fresnel(b.F0, E_avg);
  float E = ab.x + ab.y;
  vec3 Es = FssEss + Fms * (1.0 - E);
  return prefiltered * FssEss + (Fms * (1.0 - E) + lambert * (1.0 - Es)) * irradiance * kInvPi;
}
