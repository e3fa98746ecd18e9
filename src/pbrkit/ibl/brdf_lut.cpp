// The split-sum BRDF integration LUT (Karis 2013, "Real Shading in Unreal Engine 4",
// IntegrateBRDF), with a third channel E = A + B and a fourth E_avg for
// multiple-scattering compensation (Fdez-Aguera 2019; Kulla & Conty 2017). See brdf_lut.h.
#include "pbrkit/ibl/brdf_lut.h"

#include <cmath>
#include <vector>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/ibl/simd.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

namespace {
// Hammersley visible-normal samples per texel (see below). Measured against the same
// estimator with 65,536 points at every texel of a 128 x 128 LUT, both models: within
// 1.2e-3 in A and 1.5e-3 in B, the worst at roughness ~0.17 (A) and at grazing n.v ~0.02
// (B); on a 64 x 64 LUT within 8.5e-4 for roughness >= 0.5. A is biased high, by 4e-4 on
// average: Hammersley's first coordinate is i / N, not (i + 1/2) / N (centred points:
// mean 2e-6, but still up to 1e-3 at low roughness). The error falls as 1/N (4096 points,
// 32 x 32 LUT: 2.7e-4 against 1.2e-3). tests/ibl/brdf_lut_test.cpp checks sampled texels
// to 1e-3.
constexpr int kLutSamples = 1024;
static_assert(kLutSamples % simd::kLanes == 0);

// The parts of Heitz 2018's visible-normal sampling (JCGT 7(4), listing 1) that depend only
// on the point u, not on the texel: the uniform disk point (t1, t2) = sqrt(u.x)
// (cos 2 pi u.y, sin 2 pi u.y) and sqrt(1 - t1^2), in structure-of-arrays form. They hold
// the sample's only transcendental functions, so the per-texel loop has none.
struct DiskPoints {
  std::vector<float> t1, t2, edge;
};

DiskPoints disk_points() {
  DiskPoints d;
  for (int i = 0; i < kLutSamples; ++i) {
    const glm::vec2 u = hammersley(std::uint32_t(i), kLutSamples);
    const float r = std::sqrt(u.x);
    const float phi = 2.0f * kPi * u.y;
    d.t1.push_back(r * std::cos(phi));
    d.t2.push_back(r * std::sin(phi));
    d.edge.push_back(safe_sqrt(1.0f - d.t1.back() * d.t1.back()));
  }
  return d;
}

// (A, B) for one texel: the visible-normal estimator of Karis's integral (see
// compute_brdf_lut), vectorised over the samples. V = (sin, 0, cos) lies in the xz plane,
// which fixes Heitz's frame: with Vh = normalize(alpha V.x, 0, V.z), T1 = (0, 1, 0) and
// T2 = Vh x T1 = (-Vh.z, 0, Vh.x), so listing 1 reduces to the arithmetic below (the same
// operations as core's sample_ggx_vndf for this V, up to rounding).
glm::dvec2 integrate_texel(GeometryModel geometry, const DiskPoints& d, float NdotV,
                           float roughness) {
  using simd::floatv;
  const float alpha = roughness * roughness;
  const glm::vec3 V(std::sqrt(1.0f - NdotV * NdotV), 0.0f, NdotV);
  const glm::vec3 Vh = glm::normalize(glm::vec3(alpha * V.x, 0.0f, V.z));
  const float s = 0.5f * (1.0f + Vh.z);
  // The weight G / G1(v) of the estimator, with the divisions by G1(v) folded in per texel.
  // Reference (height-correlated Smith, Heitz 2014 eq. 99): with
  // Lambda(l) = (sqrt(l.z^2 + alpha^2 (l.x^2 + l.y^2)) / l.z - 1) / 2,
  //   G2 / G1(v) = (1 + Lambda(v)) / (1 + Lambda(v) + Lambda(l))
  //              = (1 + Lambda(v)) l.z / ((1/2 + Lambda(v)) l.z + sqrt(...) / 2),
  // one square root and one division per sample. Classic (Schlick-GGX Smith product,
  // k = alpha / 2): G / G1(v) = G_s(n.v) / G1(v) * l.z / (l.z (1 - k) + k).
  const float lambda_v = SmithLambdaGGX(V, alpha);
  const float g1_v = SmithG1GGX(V, alpha);
  const float k = k_ibl(roughness);
  const float classic_scale = GeometrySchlickGGX(NdotV, k) / g1_v;
  const bool reference = geometry == GeometryModel::kReference;
  const floatv alpha2 = alpha * alpha;
  floatv sum_a = 0.0f, sum_b = 0.0f;
  for (int i = 0; i < kLutSamples; i += simd::kLanes) {
    const floatv t1 = simd::load(&d.t1[i]);
    const floatv t2 = (1.0f - s) * simd::load(&d.edge[i]) + s * simd::load(&d.t2[i]);
    const floatv nz = sqrt(max(1.0f - t1 * t1 - t2 * t2, floatv(0.0f)));
    // Nh = t1 T1 + t2 T2 + nz Vh, then unstretched: h ~ (alpha Nh.x, alpha Nh.y, Nh.z).
    const floatv hx = alpha * (nz * Vh.x - t2 * Vh.z);
    const floatv hy = alpha * t1;
    const floatv hz = max(t2 * Vh.x + nz * Vh.z, floatv(1e-7f));
    const floatv inv_len = 1.0f / sqrt(hx * hx + hy * hy + hz * hz);
    const floatv VdotH = (V.x * hx + V.z * hz) * inv_len;
    // l = reflect(v, h) = 2 (v.h) h - v.
    const floatv two_vh = 2.0f * VdotH * inv_len;
    const floatv lx = two_vh * hx - V.x, ly = two_vh * hy, lz = two_vh * hz - V.z;
    floatv weight;
    if (reference) {
      const floatv q = sqrt(lz * lz + alpha2 * (lx * lx + ly * ly));
      weight = (1.0f + lambda_v) * lz / ((0.5f + lambda_v) * lz + 0.5f * q);
    } else {
      weight = classic_scale * lz / (lz * (1.0f - k) + k);
    }
    const floatv m = 1.0f - VdotH;
    const floatv Fc = (m * m) * (m * m) * m;
    // Samples below the horizon (or facing away from v) contribute nothing.
    const simd::maskv valid = lz > 0.0f && VdotH > 0.0f;
    where(valid, sum_a) += (1.0f - Fc) * weight;
    where(valid, sum_b) += Fc * weight;
  }
  return {double(reduce(sum_a)), double(reduce(sum_b))};
}

}  // namespace

