#pragma once
// The rounding allowance of the GLSL-vs-C++ BRDF comparisons (brdf_glsl_test.cpp,
// bsdf_glsl_test.cpp) for the compensated lobes.
#include <algorithm>
#include <cmath>

#include "gl/harness/brdf_eval.h"
#include "pbrkit/core/brdf.h"
#include "pbrkit/core/energy.h"

namespace pbrkit::gl::testing {

// With compensation the multiple-scattering lobe Fms (1 - E_o)(1 - E_i) / (pi (1 - E_avg))
// and the compensated diffuse lobe divide differences of numbers close to 1: at low
// roughness E is 0.99999, so one float rounding of E (6e-8) is a 1% change of 1 - E.
// Both implementations round E differently in the last bit (texture fetch, mix), so the
// comparison allows, on top of the 1e-4 relative, the propagated rounding of those lobes
// (a first-order bound with 4 ulp of 1 per table value); it is 0 without compensation.
inline double conditioning_bound(const BrdfCase& c, const BrdfOptions& options) {
  if (!options.multiscatter) return 0.0;
  const double eps = 4.0 * 5.96e-8;
  const Brdf brdf(c.layer(), options);
  const EnergyTable& table = EnergyTable::get(direct_geometry(options.model));
  const double r = brdf.roughness();
  const double one_minus_Eo = std::abs(1.0 - table.E(c.wo.z, float(r)));
  const double one_minus_Ei = std::abs(1.0 - table.E(c.wi.z, float(r)));
  const double one_minus_Eavg = std::max(1.0 - double(table.E_avg(float(r))), 1e-6);
  // The whole specular's Fms (reference: the dielectric's and the metal's mixed).
  glm::vec3 Fms = multiscatter_fresnel(brdf.F0(), table.E_avg(float(r)));
  if (options.model == BrdfModel::kReference) {
    const float s = std::clamp(c.specular, 0.0f, 1.0f);
    Fms = (1.0f - brdf.metallic()) * s *
              multiscatter_fresnel(dielectric_f0(c.ior, c.specular_color), table.E_avg(float(r))) +
          brdf.metallic() * multiscatter_fresnel(brdf.base_color(), table.E_avg(float(r)));
  }
  const double fms = std::max({Fms.r, Fms.g, Fms.b});
  const double ms = fms * (one_minus_Eo + eps) * (one_minus_Ei + eps) / (3.14159 * one_minus_Eavg);
  const double ms_bound =
      ms * (eps / (one_minus_Eo + eps) + eps / (one_minus_Ei + eps) + eps / one_minus_Eavg);
  // The diffuse lobe: lambert (1 - Es_o)(1 - Es_i) / (1 - Es_avg), the same structure, with
  // Es the whole specular's per channel (classic) or the dielectric's max3 (reference).
  const double lambert =
      (1.0 - c.metallic) * std::max({c.base_color.r, c.base_color.g, c.base_color.b}) / 3.14159;
  const glm::vec2 ab_avg = table.AB_avg(float(r));
  double diffuse_bound = 0.0;
  if (options.model == BrdfModel::kReference) {
    const glm::vec3 F0_d = dielectric_f0(c.ior, c.specular_color);
    const float s = std::clamp(c.specular, 0.0f, 1.0f);
    const glm::vec3 Fms_d = s * multiscatter_fresnel(F0_d, table.E_avg(float(r)));
    auto Es_d = [&](glm::vec2 ab) {
      return double(max3(s * (F0_d * ab.x + ab.y) + Fms_d * (1.0f - (ab.x + ab.y))));
    };
    const double a = std::abs(1.0 - Es_d(table.AB(c.wo.z, float(r)))) + eps;
    const double b = std::abs(1.0 - Es_d(table.AB(c.wi.z, float(r)))) + eps;
    const double c_avg = std::max(1.0 - Es_d(ab_avg), 1e-6);
    diffuse_bound = lambert * a * b / c_avg * (eps / a + eps / b + eps / c_avg);
  } else {
    const glm::vec3 Es_o = brdf.specular_albedo(c.wo.z), Es_i = brdf.specular_albedo(c.wi.z);
    for (int k = 0; k < 3; ++k) {
      const double a = std::abs(1.0 - Es_o[k]) + eps, b = std::abs(1.0 - Es_i[k]) + eps;
      const double es_avg =
          brdf.F0()[k] * ab_avg.x + ab_avg.y + Fms[k] * (1.0 - (ab_avg.x + ab_avg.y));
      const double c_avg = std::max(1.0 - es_avg, 1e-6);
      diffuse_bound =
          std::max(diffuse_bound, lambert * a * b / c_avg * (eps / a + eps / b + eps / c_avg));
    }
  }
  return ms_bound + diffuse_bound;
}

}  // namespace pbrkit::gl::testing
