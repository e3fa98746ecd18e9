#include "pbrkit/core/transmission.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pbrkit/core/energy.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"

namespace pbrkit {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// The interface's ior ratio as a usable number: eta must be positive and finite (the
// material's checks keep it so; this keeps a bad value from turning into NaN).
float sane_eta(float eta) {
  return eta > 0.0f && eta < kInf ? eta : 1.0f;
}

// Height-correlated Smith G2 (Heitz 2014, eq. 99). Lambda depends on tan^2 theta only, so
// it is evaluated the same way above and below the surface.
float smith_g2(glm::vec3 wo, glm::vec3 wi, float ax, float ay) {
  if (wo.z == 0.0f || wi.z == 0.0f) return 0.0f;
  return 1.0f / (1.0f + SmithLambdaGGXAniso(wo, ax, ay) + SmithLambdaGGXAniso(wi, ax, ay));
}

// The visible-normal pdf of h seen from w, on either side (Heitz 2018, eq. 3):
// G1(w) |w.h| D(h) / |w.z|, zero for normals facing away from w.
float visible_normal_pdf(glm::vec3 w, glm::vec3 h, float ax, float ay) {
  const float wh = glm::dot(w, h);
  if (w.z == 0.0f || wh * w.z <= 0.0f) return 0.0f;
  const float G1 = 1.0f / (1.0f + SmithLambdaGGXAniso(w, ax, ay));
  return G1 * std::abs(wh) * DistributionGGXAniso(h, ax, ay) / std::abs(w.z);
}

glm::vec3 flip_z(glm::vec3 v) {
  return {v.x, v.y, -v.z};
}

}  // namespace

