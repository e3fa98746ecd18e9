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
// R and the roughness's mip (for an anisotropic base, anisotropy_ibl.glsl's lobe radiance
// over E), `irradiance` E(n) (not divided by pi). `ibl_table` is the EnergyTable of the IBL G (k = alpha/2 for
// classic), the split-sum LUT, and `b` was made with it.
//
// reference (glTF Appendix B, the split sum of each Fresnel term):
//   specular = prefiltered ((1 - m) s (F0_d A + B) + m (baseColor A + B))
//   diffuse  = (1 - m) baseColor E(n)/pi (1 - max3(s F_d(n.v)))             uncompensated
//   diffuse  = (1 - m) baseColor E(n)/pi (1 - max3(Es_d(n.v)))               compensated,
//              + Fms (1 - E(n.v)) E(n)/pi
// where Es_d is the dielectric's full specular albedo of Brdf::eval_diffuse_and_ms: the
// cosine-weighted integral of its (1 - max3(Es_d(o)))(1 - max3(Es_d(i))) / (1 - max3(Es_d_avg))
// is (1 - max3(Es_d(o))) (Fdez-Aguera 2019's form), so a white furnace returns 1.
// KHR_materials_iridescence (the Khronos Sample Viewer's approach): the thin-film Fresnel
// at n.v times the directional albedo A + B replaces each split-sum Fresnel term by the
// iridescence factor; the compensated diffuse keeps the plain dielectric's weight, as the
// C++ Brdf does.
// `ab` is the IBL table's (A, B) at mu = max(n.v, 1e-4) (ibl_shading looks it up).
vec3 ibl_shading_ab(Brdf b, sampler2D ibl_table, float mu, vec2 ab, vec3 prefiltered,
                    vec3 irradiance) {
  vec3 lambert = (1.0 - b.metallic) * b.base_color;
  float E = ab.x + ab.y;
  if (!b.reference) {
    vec3 FssEss = b.F0 * ab.x + ab.y;  // single-scattering specular albedo
#ifdef BRDF_IRIDESCENCE
    vec3 F_irid = iridescence_fresnel(mu, b.film_ior, b.film_thickness, b.F0);
    FssEss = mix(FssEss, F_irid * E, b.iridescence);
#endif
    if (!b.multiscatter) {
      // kd = (1 - F)(1 - metallic) with F at n.v (the split-sum's n = v assumption).
      vec3 kd = 1.0 - brdf_fresnel(b, mu);
#ifdef BRDF_IRIDESCENCE
      kd = 1.0 - mix(brdf_fresnel(b, mu), F_irid, b.iridescence);
#endif
      return prefiltered * FssEss + kd * lambert * irradiance * kInvPi;
    }
    // Compensated: the multiple-scattering lobe integrates to Fms (1 - E(mu_o)) against
    // the cosine-weighted irradiance, and the diffuse lobe to (1 - Es(mu_o)) of it.
    vec2 ab_avg = energy_AB_avg(ibl_table, b.table_roughness);
    float E_avg = ab_avg.x + ab_avg.y;
    vec3 Fms = multiscatter_fresnel(b.F0, E_avg);
    vec3 Es = b.F0 * ab.x + ab.y + Fms * (1.0 - E);
    return prefiltered * FssEss + (Fms * (1.0 - E) + lambert * (1.0 - Es)) * irradiance * kInvPi;
  }
  vec3 Ed = brdf_dielectric_albedo(b, ab);
  vec3 Em = b.base_color * ab.x + ab.y;
  vec3 Fd = b.F0_d + (b.F90_d - b.F0_d) * fresnel_weight(b, mu);
#ifdef BRDF_IRIDESCENCE
  vec3 Fd_irid = iridescence_fresnel(mu, b.film_ior, b.film_thickness, b.F0_d);
  Ed = mix(Ed, b.spec_weight * Fd_irid * E, b.iridescence);
  Em = mix(Em, iridescence_fresnel(mu, b.film_ior, b.film_thickness, b.base_color) * E,
           b.iridescence);
  Fd = mix(Fd, Fd_irid, b.iridescence);
#endif
  vec3 specular = prefiltered * ((1.0 - b.metallic) * Ed + b.metallic * Em);
  if (!b.multiscatter) return specular + lambert * (1.0 - max3(b.spec_weight * Fd)) * irradiance * kInvPi;
  // b.Fms, b.Fms_d, b.E_avg are the IBL table's (make_brdf was given it).
  vec3 Es_d = brdf_dielectric_albedo(b, ab) + b.Fms_d * (1.0 - E);
  // The anisotropic compensation (brdf.glsl) reflects Fms (E_tot - E_ss) + Fms (1 - E_tot) =
  // Fms (1 - E_ss(wo)) of a uniform light, E_ss the anisotropic lobe's albedo at wo (its
  // table's, looked up by brdf_at); the diffuse keeps the isotropic tables' weight.
  float E_ms = b.aniso_ms ? b.E_ss_o : E;
  return specular + (b.Fms * (1.0 - E_ms) + lambert * (1.0 - max3(Es_d))) * irradiance * kInvPi;
}

vec3 ibl_shading(Brdf b, sampler2D ibl_table, float NdotV, vec3 prefiltered, vec3 irradiance) {
  float mu = max(NdotV, 1e-4);
  return ibl_shading_ab(b, ibl_table, mu, energy_AB(ibl_table, mu, b.table_roughness),
                        prefiltered, irradiance);
}

// KHR_materials_clearcoat's IBL: the coat's GGX lobe (ior 1.5, F0 0.04) as its own split
// sum at the coat's roughness, `prefiltered` taken along the coat normal's reflection;
// `coat_table` is the reference (height-correlated Smith) EnergyTable, the coat's G.
// Returns the coat's radiance; the layers under it are scaled by 1 - clearcoat F_c(n_c.v).
vec3 coat_ibl(float weight, float roughness, sampler2D coat_table, float NcdotV,
              vec3 prefiltered) {
  float mu = max(NcdotV, 1e-4);
  vec2 ab = energy_AB(coat_table, mu, clamp(roughness, kMinRoughness, 1.0));
  return weight * prefiltered * (0.04 * ab.x + ab.y);
}
