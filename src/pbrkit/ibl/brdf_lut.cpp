// The split-sum BRDF integration LUT (Karis 2013, "Real Shading in Unreal Engine 4",
// IntegrateBRDF), with a third channel E = A + B and a fourth E_avg for
// multiple-scattering compensation (Fdez-Aguera 2019; Kulla & Conty 2017).
#include <tbb/parallel_for.h>

#include <cmath>
#include <vector>

#include "pbrkit/core/material.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {
// Hammersley visible-normal samples per texel (see below); at 1024 the entries are within
// ~2e-4 of a 65,536-sample integration (tests/ibl/brdf_lut_test.cpp).
constexpr int kLutSamples = 1024;
}  // namespace

Image compute_brdf_lut(BrdfModel model, int size) {
  if (size < 1 || size > 4096) fail("BRDF LUT size must be in 1..4096, got {}", size);
  const GeometryModel geometry = ibl_geometry(model);
  Image lut(size, size, 4);
  // The points do not depend on the texel: generate them once.
  std::vector<glm::vec2> u(kLutSamples);
  for (int i = 0; i < kLutSamples; ++i) u[i] = hammersley(std::uint32_t(i), kLutSamples);
  tbb::parallel_for(0, size, [&](int y) {
    const float roughness = std::max((float(y) + 0.5f) / float(size), kMinRoughness);
    const float alpha = roughness * roughness;
    for (int x = 0; x < size; ++x) {
      const float NdotV = (float(x) + 0.5f) / float(size);
      const glm::vec3 V(std::sqrt(1.0f - NdotV * NdotV), 0.0f, NdotV);
      // The seed's IntegrateBRDF samples the NDF and weights by G (v.h) / ((n.h)(n.v)),
      // which is unbounded at grazing n.v (measured: off by 0.3 at n.v = 0.01 with 1024
      // points). Visible-normal sampling (Heitz 2018) estimates the same integral with the
      // bounded weight F G / G1(v): pdf(l) = G1(v) D (v.h) / (4 (n.v)(v.h)) cancels D and
      // the cosines of f cos. Schlick's F = F0 (1 - Fc) + Fc splits it into A and B.
      const float G1V = SmithG1GGX(V, alpha);
      double A = 0.0, B = 0.0;
      for (int i = 0; i < kLutSamples; ++i) {
        const glm::vec3 H = sample_ggx_vndf(V, u[i], alpha).h;
        const float VdotH = glm::dot(V, H);
        const glm::vec3 L = 2.0f * VdotH * H - V;
        if (L.z <= 0.0f || VdotH <= 0.0f) continue;
        const float G = GeometryG(geometry, V, L, roughness);
        const float weight = G / G1V;
        const float m = 1.0f - VdotH;
        const float Fc = (m * m) * (m * m) * m;
        A += double((1.0f - Fc) * weight);
        B += double(Fc * weight);
      }
      float* p = lut.pixel(x, y);
      p[0] = float(A / kLutSamples);
      p[1] = float(B / kLutSamples);
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
