// Thin-film Fresnel (Belcour & Barla 2017). src/pbrkit/gl/shaders/iridescence.glsl mirrors
// this file line by line (same names, same order of operations); tests/gl/
// iridescence_glsl_test.cpp checks the two agree to 1e-4 relative.
//
// Per polarisation, with signed real amplitudes r12 (outside -> film) and r23 (film -> base),
// the film's amplitude reflectance at one wavelength is Airy's
//   r = r12 + (1 - r12^2) r23 e^{i delta} / (1 + r12 r23 e^{i delta}),
//   delta = 2 pi OPD / lambda,  OPD = 2 n_film d cos(theta_film).
// Expanded as a Fourier series in delta (as Belcour & Barla 2017 do):
//   |r|^2 = C0 + 2 sum_{m >= 1} Cm cos(m (delta + phi)),
//   C0 = R12 + Rs,  Cm = (Rs - T121) r123^m,  Rs = T121^2 R23 / (1 - R12 R23),
//   R12 = r12^2, R23 = r23^2, T121 = 1 - R12, r123 = sqrt(R12 R23), phi = phi21 + phi23,
// where phi21 (phi23) is 0 or pi as the amplitude -r12 (r23) is positive or negative. Each
// cos(m (delta + phi)) integrates against the colour matching functions in closed form
// (section 4) through their Gaussian fits in Fourier space: thin_film_sensitivity.
#include "pbrkit/core/iridescence.h"

#include <algorithm>
#include <cmath>

#include "pbrkit/core/math.h"

