// The material model of docs/MODEL.md in GLSL, mirroring src/pbrkit/core/microfacet.cpp
// and src/pbrkit/core/brdf.cpp line by line (same names, same order of operations), so
// the OpenGL renderer and the path tracer evaluate one BRDF. tests/gl/brdf_glsl_test.cpp
// checks Brdf::eval against brdf_eval below to 1e-4 relative.
//
// Directions are in the local shading frame (n = +Z, +X the anisotropy direction), wo
// towards the viewer, wi towards the light. alpha = roughness^2 (Burley 2012 / Karis 2013).
// BRDF_IRIDESCENCE (defined or not): compile the thin-film Fresnel in (a material without
// KHR_materials_iridescence pays nothing for it).

#include "math.glsl"
#include "iridescence.glsl"

const float kMinRoughness = 0.02;  // pbrkit::kMinRoughness

// pbrkit::GeometryModel
const int GEOMETRY_REFERENCE = 0;       // height-correlated Smith (Heitz 2014, eq. 99)
const int GEOMETRY_CLASSIC_DIRECT = 1;  // Schlick-GGX, k = (roughness + 1)^2 / 8
const int GEOMETRY_CLASSIC_IBL = 2;     // Schlick-GGX, k = alpha / 2
const int FRESNEL_SCHLICK = 0;
const int FRESNEL_SG = 1;  // UE4's spherical-Gaussian Schlick (real-time path only)

// GGX D for a local-frame half vector: 1 / (pi alpha^2 ((hx^2 + hy^2) / alpha^2 + hz^2)^2).
float DistributionGGX(vec3 h, float alpha) {
  if (h.z <= 0.0) return 0.0;
  float s2 = h.x * h.x + h.y * h.y;
  float e = s2 / (alpha * alpha) + h.z * h.z;
  return 1.0 / (kPi * alpha * alpha * e * e);
}

// Smith's Lambda for GGX (Heitz 2014, eq. 72); only called with w.z > 0.
float SmithLambdaGGX(vec3 w, float alpha) {
  float cos2 = w.z * w.z;
  float tan2 = (w.x * w.x + w.y * w.y) / cos2;
  return 0.5 * (-1.0 + sqrt(1.0 + alpha * alpha * tan2));
}

float SmithG1GGX(vec3 w, float alpha) {
  if (w.z <= 0.0) return 0.0;
  return 1.0 / (1.0 + SmithLambdaGGX(w, alpha));
}

float SmithG2HeightCorrelated(vec3 wo, vec3 wi, float alpha) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  return 1.0 / (1.0 + SmithLambdaGGX(wo, alpha) + SmithLambdaGGX(wi, alpha));
}

// LearnOpenGL's GeometrySchlickGGX (de Vries, "PBR: Theory").
float GeometrySchlickGGX(float NdotX, float k) {
  float nom = NdotX;
  float denom = NdotX * (1.0 - k) + k;
  return nom / denom;
}

float k_direct(float roughness) { return (roughness + 1.0) * (roughness + 1.0) / 8.0; }
float k_ibl(float roughness) { return roughness * roughness / 2.0; }

float GeometrySmithSchlick(float NdotV, float NdotL, float k) {
  return GeometrySchlickGGX(max(NdotV, 0.0), k) * GeometrySchlickGGX(max(NdotL, 0.0), k);
}

float GeometryG(int model, vec3 wo, vec3 wi, float roughness) {
  if (model == GEOMETRY_REFERENCE) return SmithG2HeightCorrelated(wo, wi, roughness * roughness);
  if (model == GEOMETRY_CLASSIC_DIRECT) return GeometrySmithSchlick(wo.z, wi.z, k_direct(roughness));
  return GeometrySmithSchlick(wo.z, wi.z, k_ibl(roughness));
}

// Fresnel-Schlick: F0 + (1 - F0)(1 - cos)^5.
vec3 fresnelSchlick(float cosTheta, vec3 F0) {
  float m = saturate(1.0 - cosTheta);
  float m2 = m * m;
  return F0 + (1.0 - F0) * (m2 * m2 * m);
}

