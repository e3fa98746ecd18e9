// Path guiding (pt/guiding.h, PathTracerSettings::guiding): the guide's directional
// distribution samples what its pdf says (chi-square, as every sampler in tests/core/);
// guided renders converge to the unguided image (per-block z-test from the half buffers);
// and a guided render is the same bits whatever the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/pt/guiding.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"
#include "support/chi2.h"

namespace pbrkit::test {
namespace {

// A distribution learned the way a render learns one: two passes of records of a radiance
// with a bright spot, a dimmer broad lobe and a floor (uniformly drawn directions, each
// recorded as L / p, p = 1 / 4 pi), the second recorded into the topology the first refined.
DirectionalQuadtree learned_distribution() {
  Bounds b;
  b.extend(glm::vec3(-1.0f));
  b.extend(glm::vec3(1.0f));
  GuideOptions options;
  options.c = 1e12;  // one region: the records all go to it
  PathGuide guide(b, options);
  const glm::vec3 spot = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
  const glm::vec3 lobe = glm::normalize(glm::vec3(-0.7f, 0.6f, -0.2f));
  auto radiance = [&](glm::vec3 w) {
    const float cs = glm::dot(w, spot), cl = glm::dot(w, lobe);
    return 0.05f + (cs > 0.995f ? 200.0f : 0.0f) + 3.0f * std::pow(std::max(cl, 0.0f), 8.0f);
  };
  Pcg32 rng(5);
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < 400000; ++i) {
      const glm::vec3 w =
          sample_uniform_sphere(glm::vec2(rng.next_float(), rng.next_float())).direction;
      guide.record(0, w, radiance(w) * 4.0f * kPi);
    }
    guide.end_pass();
  }
  return guide.distribution(guide.region_at(glm::vec3(0.0f)));
}

TEST(PathGuiding, QuadtreeIsRefinedWhereTheEnergyIs) {
  const DirectionalQuadtree d = learned_distribution();
  EXPECT_GT(d.total(), 0.0f);
  // The spot (about 0.25% of the sphere, half the energy) needs several levels.
  EXPECT_GT(d.nodes.size(), 20u);
  // The pdf follows the radiance: the spot's direction far above the floor's.
  const glm::vec3 spot = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
  EXPECT_GT(d.pdf(spot), 20.0f * d.pdf(glm::vec3(0.0f, 0.0f, -1.0f)));
}

// The probability of the square's rectangle [x0, x1) x [y0, y1) under the quadtree's
// pdf, exactly: the pdf is constant on each leaf (over the square, 4 pi times the pdf over
// solid angle), so the integral is a sum of leaf densities times overlaps.
double exact_probability(const DirectionalQuadtree& d, std::uint32_t n, glm::dvec2 origin,
                         double size, double density, glm::dvec2 lo, glm::dvec2 hi) {
  const DirectionalQuadtree::Node& node = d.nodes[n];
  const double total = (double(node.sum[0]) + node.sum[1]) + (double(node.sum[2]) + node.sum[3]);
  double p = 0.0;
  for (int q = 0; q < 4; ++q) {
    const double half = size * 0.5;
    const glm::dvec2 o = origin + glm::dvec2(q & 1, q >> 1) * half;
    const glm::dvec2 a = glm::max(o, lo), b = glm::min(o + half, hi);
    if (!(a.x < b.x && a.y < b.y) || node.sum[q] <= 0.0f) continue;
    const double dq = density * 4.0 * double(node.sum[q]) / total;
    if (node.child[q])
      p += exact_probability(d, node.child[q], o, half, dq, lo, hi);
    else
      p += dq * (b.x - a.x) * (b.y - a.y);
  }
  return p;
}

