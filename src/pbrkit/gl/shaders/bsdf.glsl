// The layered material of src/pbrkit/core/bsdf.h in GLSL, mirrored line by line:
// KHR_materials_clearcoat's coat over KHR_materials_sheen's sheen over the base (brdf.glsl),
//
//   f = f_coat + A_coat (f_sheen + A_sheen f_base)
//   A_coat  = min(1 - clearcoat F_c(n_c.v), 1 - clearcoat F_c(n_c.l))
//   A_sheen = min(1 - max3(sheenColor) E_sheen(n.v), 1 - max3(sheenColor) E_sheen(n.l))
//
// (bsdf.h's header says why). tests/gl/bsdf_glsl_test.cpp checks bsdf_eval against
// pbrkit::Bsdf::eval. Directions in the base's local frame (n = +Z, +X the anisotropy).
#include "brdf.glsl"
#include "sheen.glsl"

// pbrkit::Bsdf: the base, the coat (a black dielectric Brdf, ior 1.5, reference G, no
// compensation, in the coat normal's frame) and the sheen.
struct Bsdf {
  Brdf base;
  bool has_coat;
  Brdf coat;
  float coat_weight;
  mat3 coat_frame;
  vec3 sheen_color;
  float sheen_roughness;
  float sheen_max;
  // BoundBsdf's state at wo (bsdf_at): 1 - max3(sheenColor) E_sheen(n.v), 1 - clearcoat F_c(n_c.v).
  float sheen_o;
  float coat_o;
};

// The coat's Fresnel: Schlick with F0 = 0.04, F90 = 1.
float coat_fresnel(float cos_theta) {
  float m = 1.0 - saturate(cos_theta), m2 = m * m;
  return 0.04 + 0.96 * (m2 * m2 * m);
}

// Bsdf::Bsdf. coat_normal in the base's local frame; `coat_table` the reference EnergyTable
// (unused: the coat is not compensated, but make_brdf takes one).
Bsdf make_bsdf(Brdf base, float coat_weight, float coat_roughness, vec3 coat_normal,
               vec3 sheen_color, float sheen_roughness, sampler2D coat_table) {
  Bsdf s;
  s.base = base;
  s.has_coat = coat_weight > 0.0;
  s.coat = make_brdf(base_layer(vec3(0.0), 0.0, coat_roughness), GEOMETRY_REFERENCE, false,
                     FRESNEL_SCHLICK, coat_table);
  s.coat_weight = saturate(coat_weight);
  s.coat_frame = frame_from_normal(dot(coat_normal, coat_normal) > 0.0 ? normalize(coat_normal)
                                                                       : vec3(0.0, 0.0, 1.0));
  s.sheen_color = clamp(sheen_color, 0.0, 1.0);
  s.sheen_max = max3(s.sheen_color);
  s.sheen_roughness = clamp(sheen_roughness, kMinSheenRoughness, 1.0);
  s.sheen_o = 1.0;
  s.coat_o = 1.0;
  return s;
}

// BoundBsdf's constructor: the layers' attenuations at wo, once per shading point. The base
// must already be bound (brdf_at).
Bsdf bsdf_at(Bsdf s, sampler2D sheen_lut, vec3 wo) {
  if (s.sheen_max > 0.0) s.sheen_o = 1.0 - s.sheen_max * sheen_E(sheen_lut, wo.z, s.sheen_roughness);
  if (s.has_coat) s.coat_o = 1.0 - s.coat_weight * coat_fresnel(abs(to_local(s.coat_frame, wo).z));
  return s;
}

// BoundBsdf::eval: f(wo, wi) without the cosine. `table` is the base's EnergyTable.
vec3 bsdf_eval(Bsdf s, sampler2D table, sampler2D coat_table, sampler2D sheen_lut, vec3 wo,
               vec3 wi) {
  vec3 f = brdf_eval(s.base, table, wo, wi);
  if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
  if (s.sheen_max > 0.0) {
    vec3 h = normalize(wo + wi);
    float D = D_Charlie(h.z, s.sheen_roughness);
    vec3 f_sheen = s.sheen_color * (D * V_Charlie(wo.z, wi.z, s.sheen_roughness));
    float sheen_i = 1.0 - s.sheen_max * sheen_E(sheen_lut, wi.z, s.sheen_roughness);
    f = f_sheen + min(s.sheen_o, sheen_i) * f;
  }
  if (s.has_coat) {
    vec3 wo_c = to_local(s.coat_frame, wo);
    vec3 wi_c = to_local(s.coat_frame, wi);
    vec3 f_coat = s.coat_weight * brdf_eval(s.coat, coat_table, wo_c, wi_c);
    float coat_i = 1.0 - s.coat_weight * coat_fresnel(abs(wi_c.z));
    f = f_coat + min(s.coat_o, coat_i) * f;
  }
  return f;
}
