// PLACEHOLDER (replaced by branch iridescence, with the same signature): mirrors the
// placeholder include/pbrkit/core/iridescence.h, Schlick's Fresnel with base_F0. The real
// one is Belcour & Barla 2017's thin-film Fresnel (KHR_materials_iridescence).
vec3 iridescence_fresnel(float cos_theta, float film_ior, float thickness_nm, vec3 base_F0) {
  float m = 1.0 - cos_theta;
  return base_F0 + (1.0 - base_F0) * (m * m * m * m * m);
}