// Chi-square of sample() against pdf() (pbrt-v4's and Mitsuba's construction: >= 1e6
// samples binned, expected counts from the pdf, cells expected below 5 pooled), over bins
// uniform in (cos theta, phi) (the harness of tests/support/chi2.h bins in theta and
// integrates numerically, which smears the quadtree's discontinuities; here each bin is a
// rectangle of the square and its expected count exact).
TEST(PathGuiding, QuadtreeSamplesMatchItsPdf) {
  const DirectionalQuadtree d = learned_distribution();
  constexpr int kBins = 64;
  constexpr std::size_t kSamples = 2000000;
  std::vector<double> observed(kBins * kBins, 0.0), expected(kBins * kBins, 0.0);
  double integral = 0.0;
  for (int j = 0; j < kBins; ++j)
    for (int i = 0; i < kBins; ++i) {
      const glm::dvec2 lo(double(i) / kBins, double(j) / kBins);
      const double p = exact_probability(d, 0, glm::dvec2(0.0), 1.0, 1.0, lo, lo + 1.0 / kBins);
      expected[std::size_t(j * kBins + i)] = p * double(kSamples);
      integral += p;
    }
  EXPECT_NEAR(integral, 1.0, 1e-6);
  Pcg32 rng(11);
  std::size_t mismatched_pdf = 0;
  for (std::size_t k = 0; k < kSamples; ++k) {
    float pdf = 0.0f;
    const glm::vec3 w = d.sample(glm::vec2(rng.next_float(), rng.next_float()), pdf);
    // The pdf sample() returns is pdf()'s for the direction (up to rounding at leaf edges).
    if (std::abs(pdf - d.pdf(w)) > 1e-3f * pdf) ++mismatched_pdf;
    const glm::vec2 p = direction_to_square(w);
    const int i = std::min(int(p.x * kBins), kBins - 1), j = std::min(int(p.y * kBins), kBins - 1);
    observed[std::size_t(j * kBins + i)] += 1.0;
  }
  EXPECT_LT(mismatched_pdf, kSamples / 10000);
  const PooledChi2 c = pooled_chi2(observed, expected);
  const double p_value = chi2_survival(c.statistic, c.degrees_of_freedom);
  EXPECT_GT(p_value, 0.01) << "chi2 " << c.statistic << " over " << c.degrees_of_freedom
                           << " degrees of freedom";
  EXPECT_LT(c.pooled_observed, 10.0);
  // Over solid angle: the pdf integrates to 1 on the sphere (4 pi x the square's mean).
  double mean = 0.0;
  for (int j = 0; j < 256; ++j)
    for (int i = 0; i < 256; ++i)
      mean += d.pdf(square_to_direction(glm::vec2((i + 0.5f) / 256.0f, (j + 0.5f) / 256.0f)));
  EXPECT_NEAR(mean / (256.0 * 256.0) * 4.0 * kPi, 1.0, 0.02);
}

TEST(PathGuiding, CylindricalMapRoundTrips) {
  Pcg32 rng(9);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec2 p(rng.next_float(), rng.next_float());
    const glm::vec2 q = direction_to_square(square_to_direction(p));
    EXPECT_NEAR(q.x, p.x, 1e-5f);
    EXPECT_NEAR(std::min(std::abs(q.y - p.y), 1.0f - std::abs(q.y - p.y)), 0.0f, 1e-4f);
  }
}

TEST(PathGuiding, ParsesItsNames) {
  EXPECT_EQ(parse_guiding("on"), Guiding::kOn);
  EXPECT_EQ(parse_guiding("off"), Guiding::kOff);
  EXPECT_EQ(guiding_name(Guiding::kOn), "on");
  EXPECT_THROW(parse_guiding("yes"), Error);
  EXPECT_EQ(PathTracerSettings{}.guiding, Guiding::kOff);
}

struct Render {
  PathTracerResult result;
  int width = 0, height = 0;
};