float fresnel_dielectric(float cos_i, float eta) {
  if (eta == 1.0f) return 0.0f;  // no interface
  if (!(eta > 0.0f) || !(eta < kInf)) return 1.0f;
  cos_i = std::clamp(cos_i, -1.0f, 1.0f);
  if (cos_i < 0.0f) {
    eta = 1.0f / eta;
    cos_i = -cos_i;
  }
  // Snell: sin_t = sin_i / eta; total internal reflection when it reaches 1.
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = safe_sqrt(1.0f - sin2_t);
  // Born & Wolf eq. (1.5.21): r_parallel and r_perpendicular for n_t / n_i = eta.
  const float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

bool refract(glm::vec3 w, glm::vec3 n, float eta, glm::vec3& wt) {
  eta = sane_eta(eta);
  const float cos_i = glm::dot(n, w);
  const float sin2_t = std::max(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  const float cos_t = safe_sqrt(1.0f - sin2_t);
  // wt = -w / eta + (cos_i / eta - cos_t) n  (pbrt-v4, section 9.3.2, eq. 9.4)
  const glm::vec3 t = -w / eta + (cos_i / eta - cos_t) * n;
  const float l = glm::length(t);
  if (!(l > 0.0f)) return false;
  wt = t / l;
  return true;
}

bool dielectric_is_smooth(const Dielectric& d) {
  return d.eta == 1.0f || std::max(d.alpha_x, d.alpha_y) < kSmoothDielectricAlpha;
}

glm::vec3 dielectric_half_vector(glm::vec3 wo, glm::vec3 wi, float eta) {
  eta = sane_eta(eta);
  const bool reflect = wo.z * wi.z > 0.0f;
  const float etap = reflect ? 1.0f : (wo.z > 0.0f ? eta : 1.0f / eta);
  const glm::vec3 h = wo + etap * wi;
  const float l2 = glm::dot(h, h);
  if (!(l2 > 0.0f)) return glm::vec3(0.0f);
  const glm::vec3 hn = h / std::sqrt(l2);
  return hn.z < 0.0f ? -hn : hn;
}

namespace {

// A thin wall seen from above (o.z > 0): a transmission is the reflection mirrored through
// the plane, weighted by 1 - F. Sets o, i to the pair as a reflection; returns whether wi
// was transmitted.
bool thin_wall_pair(glm::vec3 wo, glm::vec3 wi, glm::vec3& o, glm::vec3& i) {
  const float s = wo.z < 0.0f ? -1.0f : 1.0f;
  o = glm::vec3(wo.x, wo.y, s * wo.z);
  i = glm::vec3(wi.x, wi.y, s * wi.z);
  const bool transmitted = i.z < 0.0f;
  if (transmitted) i = flip_z(i);
  return transmitted;
}

float eval_single(const Dielectric& d, glm::vec3 wo, glm::vec3 wi, TransportMode mode) {
  if (dielectric_is_smooth(d) || wo.z == 0.0f || wi.z == 0.0f) return 0.0f;
  const float eta = sane_eta(d.eta);
  const float ax = d.alpha_x, ay = d.alpha_y;
  if (d.thin_walled) {
    glm::vec3 o, i;
    const bool transmitted = thin_wall_pair(wo, wi, o, i);
    const glm::vec3 h = glm::normalize(o + i);
    const float F = fresnel_dielectric(glm::dot(o, h), eta);
    const float D = DistributionGGXAniso(h, ax, ay);
    const float G = smith_g2(o, i, ax, ay);
    return (transmitted ? 1.0f - F : F) * D * G / (4.0f * o.z * i.z);
  }
  const bool reflect = wo.z * wi.z > 0.0f;
  const float etap = reflect ? 1.0f : (wo.z > 0.0f ? eta : 1.0f / eta);
  const glm::vec3 h = dielectric_half_vector(wo, wi, eta);
  if (h == glm::vec3(0.0f)) return 0.0f;
  const float oh = glm::dot(wo, h), ih = glm::dot(wi, h);
  // Microfacets seen from behind by either direction contribute nothing (Walter 2007,
  // the chi+ terms of eqs. 20-21).
  if (oh * wo.z <= 0.0f || ih * wi.z <= 0.0f) return 0.0f;
  const float F = fresnel_dielectric(oh, eta);
  const float D = DistributionGGXAniso(h, ax, ay);
  const float G = smith_g2(wo, wi, ax, ay);
  if (reflect) return F * D * G / std::abs(4.0f * wo.z * wi.z);
  // Walter 2007, eq. 21, with the eta of the side wi is on: the Jacobian of h.
  const float denom = sqr(ih + oh / etap);
  if (!(denom > 0.0f)) return 0.0f;
  float ft = (1.0f - F) * D * G * std::abs(ih * oh / (wi.z * wo.z * denom));
  // Radiance is compressed into the narrower cone of the denser side (Veach 1997, 5.2).
  if (mode == TransportMode::kRadiance) ft /= sqr(etap);
  return std::isfinite(ft) ? ft : 0.0f;
}

float pdf_single(const Dielectric& d, glm::vec3 wo, glm::vec3 wi) {
  if (dielectric_is_smooth(d) || wo.z == 0.0f || wi.z == 0.0f) return 0.0f;
  const float eta = sane_eta(d.eta);
  const float ax = d.alpha_x, ay = d.alpha_y;
  if (d.thin_walled) {
    glm::vec3 o, i;
    const bool transmitted = thin_wall_pair(wo, wi, o, i);
    const glm::vec3 h = glm::normalize(o + i);
    const float oh = glm::dot(o, h);
    const float F = fresnel_dielectric(oh, eta);
    return (transmitted ? 1.0f - F : F) * reflected_pdf(visible_normal_pdf(o, h, ax, ay), oh);
  }
  const bool reflect = wo.z * wi.z > 0.0f;
  const float etap = reflect ? 1.0f : (wo.z > 0.0f ? eta : 1.0f / eta);
  const glm::vec3 h = dielectric_half_vector(wo, wi, eta);
  if (h == glm::vec3(0.0f)) return 0.0f;
  const float oh = glm::dot(wo, h), ih = glm::dot(wi, h);
  if (oh * wo.z <= 0.0f || ih * wi.z <= 0.0f) return 0.0f;
  const float F = fresnel_dielectric(oh, eta);
  const float pdf_h = visible_normal_pdf(wo, h, ax, ay);
  if (reflect) return F * pdf_h / (4.0f * std::abs(oh));
  // dh/dwi = |wi.h| / (wi.h + wo.h / eta')^2 (Walter 2007, eq. 17).
  const float denom = sqr(ih + oh / etap);
  if (!(denom > 0.0f)) return 0.0f;
  const float p = (1.0f - F) * pdf_h * std::abs(ih) / denom;
  return std::isfinite(p) ? p : 0.0f;
}

// ---- Multiple-scattering compensation (transmission.h, DielectricCompensation). ----

// The single-scattering albedo seen from side `side` (0: +Z, 1: -Z) at mu.
float side_albedo(const Dielectric& d, int side, float mu) {
  if (d.thin_walled) return EnergyTable::get(GeometryModel::kReference).E(mu, d.ms.roughness);
  const float eta = sane_eta(d.eta);
  return DielectricEnergyTable::get().E(mu, d.ms.roughness, side == 0 ? eta : 1.0f / eta);
}

// The probability of sampling the compensation lobe from wo: its albedo 1 - E(mu_o).
float ms_probability(const Dielectric& d, glm::vec3 wo) {
  return std::clamp(1.0f - side_albedo(d, wo.z > 0.0f ? 0 : 1, std::abs(wo.z)), 0.0f, 1.0f);
}

float eval_ms(const Dielectric& d, glm::vec3 wo, glm::vec3 wi, TransportMode mode) {
  const int so = wo.z > 0.0f ? 0 : 1, si = wi.z > 0.0f ? 0 : 1;
  const float denom = 1.0f - d.ms.E_avg[si];
  if (!(denom > 1e-6f)) return 0.0f;
  const float share = so == si ? d.ms.reflect[so] : 1.0f - d.ms.reflect[so];
  float f = share * std::max(1.0f - side_albedo(d, so, std::abs(wo.z)), 0.0f) *
            std::max(1.0f - side_albedo(d, si, std::abs(wi.z)), 0.0f) / (kPi * denom);
  if (so != si && !d.thin_walled && mode == TransportMode::kRadiance) {
    const float eta = sane_eta(d.eta);
    f /= sqr(so == 0 ? eta : 1.0f / eta);
  }
  return f;
}

// The compensation lobe's sampler: reflect with probability reflect[side], a cosine lobe on
// the side chosen.
float pdf_ms(const Dielectric& d, glm::vec3 wo, glm::vec3 wi) {
  const int so = wo.z > 0.0f ? 0 : 1;
  const bool same = (wo.z > 0.0f) == (wi.z > 0.0f);
  return (same ? d.ms.reflect[so] : 1.0f - d.ms.reflect[so]) * std::abs(wi.z) * kInvPi;
}

}  // namespace

void enable_dielectric_multiscatter(Dielectric& d) {
  if (dielectric_is_smooth(d)) return;
  DielectricCompensation& ms = d.ms;
  ms.on = true;
  ms.roughness = std::clamp(std::sqrt(std::sqrt(d.alpha_x * d.alpha_y)), 0.0f, 1.0f);
  const float eta = sane_eta(d.eta);
  const DielectricEnergyTable& table = DielectricEnergyTable::get();
  if (d.thin_walled) {
    // Both sides see the same wall: any constant share is reciprocal.
    const float E_avg = EnergyTable::get(GeometryModel::kReference).E_avg(ms.roughness);
    const float R_avg = table.averages(ms.roughness, eta).y;
    ms.E_avg[0] = ms.E_avg[1] = E_avg;
    ms.reflect[0] = ms.reflect[1] = std::clamp(R_avg / std::max(E_avg, 1e-6f), 0.0f, 1.0f);
    return;
  }
  const glm::vec2 a[2] = {table.averages(ms.roughness, eta),
                          table.averages(ms.roughness, 1.0f / eta)};
  ms.E_avg[0] = a[0].x;
  ms.E_avg[1] = a[1].x;
  // The rarer side r (its far side denser, ratio e >= 1) keeps its single-scattering split;
  // the denser side's transmitted share follows from reciprocity.
  const int r = eta >= 1.0f ? 0 : 1, o = 1 - r;
  const float e = eta >= 1.0f ? eta : 1.0f / eta;
  const float t_r = std::clamp((a[r].x - a[r].y) / std::max(a[r].x, 1e-6f), 0.0f, 1.0f);
  const float loss_o = 1.0f - a[o].x;
  const float t_o =
      loss_o > 1e-6f ? std::clamp(t_r * (1.0f - a[r].x) / (e * e * loss_o), 0.0f, 1.0f) : t_r;
  ms.reflect[r] = 1.0f - t_r;
  ms.reflect[o] = 1.0f - t_o;
}

float dielectric_eval(const Dielectric& d, glm::vec3 wo, glm::vec3 wi, TransportMode mode) {
  const float f = eval_single(d, wo, wi, mode);
  if (!d.ms.on || wo.z == 0.0f || wi.z == 0.0f || dielectric_is_smooth(d)) return f;
  return f + eval_ms(d, wo, wi, mode);
}

float dielectric_pdf(const Dielectric& d, glm::vec3 wo, glm::vec3 wi) {
  const float p = pdf_single(d, wo, wi);
  if (!d.ms.on || wo.z == 0.0f || wi.z == 0.0f || dielectric_is_smooth(d)) return p;
  const float P = ms_probability(d, wo);
  return (1.0f - P) * p + P * pdf_ms(d, wo, wi);
}

namespace {

DielectricSample sample_smooth(const Dielectric& d, glm::vec3 wo, float u_lobe,
                               TransportMode mode) {
  DielectricSample s;
  const float eta = sane_eta(d.eta);
  // Seen from below the interface is the same one with 1 / eta (thin walls: the same eta).
  const float R =
      d.thin_walled ? fresnel_dielectric(std::abs(wo.z), eta) : fresnel_dielectric(wo.z, eta);
  const float T = 1.0f - R;
  s.delta = true;
  if (u_lobe < R) {
    s.wi = glm::vec3(-wo.x, -wo.y, wo.z);
    s.pdf = R;
    s.weight = 1.0f;
  } else {
    if (d.thin_walled) {
      s.wi = -wo;
      s.weight = 1.0f;
    } else {
      const glm::vec3 n(0.0f, 0.0f, wo.z > 0.0f ? 1.0f : -1.0f);
      const float etap = wo.z > 0.0f ? eta : 1.0f / eta;
      if (!refract(wo, n, etap, s.wi)) return s;  // T = 0 under TIR: not reached
      s.weight = mode == TransportMode::kRadiance ? 1.0f / sqr(etap) : 1.0f;
    }
    s.pdf = T;
    s.transmitted = true;
  }
  if (s.wi.z == 0.0f || !(s.pdf > 0.0f)) return s;
  s.f = s.weight * s.pdf / std::abs(s.wi.z);
  s.valid = true;
  return s;
}

}  // namespace

DielectricSample dielectric_sample(const Dielectric& d, glm::vec3 wo, float u_lobe, glm::vec2 u,
                                   TransportMode mode) {
  if (wo.z == 0.0f) return {};
  if (dielectric_is_smooth(d)) return sample_smooth(d, wo, u_lobe, mode);
  DielectricSample s;
  if (d.ms.on) {
    // The compensation lobe with probability P = 1 - E(mu_o), else the single-scattering
    // sampler with u_lobe rescaled; the weight uses the mixture's pdf.
    const float P = ms_probability(d, wo);
    if (u_lobe < P) {
      const int so = wo.z > 0.0f ? 0 : 1;
      s.transmitted = u_lobe / P >= d.ms.reflect[so];
      const glm::vec3 c = sample_cosine_hemisphere(u).direction;
      const float side = (wo.z > 0.0f) != s.transmitted ? 1.0f : -1.0f;
      s.wi = glm::vec3(c.x, c.y, side * c.z);
      s.f = dielectric_eval(d, wo, s.wi, mode);
      s.pdf = dielectric_pdf(d, wo, s.wi);
      if (!(s.pdf > 0.0f) || !std::isfinite(s.f)) return s;
      s.weight = s.f * std::abs(s.wi.z) / s.pdf;
      s.valid = std::isfinite(s.weight);
      return s;
    }
    u_lobe = std::min((u_lobe - P) / (1.0f - P), 0x1.fffffep-1f);
  }
  const float eta = sane_eta(d.eta);
  const float ax = d.alpha_x, ay = d.alpha_y;
  // The visible normal from wo's side (for wo below, from -wo: the microfacets face +Z).
  const float side = wo.z < 0.0f ? -1.0f : 1.0f;
  if (d.thin_walled) {
    // The wall seen from above (wo mirrored through the plane when it is below).
    const glm::vec3 o(wo.x, wo.y, side * wo.z);
    const glm::vec3 h = sample_ggx_visible_normal(o, u, ax, ay);
    const float F = fresnel_dielectric(glm::dot(o, h), eta);
    glm::vec3 i = reflect_about(o, h);
    if (!(i.z > 0.0f)) return s;
    s.transmitted = u_lobe >= F;
    if (s.transmitted) i = flip_z(i);
    s.wi = glm::vec3(i.x, i.y, side * i.z);
  } else {
    // pbrt-v4 samples the visible normals of -wo for wo below (the pdf is symmetric in wo).
    const glm::vec3 h = sample_ggx_visible_normal(side * wo, u, ax, ay);
    const float oh = glm::dot(wo, h);
    if (oh * wo.z <= 0.0f) return s;
    const float F = fresnel_dielectric(oh, eta);
    if (u_lobe < F) {
      s.wi = reflect_about(wo, h);
      if (!(s.wi.z * wo.z > 0.0f)) return s;
    } else {
      const float etap = wo.z > 0.0f ? eta : 1.0f / eta;
      if (!refract(wo, side * h, etap, s.wi)) return s;
      if (!(s.wi.z * wo.z < 0.0f)) return s;
      s.transmitted = true;
    }
  }
  s.f = dielectric_eval(d, wo, s.wi, mode);
  s.pdf = dielectric_pdf(d, wo, s.wi);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.f)) return s;
  s.weight = s.f * std::abs(s.wi.z) / s.pdf;
  s.valid = std::isfinite(s.weight);
  return s;
}

