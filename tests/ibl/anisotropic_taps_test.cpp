// ibl/anisotropic_taps.h: the three taps of an anisotropic GGX lobe, each read through a
// model of the prefiltered cube (the environment GGX-filtered at the tap's roughness, as the
// bake does), normalized by their weights and scaled by the lobe's tabulated albedo
// (ibl/anisotropic_albedo.h), against the lobe's integral under an analytic, non-uniform
// environment, integral of D G2 / (4 n.v) L dwi, computed here by the path tracer's own
// estimator (random visible normals, Heitz 2018, weight G2 / G1(wo)) with 2^16 samples.
//
// The tolerance is derived from that estimator: the taps are K = 3 fixed points, so they
// must do at least as well as K independent random samples, whose error has standard
// deviation sigma_1 / sqrt(K) (sigma_1 the one-sample standard deviation, measured here).
// Each case is held within 3 such deviations (plus the reference's own 3 standard errors),
// and the mean square over all cases within a quarter of their variance: as well as 4K
// random samples, which the exact albedo makes possible (0.09 of it measured). Taps that
// sample the wrong lobe (the isotropic lobe at the mean roughness, the split sum's old
// scale) fail that (0.53; ToleranceRejectsTheIsotropicLobe checks it).
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/ibl/anisotropic_albedo.h"
#include "pbrkit/ibl/anisotropic_taps.h"

namespace pbrkit {
namespace {

// A sun (von Mises-Fisher lobe, kappa 8) over a sky with a gradient and a ground: smooth,
// but far from uniform or symmetric about any axis of the frame.
double environment(glm::dvec3 l) {
  const glm::dvec3 sun = glm::normalize(glm::dvec3(0.6, 0.3, 0.74));
  return 0.2 + 0.15 * l.x - 0.1 * l.y + 0.1 * l.z + 3.0 * std::exp(8.0 * (glm::dot(l, sun) - 1.0));
}

struct Reference {
  double mean = 0.0;       ///< integral of D G2 / (4 n.v) L dwi
  double sigma_1 = 0.0;    ///< one sample's standard deviation
  double std_error = 0.0;  ///< the mean's
};

// The path tracer's estimator: visible normals of the anisotropic lobe, weight
// G2 / G1(wo) = (1 + Lambda_o) / (1 + Lambda_o + Lambda_i), in double from the float
// sampler of core/microfacet.h.
Reference reference(glm::vec3 wo, float ax, float ay, double (*env)(glm::dvec3)) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  constexpr int kSamples = 1 << 16;
  const double lambda_o = SmithLambdaGGXAniso(wo, ax, ay);
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const glm::vec3 h = sample_ggx_visible_normal(wo, glm::vec2(u(rng), u(rng)), ax, ay);
    const glm::dvec3 wi = glm::normalize(
        2.0 * glm::dot(glm::dvec3(wo), glm::dvec3(h)) * glm::dvec3(h) - glm::dvec3(wo));
    double x = 0.0;
    if (wi.z > 0.0)
      x = (1.0 + lambda_o) / (1.0 + lambda_o + SmithLambdaGGXAniso(glm::vec3(wi), ax, ay)) *
          env(wi);
    sum += x;
    sum2 += x * x;
  }
  Reference r;
  r.mean = sum / kSamples;
  r.sigma_1 = std::sqrt(std::max(sum2 / kSamples - r.mean * r.mean, 0.0));
  r.std_error = r.sigma_1 / std::sqrt(double(kSamples));
  return r;
}

// What the renderer's cube lookup returns: the environment prefiltered as the bake does
// (MODEL.md "Image-based lighting": GGX at alpha = roughness^2 around n = v = r, sampled
// with D(h) n.h and weighted by n.l), here with 1024 random samples in double.
double prefiltered(glm::dvec3 r, float roughness, double (*env)(glm::dvec3)) {
  const double alpha = double(roughness) * double(roughness);
  const glm::dvec3 a = std::abs(r.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(a, r)), b = glm::cross(r, t);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double sum = 0.0, weight = 0.0;
  for (int i = 0; i < 1024; ++i) {
    // GGX D(h) n.h: tan^2 theta = alpha^2 u / (1 - u).
    const double u1 = u(rng), phi = 2.0 * 3.14159265358979 * u(rng);
    const double cos_t = std::sqrt((1.0 - u1) / (1.0 + (alpha * alpha - 1.0) * u1));
    const double sin_t = std::sqrt(std::max(1.0 - cos_t * cos_t, 0.0));
    const glm::dvec3 h = sin_t * std::cos(phi) * t + sin_t * std::sin(phi) * b + cos_t * r;
    const glm::dvec3 l = 2.0 * glm::dot(r, h) * h - r;
    const double n_dot_l = glm::dot(r, l);
    if (n_dot_l <= 0.0) continue;
    sum += env(l) * n_dot_l;
    weight += n_dot_l;
  }
  return weight > 0.0 ? sum / weight : 0.0;
}