Render render_builtin(const std::string& name, int width, std::uint32_t spp, Guiding guiding,
                      std::uint32_t seed, int threads = 0, float bsdf_fraction = -1.0f) {
  const Scene scene = builtin_scene(name);
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  const RenderView view = select_view(scene, std::nullopt, width, std::nullopt);
  PathTracerSettings s;
  s.width = view.size.width;
  s.height = view.size.height;
  s.spp = spp;
  s.noise_threshold = 0.0f;
  s.guiding = guiding;
  s.guiding_bsdf_fraction = bsdf_fraction;
  s.seed = seed;
  s.threads = threads;
  return {render_path(scene, &env, view.camera, s), s.width, s.height};
}

// Per block of 4 x 4 pixels, z = (mean_a - mean_b) / sqrt(var_a + var_b), the variances of
// the block means from each pixel's two half buffers (var(mean) ~ (E - O)^2 / 4), as
// light_sampler_test does for its two samplers; independent renders (different seeds).
// A wrong MIS weight or pdf moves whole regions by many sigma.
void expect_equal_within_noise(const Render& a, const Render& b, const std::string& what) {
  ASSERT_EQ(a.width, b.width);
  const int block = 4, nbx = a.width / block, nby = a.height / block;
  auto block_stats = [&](const Film& film, int bx, int by, double& mean, double& var) {
    mean = var = 0.0;
    for (int y = by * block; y < (by + 1) * block; ++y)
      for (int x = bx * block; x < (bx + 1) * block; ++x) {
        const std::size_t i = std::size_t(y) * std::size_t(a.width) + std::size_t(x);
        const double n = film.count[i];
        const glm::dvec3 sum(film.sum[i]), even(film.sum_even[i]);
        const double s = sum.x + sum.y + sum.z, e = even.x + even.y + even.z;
        mean += s / n;
        var += 0.25 * (e / (n / 2) - (s - e) / (n / 2)) * (e / (n / 2) - (s - e) / (n / 2));
      }
    const double k = double(block * block);
    mean /= k;
    var /= k * k;
  };
  double z2 = 0.0, worst = 0.0, mean_a = 0.0, mean_b = 0.0, var_a = 0.0, var_b = 0.0;
  int blocks = 0;
  for (int by = 0; by < nby; ++by)
    for (int bx = 0; bx < nbx; ++bx) {
      double ma, va, mb, vb;
      block_stats(a.result.film, bx, by, ma, va);
      block_stats(b.result.film, bx, by, mb, vb);
      mean_a += ma;
      mean_b += mb;
      var_a += va;
      var_b += vb;
      if (!(va + vb > 0.0)) continue;  // e.g. the black background
      const double z = (ma - mb) / std::sqrt(va + vb);
      z2 += z * z;
      worst = std::max(worst, std::fabs(z));
      ++blocks;
    }
  ASSERT_GT(blocks, 0) << what;
  EXPECT_GT(mean_a, 0.0) << what;
  // sum z^2 ~ chi-square with `blocks` degrees of freedom (a little wider: each variance is
  // itself estimated from 16 pixels).
  EXPECT_GT(chi2_survival(z2, blocks), 1e-3) << what << ": sum z^2 " << z2 << " over " << blocks;
  EXPECT_LT(worst, 5.5) << what;
  // And the whole image's mean, within 4 of its standard errors.
  const double z_mean = (mean_a - mean_b) / std::sqrt(var_a + var_b);
  EXPECT_LT(std::fabs(z_mean), 4.0) << what << ": means " << mean_a << ", " << mean_b;
}