glm::vec3 volume_absorption(glm::vec3 attenuation_color, float attenuation_distance) {
  if (!(attenuation_distance < kInf)) return glm::vec3(0.0f);  // infinite or NaN: none
  glm::vec3 sigma;
  for (int c = 0; c < 3; ++c) {
    const float col = std::clamp(attenuation_color[c], 0.0f, 1.0f);
    if (col >= 1.0f || std::isnan(attenuation_color[c]))
      sigma[c] = 0.0f;
    else if (!(attenuation_distance > 0.0f) || col <= 0.0f)
      sigma[c] = kInf;
    else
      sigma[c] = -std::log(col) / attenuation_distance;
  }
  return sigma;
}

glm::vec3 volume_transmittance(glm::vec3 attenuation_color, float attenuation_distance,
                               float distance) {
  if (!(distance > 0.0f)) return glm::vec3(1.0f);
  const glm::vec3 sigma = volume_absorption(attenuation_color, attenuation_distance);
  glm::vec3 tr;
  // exp(-inf) = 0 and exp(-0) = 1: no NaN for any sigma when distance is finite and > 0.
  for (int c = 0; c < 3; ++c)
    tr[c] = sigma[c] > 0.0f ? std::exp(-sigma[c] * std::min(distance, kInf)) : 1.0f;
  return tr;
}

}  // namespace pbrkit