// The renderer's estimate: the taps' prefiltered lookups averaged with their weights, times
// the lobe's albedo from the table.
double taps_estimate(glm::vec3 wo, float ax, float ay, double (*env)(glm::dvec3)) {
  double sum = 0.0, weights = 0.0;
  for (const AnisotropicTap& t : anisotropic_taps(wo, ax, ay))
    if (t.weight > 0.0f) {
      sum += double(t.weight) * prefiltered(glm::dvec3(t.wi), t.roughness, env);
      weights += double(t.weight);
    }
  if (weights <= 0.0) return 0.0;
  return double(AnisotropicAlbedoTable::get().lookup(wo, ax, ay)) * sum / weights;
}

// A point of the unit square as the disk point Heitz's sampler makes of it: radius sqrt(u1),
// angle 2 pi u2.
glm::vec2 disk_point(glm::vec2 u) {
  const float r = std::sqrt(u.x), phi = 6.2831853f * u.y;
  return r * glm::vec2(std::cos(phi), std::sin(phi));
}

struct LobeCase {
  glm::vec3 wo;
  float ax, ay;
};

// The built-in anisotropy scene's lobes (roughness 0.3: alpha 0.09, alpha_x = mix(alpha, 1,
// anisotropy^2) for anisotropy 0.2 .. 1) and a rough one, either way round, at views from
// normal incidence to n.v = 0.15 in three azimuths.
std::vector<LobeCase> lobe_cases() {
  std::vector<LobeCase> cases;
  const float alpha = 0.09f;
  std::vector<glm::vec2> alphas;
  for (float a : {0.2f, 0.4f, 0.6f, 0.8f, 1.0f})
    alphas.emplace_back(alpha + (1.0f - alpha) * a * a, alpha);
  alphas.emplace_back(0.09f, 1.0f);
  alphas.emplace_back(0.36f, 0.6f);
  for (const glm::vec2& a : alphas)
    for (float mu : {1.0f, 0.7f, 0.4f, 0.15f})
      for (float phi : {0.0f, 0.8f, 1.5707964f}) {
        const float s = std::sqrt(1.0f - mu * mu);
        cases.push_back({glm::vec3(s * std::cos(phi), s * std::sin(phi), mu), a.x, a.y});
      }
  return cases;
}

TEST(AnisotropicTaps, ApproximateTheLobesIntegralUnderANonUniformEnvironment) {
  double sum_sq = 0.0, sum_var = 0.0;
  for (const LobeCase& c : lobe_cases()) {
    const Reference ref = reference(c.wo, c.ax, c.ay, environment);
    const double got = taps_estimate(c.wo, c.ax, c.ay, environment);
    const double sigma_k = ref.sigma_1 / std::sqrt(double(kAnisotropicTaps));
    EXPECT_NEAR(got, ref.mean, 3.0 * (sigma_k + ref.std_error))
        << "wo (" << c.wo.x << ", " << c.wo.y << ", " << c.wo.z << ") alpha " << c.ax << " x "
        << c.ay;
    sum_sq += (got - ref.mean) * (got - ref.mean);
    sum_var += sigma_k * sigma_k;
  }
  EXPECT_LT(sum_sq, 0.25 * sum_var)
      << "the taps are no better than " << 4 * kAnisotropicTaps << " random samples";
}

// With L = 1 the estimate is the tabulated albedo: within 1.5% (the table's interpolation
// between its nodes, measured below 1%) plus 3 standard errors of the reference, whose
// random visible normals share nothing with the table's fixed lattice.
double one(glm::dvec3) {
  return 1.0;
}

TEST(AnisotropicTaps, UnderAUniformEnvironmentTheEstimateIsTheLobesAlbedo) {
  for (const LobeCase& c : lobe_cases()) {
    const Reference ref = reference(c.wo, c.ax, c.ay, one);
    const double got = taps_estimate(c.wo, c.ax, c.ay, one);
    EXPECT_NEAR(got, ref.mean, 0.015 * ref.mean + 3.0 * ref.std_error)
        << "wo (" << c.wo.x << ", " << c.wo.y << ", " << c.wo.z << ") alpha " << c.ax << " x "
        << c.ay;
  }
}

// The tolerance above is tight enough to see a wrong lobe: the same three points drawn
// from the isotropic lobe at the albedo tables' geometric-mean alpha (what the split sum
// looked up before) miss the anisotropic lobe's integral by more, in root mean square,
// than 4K random samples of the right lobe would.
TEST(AnisotropicTaps, ToleranceRejectsTheIsotropicLobe) {
  double sum_sq = 0.0, sum_var = 0.0;
  for (const LobeCase& c : lobe_cases()) {
    const Reference ref = reference(c.wo, c.ax, c.ay, environment);
    const float a = std::sqrt(c.ax * c.ay);
    const double got = taps_estimate(c.wo, a, a, environment);
    const double sigma_k = ref.sigma_1 / std::sqrt(double(kAnisotropicTaps));
    sum_sq += (got - ref.mean) * (got - ref.mean);
    sum_var += sigma_k * sigma_k;
  }
  EXPECT_GT(sum_sq, 0.25 * sum_var);
}

