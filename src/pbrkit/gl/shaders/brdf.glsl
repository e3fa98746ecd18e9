// The material model of shared/spec/MODEL.md in GLSL, mirroring src/pbrkit/core/microfacet.cpp
// and src/pbrkit/core/brdf.cpp line by line (same names, same order of operations), so
// the OpenGL renderer and the path tracer evaluate one BRDF. tests/gl/brdf_glsl_test.cpp
// checks Brdf::eval against brdf_eval below to 1e-4 relative.
//
// Directions are in the local shading frame (n = +Z), wo towards the viewer, wi towards
// the light. alpha = roughness^2 (Burley 2012 / Karis 2013).

const float kPi = 3.14159265358979323846;
const float kInvPi = 0.31830988618379067154;
const float kMinRoughness = 0.02;  // pbrkit::kMinRoughness

// pbrkit::GeometryModel
const int GEOMETRY_REFERENCE = 0;       // height-correlated Smith (Heitz 2014, eq. 99)
const int GEOMETRY_CLASSIC_DIRECT = 1;  // Schlick-GGX, k = (roughness + 1)^2 / 8
const int GEOMETRY_CLASSIC_IBL = 2;     // Schlick-GGX, k = alpha / 2
const int FRESNEL_SCHLICK = 0;
const int FRESNEL_SG = 1;  // UE4's spherical-Gaussian Schlick (real-time path only)

float saturate(float x) { return clamp(x, 0.0, 1.0); }

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

// The seeds' GeometrySchlickGGX.
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

// The EnergyTable (core/energy.h) as a 32 x 33 RG32F texture: rows 0..31 hold (A, B) at
// mu = i / 31 (x) and roughness = j / 31 (y); row 32 holds (A_avg, B_avg) at x = j.
// Interpolated by hand exactly as EnergyTable::AB / AB_avg do (no hardware filtering, whose
// fixed-point weights would differ from the C++ table).
const int kEnergyMuSize = 32;
const int kEnergyRoughnessSize = 32;

vec2 energy_AB(sampler2D table, float mu, float roughness) {
  float x = clamp(mu, 0.0, 1.0) * float(kEnergyMuSize - 1);
  float y = clamp(roughness, 0.0, 1.0) * float(kEnergyRoughnessSize - 1);
  int i0 = min(int(x), kEnergyMuSize - 2);
  int j0 = min(int(y), kEnergyRoughnessSize - 2);
  float fx = x - float(i0), fy = y - float(j0);
  vec2 a00 = texelFetch(table, ivec2(i0, j0), 0).xy;
  vec2 a10 = texelFetch(table, ivec2(i0 + 1, j0), 0).xy;
  vec2 a01 = texelFetch(table, ivec2(i0, j0 + 1), 0).xy;
  vec2 a11 = texelFetch(table, ivec2(i0 + 1, j0 + 1), 0).xy;
  return mix(mix(a00, a10, fx), mix(a01, a11, fx), fy);
}

vec2 energy_AB_avg(sampler2D table, float roughness) {
  float y = clamp(roughness, 0.0, 1.0) * float(kEnergyRoughnessSize - 1);
  int j0 = min(int(y), kEnergyRoughnessSize - 2);
  vec2 a0 = texelFetch(table, ivec2(j0, kEnergyRoughnessSize), 0).xy;
  vec2 a1 = texelFetch(table, ivec2(j0 + 1, kEnergyRoughnessSize), 0).xy;
  return mix(a0, a1, y - float(j0));
}

// pbrkit::Brdf.
struct Brdf {
  vec3 base_color;
  float metallic;
  float roughness;
  float alpha;
  vec3 F0;
  int geometry;
  bool multiscatter;
  int fresnel;
  float E_avg;
  vec3 Fms;
  vec3 Es_avg;
};

