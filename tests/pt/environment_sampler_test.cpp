// The environment importance sampler against its own pdf (chi-square, pbrt-v4 style) on
// a real, very peaky HDRI, and the pdf against Environment::eval's orientation and
// rotation (an estimate of the total power by importance sampling must match a direct
// quadrature of eval).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pbrkit/core/color.h"
#include "pbrkit/core/equirect.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/environment_sampler.h"
#include "support/chi2.h"
#include "support/test_paths.h"

namespace pbrkit::test {
namespace {

// Bins in the map's own (u, v) of world directions, 64 x 32: each bin holds 8 x 8 texels
// of the 512 x 256 map, so the expected count (the pdf integrated over the bin, one point
// per texel, where pdf x sin(theta) is constant) is exact.
void chi2_test(float rotation) {
  const Environment env = Environment::load(shared_asset("hdri/studio.exr"), rotation, 1.0f);
  ASSERT_EQ(env.map.width, 512);
  const EnvironmentSampler sampler(env);
  const int nu = 64, nv = 32, sub = 8;
  const std::size_t samples = 1000000;
  std::vector<double> observed(std::size_t(nu) * nv, 0.0), expected(observed.size(), 0.0);
  Pcg32 rng(3);
  auto bin_of = [&](glm::vec3 d) {
    // World u,v (rotation 0 convention): bins rotate rigidly with the map for multiples
    // of 360/64 degrees, which the rotations used here are.
    const glm::vec2 uv = equirect_uv(d);
    const int i = std::min(int(uv.x * float(nu)), nu - 1);
    const int j = std::min(int(uv.y * float(nv)), nv - 1);
    return std::size_t(j) * nu + i;
  };
  for (std::size_t k = 0; k < samples; ++k) {
    const EnvironmentSampler::Sample s = sampler.sample(rng.next_2d());
    if (s.pdf > 0.0f) observed[bin_of(s.direction)] += 1.0;
  }
  double total_p = 0.0;
  for (int j = 0; j < nv * sub; ++j)
    for (int i = 0; i < nu * sub; ++i) {
      const glm::vec2 uv((float(i) + 0.5f) / float(nu * sub), (float(j) + 0.5f) / float(nv * sub));
      const glm::vec3 d = equirect_direction(uv);
      const double sin_theta = std::sin(kPi * double(uv.y));
      // dOmega = 2 pi^2 sin(theta) du dv
      const double p = sampler.pdf(d) * 2.0 * kPi * kPi * sin_theta / (double(nu * sub) * nv * sub);
      expected[bin_of(d)] += p * double(samples);
      total_p += p;
    }
  EXPECT_NEAR(total_p, 1.0, 1e-3);  // the pdf integrates to 1
  // Pool bins with expected counts below 5 (standard chi-square practice).
  const PooledChi2 c = pooled_chi2(observed, expected);
  const double stat = c.statistic;
  const int dof = c.degrees_of_freedom;
  if (!c.pooled_counted) {
    EXPECT_LT(c.pooled_observed, 5.0 + 5.0 * std::sqrt(5.0));  // nothing where the pdf is ~0
  }
  const double p_value = chi2_survival(stat, dof);
  // Two rotations are tested: Sidak-corrected 1% significance.
  EXPECT_GT(p_value, 1.0 - std::pow(0.99, 0.5)) << "chi2 " << stat << " dof " << dof;
}

TEST(EnvironmentSampler, ChiSquareOnStudioHdri) {
  chi2_test(0.0f);
}
TEST(EnvironmentSampler, ChiSquareOnRotatedStudioHdri) {
  chi2_test(90.0f);
}

// Importance-sampled estimate of the irradiance-like integral of eval over the sphere
// against a dense quadrature of eval itself: fails if the pdf's orientation or rotation
// disagrees with eval's (the estimate would then be badly off and noisy).
TEST(EnvironmentSampler, ConsistentWithEvalOrientationAndRotation) {
  for (float rotation : {0.0f, 37.0f}) {
    const Environment env = Environment::load(shared_asset("hdri/sunset.exr"), rotation, 2.0f);
    const EnvironmentSampler sampler(env);
    // Weighted by a lobe around +X so that orientation matters.
    auto weight = [](glm::vec3 d) { return std::pow(std::max(0.0f, d.x), 4.0f); };
    double quad = 0.0;
    const int nu = 1024, nv = 512;
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        const glm::vec2 uv((i + 0.5f) / nu, (j + 0.5f) / nv);
        const glm::vec3 d = equirect_direction(uv);
        quad += luminance(env.eval(d)) * weight(d) * 2.0 * kPi * kPi *
                std::sin(kPi * double(uv.y)) / (double(nu) * nv);
      }
    Pcg32 rng(11);
    const int n = 200000;
    double sum = 0.0, sum2 = 0.0;
    int mismatches = 0;
    for (int k = 0; k < n; ++k) {
      const EnvironmentSampler::Sample s = sampler.sample(rng.next_2d());
      double v = 0.0;
      if (s.pdf > 0.0f) {
        // pdf() agrees with sample()'s density except where float rounding of the
        // direction crosses a texel edge (a set of measure zero).
        if (std::fabs(s.pdf - sampler.pdf(s.direction)) > 1e-3f * s.pdf) ++mismatches;
        v = luminance(s.radiance) * weight(s.direction) / s.pdf;
      }
      sum += v;
      sum2 += v * v;
    }
    EXPECT_LT(mismatches, n / 1000);
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, quad, 4.0 * se + 2e-3 * quad) << "rotation " << rotation;
  }
}

// The sampler's own lookup (padded texels, precomputed rotation, fast_atan2) against
// Environment::eval: the same bilinear radiance up to the rounding of the direction's
// map coordinates (fast_atan2 is within 4e-7 rad of libm, 3e-5 of a texel here), also at
// the poles, on the seam and with the map rotated.
TEST(EnvironmentSampler, EvalMatchesEnvironmentEval) {
  for (float rotation : {0.0f, 37.0f, -90.0f}) {
    const Environment env = Environment::load(shared_asset("hdri/studio.exr"), rotation, 1.5f);
    const EnvironmentSampler sampler(env);
    float peak = 0.0f;
    for (float c : env.map.data) peak = std::max(peak, c * env.intensity);
    std::vector<glm::vec3> dirs = {{0, 1, 0},  {0, -1, 0}, {0, 0, 1},     {0, 0, -1},    {1, 0, 0},
                                   {-1, 0, 0}, {0, 0, 1},  {1e-7f, 0, 1}, {-1e-7f, 0, 1}};
    Pcg32 rng(12);
    for (int i = 0; i < 200000; ++i) dirs.push_back(sample_uniform_sphere(rng.next_2d()).direction);
    double sum_rel = 0.0;
    for (const glm::vec3& d0 : dirs) {
      const glm::vec3 d = glm::normalize(d0);
      const glm::vec3 a = sampler.eval(d), b = env.eval(d);
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(a[c], b[c], 1e-4f * peak) << "rotation " << rotation;
        sum_rel += std::fabs(a[c] - b[c]) / (std::fabs(b[c]) + 1e-3);
      }
    }
    EXPECT_LT(sum_rel / (3.0 * double(dirs.size())), 1e-5) << "rotation " << rotation;
  }
}

}  // namespace
}  // namespace pbrkit::test