// Guided and unguided renders agree within their noise: the sunlit interior (what guiding
// is for), the Cornell box (an area light, found by light sampling and by guided bounces,
// whose MIS weights must use the mixture's pdf) and the sphere grid (glossy metals and
// dielectrics: the BSDF's half of the mixture at rough vertices, no guiding at smooth ones),
// with the BSDF share fixed at one half (at these sizes the learned share keeps the guide
// off in most regions, which would test little); and the interior with the learned share.
TEST(PathGuiding, GuidedRendersEqualUnguidedWithinNoise) {
  for (const auto& [name, width, spp, share] :
       {std::tuple{"interior", 32, 255u, 0.5f}, std::tuple{"cornell", 32, 127u, 0.5f},
        std::tuple{"spheres", 48, 63u, 0.5f}, std::tuple{"interior", 64, 127u, -1.0f}}) {
    const Render off = render_builtin(name, width, spp, Guiding::kOff, 1);
    const Render on = render_builtin(name, width, spp, Guiding::kOn, 2, 0, share);
    // The guide did learn and sample (passes 1, 2, 4, ...: one fewer than its passes).
    EXPECT_GE(on.result.stats.guide_passes, 5) << name;
    EXPECT_GT(on.result.stats.guide_nodes, on.result.stats.guide_regions) << name;
    EXPECT_GT(on.result.stats.guide_guided_regions, 0u) << name;
    expect_equal_within_noise(on, off, name);
  }
}

// The BSDF share of a region is the candidate of the least estimated second moment: where
// the integrand follows the guide's pdf the smallest share (0.2), where it follows the
// BSDF's, 1 (by Cauchy-Schwarz the integral of F^2 / p is least for p proportional to F).
// Two kinds of direction, 50 samples each, drawn from the half-half mixture.
TEST(PathGuiding, BsdfShareFollowsTheIntegrand) {
  Bounds b;
  b.extend(glm::vec3(-1.0f));
  b.extend(glm::vec3(1.0f));
  for (const bool follows_guide : {true, false}) {
    PathGuide guide(b);
    EXPECT_EQ(guide.bsdf_fraction(0), PathGuide::kInitialBsdfFraction);
    for (int i = 0; i < 50; ++i)
      for (const auto& [p_bsdf, p_guide] : {std::pair{2.0f, 0.1f}, std::pair{0.1f, 2.0f}})
        guide.record_fraction(0, follows_guide ? p_guide : p_bsdf, p_bsdf, p_guide,
                              0.5f * (p_bsdf + p_guide));
    guide.end_pass();
    EXPECT_EQ(guide.bsdf_fraction(0), follows_guide ? 0.2f : 1.0f) << follows_guide;
  }
  // Too few samples keep the share; a fixed share is kept whatever the samples say.
  PathGuide few(b);
  for (int i = 0; i < 10; ++i) few.record_fraction(0, 2.0f, 0.1f, 2.0f, 1.05f);
  few.end_pass();
  EXPECT_EQ(few.bsdf_fraction(0), PathGuide::kInitialBsdfFraction);
  GuideOptions fixed;
  fixed.fixed_bsdf_fraction = 0.5f;
  PathGuide held(b, fixed);
  for (int i = 0; i < 100; ++i) held.record_fraction(0, 0.1f, 2.0f, 0.1f, 1.05f);
  held.end_pass();
  EXPECT_EQ(held.bsdf_fraction(0), 0.5f);
  for (const float bad : {1.5f, 0.0f, std::nanf("")}) {
    fixed.fixed_bsdf_fraction = bad;
    EXPECT_THROW(PathGuide(b, fixed), Error) << bad;
  }
}

// The sum over pixels of the variance of each pixel's mean, from its two half buffers
// (var(mean) ~ (E - O)^2 / 4 per channel, summed over the channels).
double variance_of_means(const Render& r) {
  const Film& film = r.result.film;
  double total = 0.0;
  for (std::size_t i = 0; i < film.count.size(); ++i) {
    const double n = film.count[i];
    if (!(n >= 2.0)) continue;
    const glm::dvec3 sum(film.sum[i]), even(film.sum_even[i]);
    const glm::dvec3 d = even / (n / 2) - (sum - even) / (n / 2);
    total += 0.25 * (d.x * d.x + d.y * d.y + d.z * d.z);
  }
  return total;
}