// Brdf::Brdf. `table` is the EnergyTable of `geometry` (the direct-lighting G).
Brdf make_brdf(vec3 base_color, float metallic, float roughness, int geometry, bool multiscatter,
               int fresnel, sampler2D table) {
  Brdf b;
  b.base_color = clamp(base_color, 0.0, 1.0);
  b.metallic = saturate(metallic);
  b.roughness = clamp(roughness, kMinRoughness, 1.0);
  b.alpha = b.roughness * b.roughness;
  // F0 = mix(0.04, baseColor, metallic) (MODEL.md).
  b.F0 = mix(vec3(0.04), b.base_color, b.metallic);
  b.geometry = geometry;
  b.multiscatter = multiscatter;
  b.fresnel = fresnel;
  b.E_avg = 1.0;
  b.Fms = vec3(0.0);
  b.Es_avg = vec3(0.0);
  if (multiscatter) {
    vec2 ab_avg = energy_AB_avg(table, b.roughness);
    b.E_avg = ab_avg.x + ab_avg.y;
    b.Fms = multiscatter_fresnel(b.F0, b.E_avg);
    b.Es_avg = b.F0 * ab_avg.x + ab_avg.y + b.Fms * (1.0 - b.E_avg);
  }
  return b;
}

vec3 brdf_fresnel(Brdf b, float cosTheta) {
  return b.fresnel == FRESNEL_SG ? fresnelSchlickSG(cosTheta, b.F0) : fresnelSchlick(cosTheta, b.F0);
}

// Brdf::specular_albedo: F0 A + B (+ Fms (1 - E) with compensation).
vec3 brdf_specular_albedo(Brdf b, sampler2D table, float mu) {
  vec2 ab = energy_AB(table, mu, b.roughness);
  vec3 Es = b.F0 * ab.x + ab.y;
  if (b.multiscatter) Es += b.Fms * (1.0 - (ab.x + ab.y));
  return Es;
}

// Cook-Torrance: D G F / (4 (n.l)(n.v)).
vec3 brdf_eval_specular(Brdf b, vec3 wo, vec3 wi) {
  vec3 h = normalize(wo + wi);
  float VdotH = max(dot(wo, h), 0.0);
  vec3 F = brdf_fresnel(b, VdotH);
  float D = DistributionGGX(h, b.alpha);
  float G = GeometryG(b.geometry, wo, wi, b.roughness);
  return D * G * F / (4.0 * wo.z * wi.z);
}

vec3 brdf_eval_diffuse_and_ms(Brdf b, sampler2D table, vec3 wo, vec3 wi) {
  vec3 lambert = (1.0 - b.metallic) * b.base_color * kInvPi;
  if (!b.multiscatter) {
    // kd = (1 - F(v.h)) (1 - metallic) (MODEL.md / LearnOpenGL).
    vec3 h = normalize(wo + wi);
    vec3 F = brdf_fresnel(b, max(dot(wo, h), 0.0));
    return (1.0 - F) * lambert;
  }
  // Diffuse weighted by what the specular lobe (single + multiple) does not reflect.
  vec3 Es_o = brdf_specular_albedo(b, table, wo.z), Es_i = brdf_specular_albedo(b, table, wi.z);
  vec3 diffuse = lambert * (1.0 - Es_o) * (1.0 - Es_i) / max(1.0 - b.Es_avg, vec3(1e-6));
  // Kulla & Conty 2017: f_ms = Fms (1 - E(mu_o))(1 - E(mu_i)) / (pi (1 - E_avg)).
  vec2 ab_o = energy_AB(table, wo.z, b.roughness), ab_i = energy_AB(table, wi.z, b.roughness);
  float E_o = ab_o.x + ab_o.y, E_i = ab_i.x + ab_i.y;
  vec3 ms = b.Fms * ((1.0 - E_o) * (1.0 - E_i) / (kPi * max(1.0 - b.E_avg, 1e-6)));
  return diffuse + ms;
}

// Brdf::eval: f(wo, wi) without the cosine; zero unless both are above the surface.
vec3 brdf_eval(Brdf b, sampler2D table, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
  return brdf_eval_specular(b, wo, wi) + brdf_eval_diffuse_and_ms(b, table, wo, wi);
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