namespace pbrkit {
namespace {

// The film's ior fades to the outside's (1) over this thickness, so a film of thickness 0
// is no film (the Khronos glTF sample viewer's smoothstep(0, 0.03, thickness)).
constexpr float kThinFilmFadeNm = 0.03f;
// The largest base F0 turned into an ior: F0 = 1 would be an infinite ior.
constexpr float kThinFilmMaxF0 = 0.9999f;
// Fourier orders m summed (KHR_materials_iridescence sums m = 1, 2).
constexpr int kThinFilmOrders = 3;

// CIE 1931 XYZ to linear Rec.709 (D65), as KHR_materials_iridescence gives it (column-major,
// as GLSL's mat3).
const glm::mat3 kThinFilmXyzToRec709(3.2404542f, -0.9692660f, 0.0556434f,   //
                                     -1.5371385f, 1.8760108f, -0.2040259f,  //
                                     -0.4985314f, 0.0415560f, 1.0572252f);

// The base's ior from its normal-incidence reflectance (the inverse of
// F0 = ((n - 1) / (n + 1))^2 against ior 1): n = (1 + sqrt(F0)) / (1 - sqrt(F0)).
float thin_film_ior_from_F0(float F0) {
  const float sqrtF0 = std::sqrt(std::clamp(F0, 0.0f, kThinFilmMaxF0));
  return (1.0f + sqrtF0) / (1.0f - sqrtF0);
}

// Exact Fresnel amplitude of the s polarisation from ior n1 (cosine c1) into ior n2 (cosine
// c2): (n1 c1 - n2 c2) / (n1 c1 + n2 c2). Both cosines are 0 only where n1 = n2 (no interface).
float thin_film_rs(float n1, float n2, float c1, float c2) {
  const float num = n1 * c1 - n2 * c2;
  const float den = n1 * c1 + n2 * c2;
  return den > 0.0f ? num / den : 0.0f;
}

// The p polarisation, in the same sign convention: (n2 c1 - n1 c2) / (n2 c1 + n1 c2); with it
// r21 = -r12 and t12 t21 = 1 - r12^2, as Airy's sum above assumes.
float thin_film_rp(float n1, float n2, float c1, float c2) {
  const float num = n2 * c1 - n1 * c2;
  const float den = n2 * c1 + n1 * c2;
  return den > 0.0f ? num / den : 0.0f;
}

// The spectral integral of cos(2 pi OPD / lambda + shift) against the CIE 1931 matching
// functions (Belcour & Barla 2017, section 4: each matching function as Gaussians in
// Fourier space, whose transform is a Gaussian times a cosine), in linear Rec.709. The fit's
// constants are those of KHR_materials_iridescence. The result is divided by its value at
// OPD = 0, shift = 0 (Rec.709 of the equal-energy white: (1.205, 0.948, 0.909)), so that the
// DC term and the interference terms share one white: a reflectance constant over the
// spectrum, R, integrates to R in every channel.
glm::vec3 thin_film_sensitivity(float opd_nm, glm::vec3 shift) {
  const float phase = 2.0f * kPi * opd_nm * 1.0e-9f;
  const glm::vec3 val(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
  const glm::vec3 pos(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
  const glm::vec3 var(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
  const glm::vec3 amplitude = val * glm::sqrt(2.0f * kPi * var);
  glm::vec3 xyz = amplitude * glm::cos(pos * phase + shift) * glm::exp(-(phase * phase) * var);
  const float amplitude_x2 = 9.7470e-14f * std::sqrt(2.0f * kPi * 4.5282e+09f);
  xyz.x += amplitude_x2 * std::cos(2.2399e+06f * phase + shift.x) *
           std::exp(-4.5282e+09f * (phase * phase));
  xyz /= 1.0685e-7f;
  // The same at OPD = 0, shift = 0: cos = exp = 1.
  glm::vec3 white_xyz = amplitude;
  white_xyz.x += amplitude_x2;
  white_xyz /= 1.0685e-7f;
  return (kThinFilmXyzToRec709 * xyz) / (kThinFilmXyzToRec709 * white_xyz);
}

// The Fourier-form Airy sum above for one polarisation: r12 the film's amplitude, r23 the
// base's per channel, opd_nm the optical path difference; the RGB reflectance.
glm::vec3 thin_film_airy(float r12, glm::vec3 r23, float opd_nm) {
  const float R12 = r12 * r12;
  const glm::vec3 R23 = r23 * r23;
  const float T121 = 1.0f - R12;
  // Phase of r21 = -r12, and of r23: 0 when positive, pi when negative.
  const float phi21 = r12 > 0.0f ? kPi : 0.0f;
  glm::vec3 phi23(0.0f);
  for (int i = 0; i < 3; ++i) phi23[i] = r23[i] < 0.0f ? kPi : 0.0f;
  const glm::vec3 phi = glm::vec3(phi21) + phi23;
  // Compound terms (R12 R23 < 1 except in the limits the guard keeps finite).
  const glm::vec3 R123 = R12 * R23;
  const glm::vec3 r123 = glm::sqrt(R123);
  const glm::vec3 Rs = (T121 * T121) * R23 / glm::max(1.0f - R123, glm::vec3(1e-7f));
  // m = 0: the incoherent sum; m > 0: the interference terms.
  const glm::vec3 C0 = R12 + Rs;
  glm::vec3 I = C0;
  glm::vec3 Cm = Rs - T121;
  for (int m = 1; m <= kThinFilmOrders; ++m) {
    Cm *= r123;
    const glm::vec3 Sm = 2.0f * thin_film_sensitivity(float(m) * opd_nm, float(m) * phi);
    I += Cm * Sm;
  }
  return I;
}

}  // namespace

glm::vec3 iridescence_fresnel(float cos_theta, float film_ior, float thickness_nm,
                              glm::vec3 base_F0) {
  const float cos1 = std::clamp(cos_theta, 0.0f, 1.0f);
  const float d = std::max(thickness_nm, 0.0f);
  // The film fades into the outside medium as d -> 0 (no film at d = 0).
  const float t = std::min(d / kThinFilmFadeNm, 1.0f);
  const float fade = t * t * (3.0f - 2.0f * t);  // smoothstep(0, kThinFilmFadeNm, d)
  const float eta2 = 1.0f + (film_ior - 1.0f) * fade;
  // Snell's law into the film, sin1 = eta2 sin2, written as
  // cos2^2 = ((eta2 - 1)(eta2 + 1) + cos1^2) / eta2^2, which does not cancel at grazing
  // incidence; a film of ior < 1 can reflect totally.
  const float cos2Sq = ((eta2 - 1.0f) * (eta2 + 1.0f) + cos1 * cos1) / (eta2 * eta2);
  if (cos2Sq < 0.0f) return glm::vec3(1.0f);
  const float cos2 = std::sqrt(cos2Sq);
  // First interface, outside (ior 1) -> film.
  const float r12s = thin_film_rs(1.0f, eta2, cos1, cos2);
  const float r12p = thin_film_rp(1.0f, eta2, cos1, cos2);
  // Second interface, film -> base, per channel (the base's ior >= 1: no total reflection).
  glm::vec3 r23s(0.0f), r23p(0.0f);
  for (int i = 0; i < 3; ++i) {
    const float n3 = thin_film_ior_from_F0(base_F0[i]);
    // sin1 = n3 sin3, in the same form as cos2.
    const float cos3 = std::sqrt(std::max((n3 - 1.0f) * (n3 + 1.0f) + cos1 * cos1, 0.0f)) / n3;
    r23s[i] = thin_film_rs(eta2, n3, cos2, cos3);
    r23p[i] = thin_film_rp(eta2, n3, cos2, cos3);
  }
  // First-order optical path difference of one round trip in the film.
  const float opd_nm = 2.0f * eta2 * d * cos2;
  // Unpolarised light: the mean of the two polarisations' reflectances.
  const glm::vec3 I =
      0.5f * (thin_film_airy(r12s, r23s, opd_nm) + thin_film_airy(r12p, r23p, opd_nm));
  return glm::clamp(I, 0.0f, 1.0f);
}

}  // namespace pbrkit