// Karis 2013: F0 + (1 - F0) 2^((-5.55473 c - 6.98316) c).
vec3 fresnelSchlickSG(float cosTheta, vec3 F0) {
  float c = saturate(cosTheta);
  return F0 + (1.0 - F0) * exp2((-5.55473 * c - 6.98316) * c);
}

vec3 fresnelSchlickAverage(vec3 F0) { return F0 + (1.0 - F0) * (1.0 / 21.0); }

// Kulla & Conty 2017, slide 18: Fms = Favg^2 E_avg / (1 - Favg (1 - E_avg)).
vec3 multiscatter_fresnel(vec3 F0, float E_avg) {
  vec3 F_avg = fresnelSchlickAverage(F0);
  return F_avg * F_avg * E_avg / (1.0 - F_avg * (1.0 - E_avg));
}

// The EnergyTable (core/energy.h) as a 32 x 33 RGBA32F texture (gl/energy_texture.cpp):
// rows 0..31 hold (A, B) at mu = i / 31 (x) and roughness = j / 31 (y) in .xy and the next
// node along mu in .zw; row 32 holds (A_avg, B_avg) at x = j in .xy and at j + 1 in .zw.
// Interpolated by hand exactly as EnergyTable::AB / AB_avg do (no hardware filtering, whose
// fixed-point weights would differ from the C++ table); two fetches per lookup.
const int kEnergyMuSize = 32;
const int kEnergyRoughnessSize = 32;

vec2 energy_AB(sampler2D table, float mu, float roughness) {
  float x = clamp(mu, 0.0, 1.0) * float(kEnergyMuSize - 1);
  float y = clamp(roughness, 0.0, 1.0) * float(kEnergyRoughnessSize - 1);
  int i0 = min(int(x), kEnergyMuSize - 2);
  int j0 = min(int(y), kEnergyRoughnessSize - 2);
  float fx = x - float(i0), fy = y - float(j0);
  vec4 row0 = texelFetch(table, ivec2(i0, j0), 0);
  vec4 row1 = texelFetch(table, ivec2(i0, j0 + 1), 0);
  return mix(mix(row0.xy, row0.zw, fx), mix(row1.xy, row1.zw, fx), fy);
}

vec2 energy_AB_avg(sampler2D table, float roughness) {
  float y = clamp(roughness, 0.0, 1.0) * float(kEnergyRoughnessSize - 1);
  int j0 = min(int(y), kEnergyRoughnessSize - 2);
  vec4 pair = texelFetch(table, ivec2(j0, kEnergyRoughnessSize), 0);
  return mix(pair.xy, pair.zw, y - float(j0));
}

float max3(vec3 v) { return max(v.x, max(v.y, v.z)); }

// ---- Anisotropic GGX (microfacet.h; KHR_materials_anisotropy): alpha_x along the local
// +X (the anisotropy direction), alpha_y along +Y.

// D(h) = 1 / (pi ax ay (hx^2/ax^2 + hy^2/ay^2 + hz^2)^2).
float DistributionGGXAniso(vec3 h, float ax, float ay) {
  if (h.z <= 0.0) return 0.0;
  float x = h.x / ax, y = h.y / ay;
  float e = x * x + y * y + h.z * h.z;
  return 1.0 / (kPi * ax * ay * e * e);
}

// Smith's Lambda (Heitz 2014, eq. 86); only for w.z > 0.
float SmithLambdaGGXAniso(vec3 w, float ax, float ay) {
  float x = ax * w.x, y = ay * w.y;
  return 0.5 * (-1.0 + sqrt(1.0 + (x * x + y * y) / (w.z * w.z)));
}

// ---- The anisotropic lobe's multiple-scattering compensation (core/anisotropic_energy.h),
// compiled in where the program binds its table at BINDING_ANISOTROPIC_ENERGY (the surface
// program's prelude; a shader unit test defines it): without it an anisotropic lobe keeps
// the isotropic Kulla-Conty lobe at the geometric-mean alpha.
#ifdef BINDING_ANISOTROPIC_ENERGY
// AnisotropicEnergyTable as gl/energy_texture.h's create_anisotropic_energy_texture lays it
// out, interpolated by hand exactly as AnisotropicEnergyTable::lookup and ::averages do.
layout(binding = BINDING_ANISOTROPIC_ENERGY) uniform sampler3D uAnisotropicEnergy;
const int kAnisoEnergyMu = 16, kAnisoEnergyPhi = 8, kAnisoEnergyR = 16, kAnisoEnergyS = 8;