// The taps hold to the lobe as the view turns: across the line where the stretched view's
// azimuth swings by pi (n.v's azimuth across the long axis, wo.x through 0 with alpha_x 1,
// alpha_y 0.09), a small step of wo moves every tap a little. Heitz's sampler with a point
// fixed in its own frame moves by up to the lobe's width there (the crease this avoids),
// which the second check shows for a point off the long axis (the taps' own points, on the
// axis and opposite, would swap places there, a set unchanged but each tap jumping).
TEST(AnisotropicTaps, TapsMoveSmoothlyAcrossTheViewsSwing) {
  const float ax = 1.0f, ay = 0.09f;
  const glm::vec3 a = glm::normalize(glm::vec3(-2e-3f, 0.6f, 0.8f));
  const glm::vec3 b = glm::normalize(glm::vec3(2e-3f, 0.6f, 0.8f));
  float largest = 0.0f;
  for (int i = 0; i < kAnisotropicTaps; ++i) {
    const glm::vec2 d = anisotropic_tap_point(i);
    largest = std::max(largest, glm::length(anisotropic_visible_normal(a, d, ax, ay) -
                                            anisotropic_visible_normal(b, d, ax, ay)));
  }
  const glm::vec2 u(0.5625f, 0.3125f);  // r 0.75 at 112.5 degrees from T1
  const float view_frame = glm::length(sample_ggx_visible_normal(a, u, ax, ay) -
                                       sample_ggx_visible_normal(b, u, ax, ay));
  // wo moved by 4e-3: the lobe-held taps move by about that, the view-frame point by
  // twenty times as much: the crease.
  EXPECT_LT(largest, 0.02f);
  EXPECT_GT(view_frame, 0.05f);
}

// Uniform points give the visible normals' distribution, as Heitz's sampler does: the
// first and second moments of h and of the estimator's weight over 2^16 random points agree
// with core/microfacet.h's sampler within 4 standard errors of their difference.
TEST(AnisotropicTaps, VisibleNormalSamplerIsHeitzs) {
  for (const LobeCase& c : lobe_cases()) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    constexpr int kN = 1 << 14;
    glm::dvec3 m_ours(0.0), m_core(0.0), m2_ours(0.0), m2_core(0.0);
    for (int i = 0; i < kN; ++i) {
      const glm::vec2 p(u(rng), u(rng));
      const glm::dvec3 h1(anisotropic_visible_normal(c.wo, disk_point(p), c.ax, c.ay));
      const glm::dvec3 h2(sample_ggx_visible_normal(c.wo, glm::vec2(u(rng), u(rng)), c.ax, c.ay));
      m_ours += h1;
      m_core += h2;
      m2_ours += h1 * h1;
      m2_core += h2 * h2;
    }
    for (int k = 0; k < 3; ++k) {
      const double mean1 = m_ours[k] / kN, mean2 = m_core[k] / kN;
      const double var1 = m2_ours[k] / kN - mean1 * mean1, var2 = m2_core[k] / kN - mean2 * mean2;
      const double se = std::sqrt((var1 + var2) / kN);
      EXPECT_NEAR(mean1, mean2, 4.0 * se + 1e-6)
          << "axis " << k << " alpha " << c.ax << " x " << c.ay;
    }
  }
}

// The taps' lookup roughness is the isotropic lobe's with the lobe's whole solid angle at
// normal incidence, 4 pi alpha_l^2 = 1 / pdf with pdf the visible normals' at wo = n,
// G1 D(h) / (4 n.v) (core/microfacet.h's D at the normal; G1 = 1 there), for every view and
// tap. For an isotropic lobe that is alpha_l = alpha in closed form. And never outside the
// cube's roughness range.
TEST(AnisotropicTaps, LookupRoughnessIsTheLobesSolidAngle) {
  for (float alpha : {0.05f, 0.25f, 0.8f})
    for (int i = 0; i < kAnisotropicTaps; ++i) {
      const AnisotropicTap t = anisotropic_tap(glm::vec3(0, 0, 1), alpha, alpha, i);
      EXPECT_NEAR(t.roughness, std::max(std::sqrt(alpha), kMinRoughness), 1e-4f)
          << alpha << " tap " << i;
    }
  for (const LobeCase& c : lobe_cases()) {
    const double pdf = DistributionGGXAniso(glm::vec3(0, 0, 1), c.ax, c.ay) / 4.0;
    const double alpha_l2 = 1.0 / (pdf * 4.0 * 3.14159265358979);
    for (int i = 0; i < kAnisotropicTaps; ++i)
      EXPECT_NEAR(anisotropic_tap(c.wo, c.ax, c.ay, i).roughness,
                  std::max(float(std::sqrt(std::sqrt(alpha_l2))), kMinRoughness), 1e-4f);
  }
  for (const AnisotropicTap& t : anisotropic_taps(glm::vec3(0.6f, 0.0f, 0.8f), 1.0f, 4e-4f)) {
    EXPECT_GE(t.roughness, kMinRoughness);
    EXPECT_LE(t.roughness, 1.0f);
  }
}

}  // namespace
}  // namespace pbrkit
