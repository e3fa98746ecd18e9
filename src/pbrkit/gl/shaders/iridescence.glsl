// Thin-film Fresnel (Belcour & Barla 2017, KHR_materials_iridescence) in GLSL, mirroring
// src/pbrkit/core/iridescence.cpp line by line (same names, same order of operations; the
// formulas and their derivation are in that file's header). tests/gl/iridescence_glsl_test.cpp
// checks iridescence_fresnel below against pbrkit::iridescence_fresnel to 1e-4 relative.
#include "math.glsl"

// The film's ior fades to the outside's (1) over this thickness (pbrkit's kThinFilmFadeNm).
const float kThinFilmFadeNm = 0.03;
// The largest base F0 turned into an ior.
const float kThinFilmMaxF0 = 0.9999;
// Fourier orders m summed (pbrkit's kThinFilmOrders).
const int kThinFilmOrders = 3;

// CIE 1931 XYZ to linear Rec.709 (D65), column-major.
const mat3 kThinFilmXyzToRec709 = mat3(3.2404542, -0.9692660, 0.0556434,   //
                                       -1.5371385, 1.8760108, -0.2040259,  //
                                       -0.4985314, 0.0415560, 1.0572252);

// n = (1 + sqrt(F0)) / (1 - sqrt(F0)).
float thin_film_ior_from_F0(float F0) {
  float sqrtF0 = sqrt(clamp(F0, 0.0, kThinFilmMaxF0));
  return (1.0 + sqrtF0) / (1.0 - sqrtF0);
}

// Exact Fresnel amplitude, s polarisation: (n1 c1 - n2 c2) / (n1 c1 + n2 c2).
float thin_film_rs(float n1, float n2, float c1, float c2) {
  float num = n1 * c1 - n2 * c2;
  float den = n1 * c1 + n2 * c2;
  return den > 0.0 ? num / den : 0.0;
}

// p polarisation: (n2 c1 - n1 c2) / (n2 c1 + n1 c2).
float thin_film_rp(float n1, float n2, float c1, float c2) {
  float num = n2 * c1 - n1 * c2;
  float den = n2 * c1 + n1 * c2;
  return den > 0.0 ? num / den : 0.0;
}

// Spectral integral of cos(2 pi OPD / lambda + shift) against the CIE 1931 matching
// functions (Belcour & Barla's Gaussian fits in Fourier space), Rec.709, white-normalised.
vec3 thin_film_sensitivity(float opd_nm, vec3 shift) {
  float phase = 2.0 * kPi * opd_nm * 1.0e-9;
  vec3 val = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13);
  vec3 pos = vec3(1.6810e+06, 1.7953e+06, 2.2084e+06);
  vec3 var = vec3(4.3278e+09, 9.3046e+09, 6.6121e+09);
  vec3 amplitude = val * sqrt(2.0 * kPi * var);
  vec3 xyz = amplitude * cos(pos * phase + shift) * exp(-(phase * phase) * var);
  float amplitude_x2 = 9.7470e-14 * sqrt(2.0 * kPi * 4.5282e+09);
  xyz.x += amplitude_x2 * cos(2.2399e+06 * phase + shift.x) * exp(-4.5282e+09 * (phase * phase));
  xyz /= 1.0685e-7;
  // The same at OPD = 0, shift = 0: cos = exp = 1.
  vec3 white_xyz = amplitude;
  white_xyz.x += amplitude_x2;
  white_xyz /= 1.0685e-7;
  return (kThinFilmXyzToRec709 * xyz) / (kThinFilmXyzToRec709 * white_xyz);
}

// Airy's sum in Fourier form for one polarisation.
vec3 thin_film_airy(float r12, vec3 r23, float opd_nm) {
  float R12 = r12 * r12;
  vec3 R23 = r23 * r23;
  float T121 = 1.0 - R12;
  float phi21 = r12 > 0.0 ? kPi : 0.0;
  vec3 phi23 = vec3(0.0);
  for (int i = 0; i < 3; ++i) phi23[i] = r23[i] < 0.0 ? kPi : 0.0;
  vec3 phi = vec3(phi21) + phi23;
  vec3 R123 = R12 * R23;
  vec3 r123 = sqrt(R123);
  vec3 Rs = (T121 * T121) * R23 / max(1.0 - R123, vec3(1e-7));
  vec3 C0 = R12 + Rs;
  vec3 I = C0;
  vec3 Cm = Rs - T121;
  for (int m = 1; m <= kThinFilmOrders; ++m) {
    Cm *= r123;
    vec3 Sm = 2.0 * thin_film_sensitivity(float(m) * opd_nm, float(m) * phi);
    I += Cm * Sm;
  }
  return I;
}

vec3 iridescence_fresnel(float cos_theta, float film_ior, float thickness_nm, vec3 base_F0) {
  float cos1 = clamp(cos_theta, 0.0, 1.0);
  float d = max(thickness_nm, 0.0);
  float t = min(d / kThinFilmFadeNm, 1.0);
  float fade = t * t * (3.0 - 2.0 * t);  // smoothstep(0, kThinFilmFadeNm, d)
  float eta2 = 1.0 + (film_ior - 1.0) * fade;
  float cos2Sq = ((eta2 - 1.0) * (eta2 + 1.0) + cos1 * cos1) / (eta2 * eta2);
  if (cos2Sq < 0.0) return vec3(1.0);
  float cos2 = sqrt(cos2Sq);
  float r12s = thin_film_rs(1.0, eta2, cos1, cos2);
  float r12p = thin_film_rp(1.0, eta2, cos1, cos2);
  vec3 r23s = vec3(0.0), r23p = vec3(0.0);
  for (int i = 0; i < 3; ++i) {
    float n3 = thin_film_ior_from_F0(base_F0[i]);
    float cos3 = sqrt(max((n3 - 1.0) * (n3 + 1.0) + cos1 * cos1, 0.0)) / n3;
    r23s[i] = thin_film_rs(eta2, n3, cos2, cos3);
    r23p[i] = thin_film_rp(eta2, n3, cos2, cos3);
  }
  float opd_nm = 2.0 * eta2 * d * cos2;
  vec3 I = 0.5 * (thin_film_airy(r12s, r23s, opd_nm) + thin_film_airy(r12p, r23p, opd_nm));
  return clamp(I, 0.0, 1.0);
}