// The nodes and weight of coordinate c in [0, 1] over n nodes (anisotropic_energy.cpp's bracket).
void aniso_energy_bracket(float c, int n, out int i0, out float f) {
  float x = clamp(c * float(n - 1), 0.0, float(n - 1));
  i0 = min(int(x), n - 2);
  f = x - float(i0);
}

// AnisotropicEnergyTable::coordinates: (sqrt(n.v), p, sqrt(alpha_y), sqrt(strength)).
vec4 aniso_energy_coordinates(vec3 wo, float ax, float ay) {
  vec2 xy = abs(wo.xy);
  if (ay > ax) {
    float t = ax;
    ax = ay;
    ay = t;
    xy = xy.yx;
  }
  float p = xy.x + xy.y > 0.0 ? xy.y / (xy.x + xy.y) : 0.0;
  float s = ay < 1.0 ? clamp((ax - ay) / (1.0 - ay), 0.0, 1.0) : 0.0;
  return vec4(sqrt(clamp(wo.z, 0.0, 1.0)), p, sqrt(ay), sqrt(s));
}

// AnisotropicEnergyTable::lookup at wo: (h, E_tot) for column 0, (E_ss, -) for column 1.
vec2 anisotropic_energy(vec3 wo, float ax, float ay, int column) {
  vec4 c = aniso_energy_coordinates(wo, ax, ay);
  int i, j, k, l;
  float fi, fj, fk, fl;
  aniso_energy_bracket(c.x, kAnisoEnergyMu, i, fi);
  aniso_energy_bracket(c.y, kAnisoEnergyPhi, j, fj);
  aniso_energy_bracket(c.z, kAnisoEnergyR, k, fk);
  aniso_energy_bracket(c.w, kAnisoEnergyS, l, fl);
  vec2 sum = vec2(0.0);
  for (int d = 0; d < 8; ++d) {
    int b = d & 1, e = (d >> 1) & 1, g = (d >> 2) & 1;
    float w = (b != 0 ? fj : 1.0 - fj) * (e != 0 ? fk : 1.0 - fk) * (g != 0 ? fl : 1.0 - fl);
    vec4 t = texelFetch(uAnisotropicEnergy,
                        ivec3(2 * i + column, j + b, (l + g) * kAnisoEnergyR + k + e), 0);
    sum += w * (column == 0 ? (1.0 - fi) * t.xy + fi * t.zw
                            : vec2((1.0 - fi) * t.x + fi * t.y, 0.0));
  }
  return sum;
}

// AnisotropicEnergyTable::averages: (E_ss_avg, E_tot_avg).
vec2 anisotropic_energy_averages(float ax, float ay) {
  vec4 c = aniso_energy_coordinates(vec3(0.0, 0.0, 1.0), ax, ay);
  int k, l;
  float fk, fl;
  aniso_energy_bracket(c.z, kAnisoEnergyR, k, fk);
  aniso_energy_bracket(c.w, kAnisoEnergyS, l, fl);
  int slice = kAnisoEnergyR * kAnisoEnergyS;
  vec4 t0 = texelFetch(uAnisotropicEnergy, ivec3(k, l, slice), 0);
  vec4 t1 = texelFetch(uAnisotropicEnergy, ivec3(k, l + 1, slice), 0);
  return (1.0 - fl) * ((1.0 - fk) * t0.zx + fk * t0.wy) + fl * ((1.0 - fk) * t1.zx + fk * t1.wy);
}
#endif

// AnisotropicEnergyTable::broadened_alphas: min(beta alpha, 1), beta(alpha_x / alpha_y)
// 1.5 up to 4.4, then 1.5 - 0.87 ln(rho / 4.4), at least 0.5.
vec2 aniso_broadened_alphas(float ax, float ay) {
  float rho = max(ax, ay) / max(min(ax, ay), 1e-6);
  float beta = max(1.5 - 0.87 * log(max(rho / 4.4, 1.0)), 0.5);
  return min(beta * vec2(ax, ay), vec2(1.0));
}