Image compute_brdf_lut(BrdfModel model, int size) {
  if (size < 1 || size > 4096) fail("BRDF LUT size must be in 1..4096, got {}", size);
  const GeometryModel geometry = ibl_geometry(model);
  Image lut(size, size, 4);
  // The points do not depend on the texel: generate them once.
  const DiskPoints points = disk_points();
  pbrkit::parallel_for(0, size, [&](int y) {
    const float roughness = std::max((float(y) + 0.5f) / float(size), kMinRoughness);
    for (int x = 0; x < size; ++x) {
      const float NdotV = (float(x) + 0.5f) / float(size);
      // The seed's IntegrateBRDF samples the NDF and weights by G (v.h) / ((n.h)(n.v)),
      // which is unbounded at grazing n.v (measured: off by 0.3 at n.v = 0.01 with 1024
      // points). Visible-normal sampling (Heitz 2018) estimates the same integral with the
      // bounded weight F G / G1(v): pdf(l) = G1(v) D (v.h) / (4 (n.v)(v.h)) cancels D and
      // the cosines of f cos. Schlick's F = F0 (1 - Fc) + Fc splits it into A and B.
      const glm::dvec2 AB = integrate_texel(geometry, points, NdotV, roughness);
      float* p = lut.pixel(x, y);
      p[0] = float(AB.x / kLutSamples);
      p[1] = float(AB.y / kLutSamples);
      p[2] = p[0] + p[1];
    }
    // E_avg = 2 int_0^1 E(mu) mu dmu (Kulla & Conty 2017), midpoint rule over the row.
    double E_avg = 0.0;
    for (int x = 0; x < size; ++x) {
      const double mu = (x + 0.5) / size;
      E_avg += 2.0 * double(lut.pixel(x, y)[2]) * mu / size;
    }
    for (int x = 0; x < size; ++x) lut.pixel(x, y)[3] = float(E_avg);
  });
  return lut;
}

}  // namespace pbrkit
