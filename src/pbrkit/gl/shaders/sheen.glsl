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
// A table of the cell-corner layout whose rows start at `row0`.
float sheen_table_corners(sampler2D sheen_lut, int row0, float mu, float roughness) {
  float x = sqrt(clamp(mu, 0.0, 1.0)) * float(kSheenMuSize - 1);
  float r = clamp(roughness, kMinSheenRoughness, 1.0);
  float y = sqrt((r - kMinSheenRoughness) / (1.0 - kMinSheenRoughness)) * float(kSheenRoughnessSize - 1);
  int i0 = min(int(x), kSheenMuSize - 2);
  int j0 = min(int(y), kSheenRoughnessSize - 2);
  float fx = x - float(i0), fy = y - float(j0);
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

// SheenTable::lobe_mean(mu, roughness): the mean of the cosine-weighted Charlie lobe as
// (along t, along n), t being v's direction in the tangent plane, on E's nodes, in rows
// kSheenRoughnessSize.. of the same texture (gl/energy_texture.cpp): texel (i, j) holds the
// nodes (i, j) and (i + 1, j), so two fetches, interpolated as sheen_E.
vec2 sheen_lobe_mean(sampler2D sheen_lut, float mu, float roughness) {
  float x = sqrt(clamp(mu, 0.0, 1.0)) * float(kSheenMuSize - 1);
  float r = clamp(roughness, kMinSheenRoughness, 1.0);
  float y = sqrt((r - kMinSheenRoughness) / (1.0 - kMinSheenRoughness)) * float(kSheenRoughnessSize - 1);
  int i0 = min(int(x), kSheenMuSize - 2);
  int j0 = min(int(y), kSheenRoughnessSize - 2);
  float fx = x - float(i0), fy = y - float(j0);
  vec4 c0 = texelFetch(sheen_lut, ivec2(i0, kSheenRoughnessSize + j0), 0);
  vec4 c1 = texelFetch(sheen_lut, ivec2(i0, kSheenRoughnessSize + j0 + 1), 0);
  return mix(mix(c0.xy, c0.zw, fx), mix(c1.xy, c1.zw, fx), fy);
}

// core/sheen.h's sheen_lobe_direction: where the sheen lobe gathers light, the lobe's mean
// in the frame (t, n), normalised. At grazing view the Charlie lobe back-scatters (its half
// vectors lie near the surface, so l comes back towards v): the mean lies on the viewer's
// side of n (e.g. 9-15 degrees from n at roughness 1, 23-38 at 0.3), while the mirror
// direction R lies on the other side.
vec3 sheen_lobe_direction(sampler2D sheen_lut, vec3 n, vec3 v, float roughness) {
  float mu = dot(n, v);
  vec3 t = v - n * mu;
  float tl = length(t);
  if (!(tl > 1e-6)) return n;
  vec2 m = sheen_lobe_mean(sheen_lut, mu, roughness);
  return normalize(m.y * n + (m.x / tl) * t);
}