// pbrkit::dielectric_f0: min(((ior - 1) / (ior + 1))^2 specularColor, 1); 0.04 exactly for
// ior 1.5.
vec3 dielectric_f0(float ior, vec3 specular_color) {
  float r = (ior - 1.0) / (ior + 1.0);
  float r2 = ior == 1.5 ? 0.04 : r * r;
  return min(r2 * specular_color, vec3(1.0));
}

// pbrkit::BaseLayer: the base layer's inputs after textures.
struct BaseLayer {
  vec3 base_color;
  float metallic;
  float roughness;
  float ior;             // KHR_materials_ior
  float specular;        // KHR_materials_specular
  vec3 specular_color;   // KHR_materials_specular
  float anisotropy;      // KHR_materials_anisotropy strength, along the local +X
  float iridescence;     // KHR_materials_iridescence
  float iridescence_ior;
  float iridescence_thickness;  // nm
};

// BaseLayer{base_color, metallic, roughness} with every extension at its default.
BaseLayer base_layer(vec3 base_color, float metallic, float roughness) {
  return BaseLayer(base_color, metallic, roughness, 1.5, 1.0, vec3(1.0), 0.0, 0.0, 1.3, 0.0);
}

// pbrkit::Brdf (with BoundBrdf's wo-independent state).
struct Brdf {
  vec3 base_color;
  float metallic;
  float roughness;
  float alpha;
  float alpha_x;
  float alpha_y;
  vec3 F0;    // mix(s F0_d, baseColor, metallic)
  vec3 F0_d;  // the dielectric's F0 (ior, specular colour)
  float F90_d;  // the dielectric's F90: 1, or 0 for ior 1 (no interface)
  float table_roughness;  // the albedo tables' roughness: sqrt(sqrt(alpha_x alpha_y))
  float spec_weight;
  float iridescence;
  float film_ior;
  float film_thickness;
  bool reference;  // the model: geometry == GEOMETRY_REFERENCE
  int geometry;
  bool multiscatter;
  int fresnel;
  float E_avg;
  vec3 Fms;     // the whole specular's Fms
  vec3 Fms_d;   // reference: the dielectric's (weighted)
  vec3 Es_avg;  // classic: per channel; reference: the dielectric's
  // BoundBrdf's state at wo (brdf_at), with compensation: E(mu_o), the reference diffuse
  // lobe's factor at wo, classic's Es(mu_o).
  float E_o;
  float diffuse_o;
  vec3 Es_o;
  vec2 ab_o;  // the table's (A, B) at mu_o
  // The anisotropic compensation (reference, anisotropic, compensated; Brdf's aniso_table_):
  // the broadened lobe's alphas, 1 / (pi (1 - E_tot_avg)); at wo (brdf_at) h(wo),
  // 1 - E_tot(wo), Smith's Lambda at the broadened alphas, and E_ss(wo), the lobe's albedo
  // (the environment light's multiple scattering is Fms (1 - E_ss(wo))).
  bool aniso_ms;
  float bx;
  float by;
  float aniso_rest_norm;
  float h_o;
  float rest_o;
  float lambda_b_o;
  float E_ss_o;
};

