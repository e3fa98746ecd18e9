// KHR_materials_sheen's Charlie sheen (Estevez & Kulla 2017) in GLSL, mirroring
// include/pbrkit/core/sheen.h. That header is a PLACEHOLDER on this branch (branch
// sheen-bake brings the real one, with a baked E table and Charlie-prefiltered cubes): D
// is the README's, V is Ashikhmin & Premoze's 1 / (4 (n.l + n.v - n.l n.v)) and E a
// constant 0.1. SHEEN_VISIBILITY_README 1 selects the README's Charlie visibility below
// (1 / ((1 + Lambda(v) + Lambda(l)) 4 n.v n.l) with the l(x, alphaG) fit), which the real
// sheen.h's VisibilityCharlie must then match; tests/gl/bsdf_glsl_test.cpp compares
// against the C++ either way.
#ifndef SHEEN_VISIBILITY_README
#define SHEEN_VISIBILITY_README 0
#endif

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

float charlie_lambda(float cos_theta, float alphaG) {
  return abs(cos_theta) < 0.5 ? exp(charlie_l(cos_theta, alphaG))
                              : exp(2.0 * charlie_l(0.5, alphaG) - charlie_l(1.0 - cos_theta, alphaG));
}

// VisibilityCharlie (includes 1 / (4 n.v n.l)).
float V_Charlie(float NdotV, float NdotL, float roughness) {
  if (NdotV <= 0.0 || NdotL <= 0.0) return 0.0;
#if SHEEN_VISIBILITY_README
  float r = max(roughness, kMinSheenRoughness);
  float alphaG = r * r;
  return 1.0 / ((1.0 + charlie_lambda(NdotV, alphaG) + charlie_lambda(NdotL, alphaG)) *
                (4.0 * NdotV * NdotL));
#else
  return 1.0 / (4.0 * (NdotL + NdotV - NdotL * NdotV));
#endif
}

// SheenTable::E(mu, roughness): the sheen's directional albedo, read from `sheen_lut` at
// (mu, roughness) in R. The renderer binds a 1x1 texture holding the placeholder's 0.1
// until the baker's sheen LUT lands (then this must interpolate as the C++ table does,
// as energy_AB does for the EnergyTable).
float sheen_E(sampler2D sheen_lut, float mu, float roughness) {
  return textureLod(sheen_lut, vec2(clamp(mu, 0.0, 1.0), clamp(roughness, 0.0, 1.0)), 0.0).r;
}
