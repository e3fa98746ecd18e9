// KHR_materials_sheen's Charlie sheen (Estevez & Kulla 2017) in GLSL, mirroring
// src/pbrkit/core/sheen.cpp line by line: the README's D and Charlie visibility (alphaG =
// sheenRoughness as the README writes it, clamped to >= 0.07) and SheenTable::E read from
// the table uploaded by gl/energy_texture.cpp. tests/gl/bsdf_glsl_test.cpp compares the
// layered evaluation with the C++.
const float kMinSheenRoughness = 0.07;  // pbrkit::kMinSheenRoughness

// DistributionCharlie: (2 + 1/r) sin(theta_h)^(1/r) / (2 pi).
float D_Charlie(float NdotH, float roughness) {
  float r = max(roughness, kMinSheenRoughness);
  float inv = 1.0 / r;
  float sin2 = max(1.0 - NdotH * NdotH, 0.0);
  return (2.0 + inv) * pow(sin2, 0.5 * inv) / (2.0 * kPi);
}

// The README's fit of the Charlie Lambda, l(x, alphaG).
float charlie_l(float x, float alphaG) {
  float one_minus_alpha_sq = (1.0 - alphaG) * (1.0 - alphaG);
  float a = mix(21.5473, 25.3245, one_minus_alpha_sq);
  float b = mix(3.82987, 3.32435, one_minus_alpha_sq);
  float c = mix(0.19823, 0.16801, one_minus_alpha_sq);
  float d = mix(-1.97760, -1.27393, one_minus_alpha_sq);
  float e = mix(-4.32054, -4.85967, one_minus_alpha_sq);
  return a / (1.0 + b * pow(x, c)) + d * x + e;
}

// SheenLambda.
float charlie_lambda(float cos_theta, float alphaG) {
  float c = min(abs(cos_theta), 1.0);
  return c < 0.5 ? exp(charlie_l(c, alphaG)) : exp(2.0 * charlie_l(0.5, alphaG) - charlie_l(1.0 - c, alphaG));
}

// VisibilityCharlie (includes 1 / (4 n.v n.l)).
float V_Charlie(float NdotV, float NdotL, float roughness) {
  if (NdotV <= 0.0 || NdotL <= 0.0) return 0.0;
  float alphaG = clamp(roughness, kMinSheenRoughness, 1.0);
  return 1.0 / ((1.0 + charlie_lambda(NdotV, alphaG) + charlie_lambda(NdotL, alphaG)) *
                (4.0 * NdotV * NdotL));
}

// SheenTable::E(mu, roughness), interpolated by hand exactly as the C++ table does: nodes
// at mu_i = (i / 63)^2 (x) and r_j = 0.07 + 0.93 (j / 47)^2 (y); texel (i, j) holds the
// cell's corners (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1), so one fetch per lookup.
const int kSheenMuSize = 64;
const int kSheenRoughnessSize = 48;
// The table cell holding (mu, roughness): its lower node (i0, j0) in .xy (as floats) and
// the position within it in .zw, on the node spacing SheenTable uses.
vec4 sheen_table_cell(float mu, float roughness) {
  float x = sqrt(clamp(mu, 0.0, 1.0)) * float(kSheenMuSize - 1);
  float r = clamp(roughness, kMinSheenRoughness, 1.0);
  float y = sqrt((r - kMinSheenRoughness) / (1.0 - kMinSheenRoughness)) * float(kSheenRoughnessSize - 1);
  vec2 n0 = vec2(min(floor(x), float(kSheenMuSize - 2)), min(floor(y), float(kSheenRoughnessSize - 2)));
  return vec4(n0, x - n0.x, y - n0.y);
}
// A table of the cell-corner layout whose rows start at `row0`.
float sheen_table_corners(sampler2D sheen_lut, int row0, float mu, float roughness) {
  vec4 cell = sheen_table_cell(mu, roughness);
  int i0 = int(cell.x), j0 = int(cell.y);
  float fx = cell.z, fy = cell.w;
  vec4 c = texelFetch(sheen_lut, ivec2(i0, row0 + j0), 0);
  return mix(mix(c.x, c.y, fx), mix(c.z, c.w, fx), fy);
}
float sheen_E(sampler2D sheen_lut, float mu, float roughness) {
  return sheen_table_corners(sheen_lut, 0, mu, roughness);
}