// Brdf::Brdf. `table` is the EnergyTable of `geometry` (the direct-lighting G); the model
// is `reference` for GEOMETRY_REFERENCE, `classic` otherwise.
Brdf make_brdf(BaseLayer layer, int geometry, bool multiscatter, int fresnel, sampler2D table) {
  Brdf b;
  b.base_color = clamp(layer.base_color, 0.0, 1.0);
  b.metallic = saturate(layer.metallic);
  b.roughness = clamp(layer.roughness, kMinRoughness, 1.0);
  b.alpha = b.roughness * b.roughness;
  // ior 0: KHR_materials_ior's F0 = 1 mode; other values below 1 count as 1.
  b.F0_d = dielectric_f0(layer.ior == 0.0 ? 0.0 : max(layer.ior, 1.0),
                         max(layer.specular_color, 0.0));
  b.F90_d = layer.ior > 1.0 || layer.ior == 0.0 ? 1.0 : 0.0;
  b.spec_weight = saturate(layer.specular);
  b.iridescence = saturate(layer.iridescence);
  b.film_ior = max(layer.iridescence_ior, 1.0);
  b.film_thickness = max(layer.iridescence_thickness, 0.0);
  b.reference = geometry == GEOMETRY_REFERENCE;
  b.geometry = geometry;
  b.multiscatter = multiscatter;
  b.fresnel = fresnel;
  // KHR_materials_anisotropy: alpha_t = mix(alpha, 1, anisotropy^2), alpha_b = alpha.
  float aniso = saturate(layer.anisotropy);
  b.alpha_x = mix(b.alpha, 1.0, aniso * aniso);
  b.alpha_y = b.alpha;
  b.table_roughness = aniso > 0.0 ? sqrt(sqrt(b.alpha_x * b.alpha_y)) : b.roughness;
  // F0 = mix(0.04, baseColor, metallic) (MODEL.md), the 0.04 from ior, specular colour, weight.
  b.F0 = mix(b.spec_weight * b.F0_d, b.base_color, b.metallic);
  b.E_avg = 1.0;
  b.Fms = vec3(0.0);
  b.Fms_d = vec3(0.0);
  b.Es_avg = vec3(0.0);
  b.E_o = 0.0;
  b.diffuse_o = 1.0;
  b.Es_o = vec3(0.0);
  b.ab_o = vec2(0.0);
  b.aniso_ms = false;
  b.bx = 1.0;
  b.by = 1.0;
  b.aniso_rest_norm = 0.0;
  b.h_o = 0.0;
  b.rest_o = 0.0;
  b.lambda_b_o = 0.0;
  b.E_ss_o = 1.0;
  if (multiscatter) {
    vec2 ab_avg = energy_AB_avg(table, b.table_roughness);
    b.E_avg = ab_avg.x + ab_avg.y;
    if (b.reference) {
      b.Fms_d = b.spec_weight * b.F90_d * multiscatter_fresnel(b.F0_d, b.E_avg);
      b.Fms = (1.0 - b.metallic) * b.Fms_d + b.metallic * multiscatter_fresnel(b.base_color, b.E_avg);
      b.Es_avg = b.spec_weight * (b.F0_d * ab_avg.x + b.F90_d * ab_avg.y) + b.Fms_d * (1.0 - b.E_avg);
    } else {
      b.Fms = multiscatter_fresnel(b.F0, b.E_avg);
      b.Es_avg = b.F0 * ab_avg.x + ab_avg.y + b.Fms * (1.0 - b.E_avg);
    }
#ifdef BINDING_ANISOTROPIC_ENERGY
    if (aniso > 0.0 && b.reference) {
      // The anisotropic lobe's own compensation; Fms and the diffuse weight stay the
      // isotropic tables'.
      b.aniso_ms = true;
      vec2 bb = aniso_broadened_alphas(b.alpha_x, b.alpha_y);
      b.bx = bb.x;
      b.by = bb.y;
      float E_tot_avg = anisotropic_energy_averages(b.alpha_x, b.alpha_y).y;
      b.aniso_rest_norm = 1.0 / (kPi * max(1.0 - E_tot_avg, 1e-6));
    }
#endif
  }
  return b;
}

// Schlick's weight (1 - c)^5, or UE4's spherical-Gaussian fit of it (FRESNEL_SG).
float fresnel_weight(Brdf b, float c) {
  if (b.fresnel == FRESNEL_SG) return exp2((-5.55473 * c - 6.98316) * c);
  float m = 1.0 - c, m2 = m * m;
  return m2 * m2 * m;
}

vec3 brdf_fresnel(Brdf b, float cosTheta) {
  return b.fresnel == FRESNEL_SG ? fresnelSchlickSG(cosTheta, b.F0) : fresnelSchlick(cosTheta, b.F0);
}

// Brdf::dielectric_albedo: the dielectric's specular with F90 = 1, weighted.
vec3 brdf_dielectric_albedo(Brdf b, vec2 ab) {
  return b.spec_weight * (b.F0_d * ab.x + b.F90_d * ab.y);
}