// Guiding must not fill a scene with rough glass with fireflies. Paths inside a rough glass
// sphere reflect internally along directions the guide thinks dark, and drawn from the
// mixture each such bounce doubles the path's weight: with rough glass guided, the sum of
// the pixels' variances was 16.5 times the unguided one here; with transmissive
// dielectrics unguided, 1.43 times (the learning passes' cost on this scene; 3 allows for it).
TEST(PathGuiding, RoughGlassMakesNoFireflies) {
  const Render off = render_builtin("glass", 96, 255, Guiding::kOff, 1);
  const Render on = render_builtin("glass", 96, 255, Guiding::kOn, 2);
  expect_equal_within_noise(on, off, "glass");
  const double v_off = variance_of_means(off), v_on = variance_of_means(on);
  EXPECT_LT(v_on, 3.0 * v_off) << "variance guided " << v_on << ", unguided " << v_off;
}

bool same_bits(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

// A guided render split into sample ranges learns one guide per part (README: the parts'
// bits differ from an uninterrupted render's), and a resumed one learns afresh from where
// it resumes; both stay unbiased: merged parts and a resumed render equal an unguided
// render within noise, and resuming the same checkpoint twice gives the same bits.
TEST(PathGuiding, PartsAndResumesKeepTheMean) {
  const Scene scene = builtin_scene("interior");
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  const RenderView view = select_view(scene, std::nullopt, 32, std::nullopt);
  PathTracerSettings s;
  s.width = view.size.width;
  s.height = view.size.height;
  s.spp = 255;
  s.noise_threshold = 0.0f;
  s.guiding = Guiding::kOn;
  s.guiding_bsdf_fraction = 0.5f;  // so that the small render does guide
  s.seed = 4;
  Render merged{{}, s.width, s.height};
  for (auto [begin, end] : {std::pair{0u, 100u}, std::pair{100u, 255u}}) {
    PathTracerSettings part = s;
    part.sample_begin = begin;
    part.sample_end = end;
    PathTracerResult r = render_path(scene, &env, view.camera, part);
    EXPECT_GT(r.stats.guide_guided_regions, 0u);
    if (merged.result.film.width == 0)
      merged.result.film = std::move(r.film);
    else
      merged.result.film.merge(r.film);
  }
  const Render off = render_builtin("interior", 32, 255, Guiding::kOff, 1);
  expect_equal_within_noise(merged, off, "parts");

  // A checkpoint after the first passes, resumed twice.
  Film saved;
  PathTracerSettings c = s;
  c.checkpoint_interval = 1e-9;
  c.checkpoint = [&](const Film& film) {
    if (saved.width == 0 && film.count[0] >= 7.0f) saved = film;
  };
  render_path(scene, &env, view.camera, c);
  ASSERT_GT(saved.width, 0);
  ASSERT_LT(saved.count[0], 255.0f);
  PathTracerSettings r = s;
  r.resume = &saved;
  const Render a{render_path(scene, &env, view.camera, r), s.width, s.height};
  const Render b{render_path(scene, &env, view.camera, r), s.width, s.height};
  EXPECT_TRUE(same_bits(a.result.film.sum, b.result.film.sum));
  expect_equal_within_noise(a, off, "resumed");
}

// The records of a pass are summed with integer atomics and the guide built between passes
// in a fixed order: one thread and two give the same bits; and guiding does change them.
TEST(PathGuiding, OneThreadEqualsTwoThreads) {
  const Render a = render_builtin("interior", 64, 127, Guiding::kOn, 3, 1);
  const Render b = render_builtin("interior", 64, 127, Guiding::kOn, 3, 2);
  EXPECT_TRUE(same_bits(a.result.film.sum, b.result.film.sum));
  EXPECT_TRUE(same_bits(a.result.film.sum_even, b.result.film.sum_even));
  EXPECT_EQ(a.result.stats.guide_nodes, b.result.stats.guide_nodes);
  const Render off = render_builtin("interior", 64, 127, Guiding::kOff, 3, 2);
  EXPECT_FALSE(same_bits(a.result.film.sum, off.result.film.sum));
}

}  // namespace
}  // namespace pbrkit::test