// SheenTable::E_max_avg(mu, roughness): the cosine-weighted average over l of
// max(E(n.v), E(n.l)), so that 1 - max3(sheenColor) E_max_avg(n.v) scales the base's
// image-based light as the layered Bsdf's min(1 - c E(n.v), 1 - c E(n.l)) scales it under a
// uniform environment (rows 2 kSheenRoughnessSize.. of the texture).
float sheen_E_max_avg(sampler2D sheen_lut, float mu, float roughness) {
  return sheen_table_corners(sheen_lut, 2 * kSheenRoughnessSize, mu, roughness);
}

// A table of the node-pair layout whose rows start at `row0`: texel (i, row0 + j) holds two
// values at node (i, j) in .xy and at (i + 1, j) in .zw, so two fetches, interpolated as
// sheen_E.
vec2 sheen_table_pairs(sampler2D sheen_lut, int row0, float mu, float roughness) {
  vec4 cell = sheen_table_cell(mu, roughness);
  int i0 = int(cell.x), j0 = int(cell.y);
  float fx = cell.z, fy = cell.w;
  vec4 c0 = texelFetch(sheen_lut, ivec2(i0, row0 + j0), 0);
  vec4 c1 = texelFetch(sheen_lut, ivec2(i0, row0 + j0 + 1), 0);
  return mix(mix(c0.xy, c0.zw, fx), mix(c1.xy, c1.zw, fx), fy);
}

// ibl/sheen_sh.h's sheen_tangent: v's direction in the tangent plane, or at normal incidence
// (where the lobe is symmetric about n) a fixed perpendicular of n.
vec3 sheen_tangent(vec3 n, vec3 v) {
  vec3 t = v - n * dot(n, v);
  float tl = length(t);
  if (tl > 1e-6) return t / tl;
  return normalize(cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
}

// ibl/sheen_sh.h's sheen_sh_radiance: the environment's order-2 spherical harmonics (`sh`,
// ibl/spherical_harmonics.h's irradiance coefficients, the cosine's A_l = pi, 2 pi / 3, pi / 4
// folded in) averaged over the normalised cosine-weighted Charlie lobe at (n, v):
//   int L(l) D V (n.l) dl / E = sum_lm L_lm <Y_lm>,
// each <Y_lm> a polynomial of degree <= 2 in l, so a combination of the lobe's first and
// second moments (SheenTable::lobe_mean, lobe_second_moments, tabulated in the frame t, n,
// b = n x t and turned into the world's here). Exact for the environment's bands 0-2: the
// mean says where the lobe gathers light (at grazing view on the viewer's side of n: the
// lobe back-scatters), the second moments how widely.
vec3 sheen_sh_radiance(sampler2D sheen_lut, vec3 sh[9], vec3 n, vec3 v, float roughness) {
  float mu = dot(n, v);
  vec3 t = sheen_tangent(n, v);
  vec3 b = cross(n, t);
  vec2 m = sheen_table_pairs(sheen_lut, kSheenRoughnessSize, mu, roughness);
  vec2 q = sheen_table_pairs(sheen_lut, 3 * kSheenRoughnessSize, mu, roughness);
  float tn = sheen_table_corners(sheen_lut, 4 * kSheenRoughnessSize, mu, roughness);
  vec3 mean = m.x * t + m.y * n;
  // The second moments in the world frame (symmetric; M[c][r] is column c, row r).
  mat3 M = q.x * outerProduct(t, t) + q.y * outerProduct(n, n) + (1.0 - q.x - q.y) * outerProduct(b, b) +
           tn * (outerProduct(t, n) + outerProduct(n, t));
  // Radiance coefficients L_lm = sh_lm / A_l, times <Y_lm> (ibl.glsl's basis).
  vec3 band0 = sh[0] * (0.282095 / kPi);
  vec3 band1 = (sh[1] * mean.y + sh[2] * mean.z + sh[3] * mean.x) * (0.488603 * 3.0 / (2.0 * kPi));
  vec3 band2 = (sh[4] * (1.092548 * M[0][1]) + sh[5] * (1.092548 * M[1][2]) +
                sh[6] * (0.315392 * (3.0 * M[2][2] - 1.0)) + sh[7] * (1.092548 * M[0][2]) +
                sh[8] * (0.546274 * (M[0][0] - M[1][1]))) *
               (4.0 / kPi);
  return band0 + band1 + band2;
}