// Brdf::specular_albedo: (1 - m) s (F0_d A + B) + m (baseColor A + B) for reference,
// F0 A + B for classic (+ Fms (1 - E) with compensation).
vec3 brdf_specular_albedo(Brdf b, sampler2D table, float mu) {
  vec2 ab = energy_AB(table, mu, b.table_roughness);
  float b_weight = b.reference ? (1.0 - b.metallic) * b.spec_weight * b.F90_d + b.metallic : 1.0;
  vec3 Es = b.F0 * ab.x + ab.y * b_weight;
  if (b.multiscatter) Es += b.Fms * (1.0 - (ab.x + ab.y));
  return Es;
}

// Brdf::at / BoundBrdf's constructor: what the compensation needs at wo, computed once per
// shading point (every light's brdf_eval reuses it; on llvmpipe each table lookup is four
// fetches). Every Brdf must be bound before brdf_eval.
Brdf brdf_at(Brdf b, sampler2D table, vec3 wo) {
  if (!b.multiscatter) return b;
  vec2 ab_o = energy_AB(table, max(wo.z, 0.0), b.table_roughness);
  b.ab_o = ab_o;
  b.E_o = ab_o.x + ab_o.y;
  if (b.reference) {
    // The diffuse lobe under the dielectric's specular (single + multiple scattering).
    vec3 Es_o = brdf_dielectric_albedo(b, ab_o) + b.Fms_d * (1.0 - b.E_o);
    b.diffuse_o = (1.0 - max3(Es_o)) / max(1.0 - max3(b.Es_avg), 1e-6);
  } else {
    b.Es_o = brdf_specular_albedo(b, table, wo.z);
  }
#ifdef BINDING_ANISOTROPIC_ENERGY
  if (b.aniso_ms && wo.z > 0.0) {
    vec2 e = anisotropic_energy(wo, b.alpha_x, b.alpha_y, 0);
    b.h_o = e.x;
    b.rest_o = 1.0 - e.y;
    b.lambda_b_o = SmithLambdaGGXAniso(wo, b.bx, b.by);
    b.E_ss_o = anisotropic_energy(wo, b.alpha_x, b.alpha_y, 1).x;
  }
#endif
  return b;
}

// BoundBrdf::specular_fresnel: the specular lobe's Fresnel at v.h and, in diffuse_weight,
// the diffuse lobe's Fresnel weight without compensation.
vec3 brdf_specular_fresnel(Brdf b, float WOdotH, out vec3 diffuse_weight) {
  float c = max(WOdotH, 0.0);
  float w5 = fresnel_weight(b, c);
  if (!b.reference) {
    vec3 F = b.F0 + (1.0 - b.F0) * w5;
#ifdef BRDF_IRIDESCENCE
    if (b.iridescence > 0.0)
      F = mix(F, iridescence_fresnel(c, b.film_ior, b.film_thickness, b.F0), b.iridescence);
#endif
    diffuse_weight = 1.0 - F;
    return F;
  }
  // glTF Appendix B: the dielectric's Fresnel (F90 = 1, weighted by specular) and the
  // metal's, mixed by metallic; the diffuse sits under the dielectric's only.
  vec3 Fd = b.F0_d + (b.F90_d - b.F0_d) * w5;
  vec3 Fm = b.base_color + (1.0 - b.base_color) * w5;
#ifdef BRDF_IRIDESCENCE
  if (b.iridescence > 0.0) {
    Fd = mix(Fd, iridescence_fresnel(c, b.film_ior, b.film_thickness, b.F0_d), b.iridescence);
    Fm = mix(Fm, iridescence_fresnel(c, b.film_ior, b.film_thickness, b.base_color),
             b.iridescence);
  }
#endif
  Fd *= b.spec_weight;
  diffuse_weight = vec3(1.0 - max3(Fd));
  return (1.0 - b.metallic) * Fd + b.metallic * Fm;
}

// BoundBrdf::eval_diffuse_and_ms.
vec3 brdf_eval_diffuse_and_ms(Brdf b, sampler2D table, vec3 wo, vec3 wi, vec3 diffuse_weight) {
  vec3 lambert = (1.0 - b.metallic) * b.base_color * kInvPi;
  if (!b.multiscatter) return diffuse_weight * lambert;
  vec2 ab_i = energy_AB(table, wi.z, b.table_roughness);
  float E_i = ab_i.x + ab_i.y;
  vec3 diffuse;
  if (b.reference) {
    // Weighted reciprocally by what the dielectric's specular (single + multiple) does not
    // reflect: (1 - max3(Es(o)))(1 - max3(Es(i))) / (1 - max3(Es_avg)).
    vec3 Es_i = brdf_dielectric_albedo(b, ab_i) + b.Fms_d * (1.0 - E_i);
    diffuse = lambert * (b.diffuse_o * (1.0 - max3(Es_i)));
  } else {
    vec3 Es_i = brdf_specular_albedo(b, table, wi.z);
    diffuse = lambert * (1.0 - b.Es_o) * (1.0 - Es_i) / max(1.0 - b.Es_avg, vec3(1e-6));
  }
#ifdef BINDING_ANISOTROPIC_ENERGY
  if (b.aniso_ms) {
    // Anisotropic: h(wo) h(wi) f_b(wo, wi), the single-scattering lobe at the broadened
    // alphas scaled symmetrically, plus Kulla & Conty 2017's lobe on what is left,
    // (1 - E_tot(wo))(1 - E_tot(wi)) / (pi (1 - E_tot_avg)) (core/anisotropic_energy.h).
    vec2 e = anisotropic_energy(wi, b.alpha_x, b.alpha_y, 0);
    vec3 h = normalize(wo + wi);
    float G2 = 1.0 / (1.0 + b.lambda_b_o + SmithLambdaGGXAniso(wi, b.bx, b.by));
    float f_b = DistributionGGXAniso(h, b.bx, b.by) * G2 / (4.0 * wo.z * wi.z);
    return diffuse + b.Fms * (b.h_o * e.x * f_b + b.rest_o * (1.0 - e.y) * b.aniso_rest_norm);
  }
#endif
  // Kulla & Conty 2017: f_ms = Fms (1 - E(mu_o))(1 - E(mu_i)) / (pi (1 - E_avg)).
  vec3 ms = b.Fms * ((1.0 - b.E_o) * (1.0 - E_i) / (kPi * max(1.0 - b.E_avg, 1e-6)));
  return diffuse + ms;
}

// BoundBrdf::eval: f(wo, wi) without the cosine; zero unless both are above the surface.
vec3 brdf_eval(Brdf b, sampler2D table, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
  vec3 h = normalize(wo + wi);
  float WOdotH = dot(wo, h);
  float D = DistributionGGXAniso(h, b.alpha_x, b.alpha_y);
  vec3 diffuse_weight;
  vec3 F = brdf_specular_fresnel(b, WOdotH, diffuse_weight);
  float G;
  if (b.geometry == GEOMETRY_REFERENCE) {
    // Height-correlated Smith (Heitz 2014, eq. 99).
    G = 1.0 / (1.0 + SmithLambdaGGXAniso(wo, b.alpha_x, b.alpha_y) +
               SmithLambdaGGXAniso(wi, b.alpha_x, b.alpha_y));
  } else {
    // LearnOpenGL's GeometrySmith: Schlick-GGX with k_direct.
    G = GeometrySchlickGGX(max(wo.z, 0.0), k_direct(b.roughness)) *
        GeometrySchlickGGX(wi.z, k_direct(b.roughness));
  }
  return D * G * F / (4.0 * wo.z * wi.z) + brdf_eval_diffuse_and_ms(b, table, wo, wi, diffuse_weight);
}

// pbrkit::Frame's constructor (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
mat3 frame_from_normal(vec3 n) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float bb = n.x * n.y * a;
  vec3 t = vec3(1.0 + s * n.x * n.x * a, s * bb, -s * n.x);
  vec3 b = vec3(bb, s + n.y * n.y * a, -n.y);
  return mat3(t, b, n);
}
// World -> local: transpose(frame) * v = (v.t, v.b, v.n).
vec3 to_local(mat3 frame, vec3 v) { return v * frame; }
