// Chi-square goodness-of-fit test for direction samplers (see chi2.h). The structure
// follows Mitsuba 3's ChiSquareTest (python/mitsuba/chi2.py) and pbrt-v4's
// bsdfs_test.cpp: histogram of samples, expected frequencies from the integrated pdf,
// pooling of cells with expected counts below 5, and a chi-square p-value compared with a
// Sidak-corrected significance level.
#include "support/chi2.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "pbrkit/core/sampling.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

glm::vec3 direction(double theta, double phi) {
  const double s = std::sin(theta);
  return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(std::cos(theta)));
}

// 3-point Gauss-Legendre on [-1, 1] (exact for polynomials of degree 5).
constexpr std::array<double, 3> kGlNodes = {-0.77459666924148337704, 0.0, 0.77459666924148337704};
constexpr std::array<double, 3> kGlWeights = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

struct Cubature {
  const std::function<double(glm::vec3)>& pdf;
  double tolerance_per_area;  // absolute tolerance per unit of (theta, phi) area
  int max_depth;

  // Integral of pdf(w(theta, phi)) sin(theta) over [t0, t1] x [p0, p1] by tensor GL.
  double rule(double t0, double t1, double p0, double p1) const {
    const double tc = 0.5 * (t0 + t1), th = 0.5 * (t1 - t0);
    const double pc = 0.5 * (p0 + p1), ph = 0.5 * (p1 - p0);
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double t = tc + th * kGlNodes[i];
      const double st = std::sin(t);
      for (int j = 0; j < 3; ++j) {
        const double p = pc + ph * kGlNodes[j];
        sum += kGlWeights[i] * kGlWeights[j] * pdf(direction(t, p)) * st;
      }
    }
    return sum * th * ph;
  }

  double adapt(double t0, double t1, double p0, double p1, double whole, int depth) const {
    const double tm = 0.5 * (t0 + t1), pm = 0.5 * (p0 + p1);
    const double c[4] = {rule(t0, tm, p0, pm), rule(tm, t1, p0, pm), rule(t0, tm, pm, p1),
                         rule(tm, t1, pm, p1)};
    const double sum = c[0] + c[1] + c[2] + c[3];
    // Absolute tolerance in proportion to the cell's area, or a relative one. |sum - whole|
    // estimates the error of the coarse rule; the degree-5 rule's error on the accepted
    // four-cell sum is far smaller (measured: a GGX lobe at alpha = 0.0025 integrates to
    // 1 within 4e-7), well below the sqrt(expected)/samples that the test can resolve.
    constexpr double kRelative = 1e-4;
    const double tol =
        std::max(tolerance_per_area * (t1 - t0) * (p1 - p0), kRelative * std::abs(sum));
    if (depth >= max_depth || std::abs(sum - whole) <= tol) return sum;
    return adapt(t0, tm, p0, pm, c[0], depth + 1) + adapt(tm, t1, p0, pm, c[1], depth + 1) +
           adapt(t0, tm, pm, p1, c[2], depth + 1) + adapt(tm, t1, pm, p1, c[3], depth + 1);
  }

  double bin(double t0, double t1, double p0, double p1, int resolution) const {
    double sum = 0.0;
    const double dt = (t1 - t0) / resolution, dp = (p1 - p0) / resolution;
    for (int i = 0; i < resolution; ++i)
      for (int j = 0; j < resolution; ++j) {
        const double a0 = t0 + i * dt, a1 = i + 1 == resolution ? t1 : a0 + dt;
        const double b0 = p0 + j * dp, b1 = j + 1 == resolution ? p1 : b0 + dp;
        sum += adapt(a0, a1, b0, b1, rule(a0, a1, b0, b1), 0);
      }
    return sum;
  }
};

// Regularised lower incomplete gamma P(a, x) by its series (x < a + 1) and upper Q(a, x)
// by Lentz's continued fraction otherwise (Numerical Recipes, 3rd ed., section 6.2).
double gamma_p_series(double a, double x) {
  double ap = a, del = 1.0 / a, sum = del;
  for (int n = 0; n < 10000; ++n) {
    ap += 1.0;
    del *= x / ap;
    sum += del;
    if (std::abs(del) < std::abs(sum) * 1e-16) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

double gamma_q_fraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

PooledChi2 pooled_chi2(const std::vector<double>& observed, const std::vector<double>& expected) {
  PooledChi2 r;
  for (std::size_t b = 0; b < observed.size(); ++b) {
    if (expected[b] < 5.0) {
      r.pooled_observed += observed[b];
      r.pooled_expected += expected[b];
      continue;
    }
    r.statistic += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
    ++r.degrees_of_freedom;
  }
  if (r.pooled_expected >= 5.0) {
    r.statistic += (r.pooled_observed - r.pooled_expected) *
                   (r.pooled_observed - r.pooled_expected) / r.pooled_expected;
    ++r.degrees_of_freedom;
    r.pooled_counted = true;
  }
  return r;
}

double chi2_survival(double statistic, int dof) {
  if (dof <= 0) return 1.0;
  if (!(statistic > 0.0)) return 1.0;
  const double a = 0.5 * dof, x = 0.5 * statistic;
  if (x < a + 1.0) return 1.0 - gamma_p_series(a, x);
  return gamma_q_fraction(a, x);
}

std::vector<double> integrate_pdf_over_bins(const std::function<double(glm::vec3)>& pdf,
                                            const Chi2Options& options) {
  const int nt = options.theta_bins, np = options.phi_bins;
  const Cubature cubature{pdf, options.integration_tolerance / (2.0 * kPi * kPi),
                          options.integration_max_depth};
  std::vector<double> integral(std::size_t(nt) * np);
  pbrkit::parallel_for(0, nt * np, [&](int k) {
    const int i = k / np, j = k % np;
    const double t0 = kPi * i / nt, t1 = kPi * (i + 1) / nt;
    const double p0 = 2.0 * kPi * j / np, p1 = 2.0 * kPi * (j + 1) / np;
    integral[std::size_t(k)] = cubature.bin(t0, t1, p0, p1, options.integration_resolution);
  });
  return integral;
}

Chi2Result chi2_sphere_test(const std::function<std::optional<glm::vec3>(float, glm::vec2)>& sample,
                            const std::function<double(glm::vec3)>& pdf,
                            const Chi2Options& options) {
  const int nt = options.theta_bins, np = options.phi_bins;
  const std::size_t cells = std::size_t(nt) * np;
  Chi2Result result;

  // 1. Histogram. Fixed chunks with one PCG32 stream each: deterministic for any thread
  //    count. The last two slots count rejected and malformed samples.
  constexpr std::size_t kChunk = 1 << 15;
  const std::size_t chunks = (options.samples + kChunk - 1) / kChunk;
  std::vector<std::vector<std::uint64_t>> partial(chunks);
  pbrkit::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    auto& hist = partial[c];
    hist.assign(cells + 2, 0);
    Pcg32 rng(options.seed, c);
    const std::size_t end = std::min(options.samples, (c + 1) * kChunk);
    for (std::size_t s = c * kChunk; s < end; ++s) {
      const float u_lobe = rng.next_float();
      const glm::vec2 u = rng.next_2d();
      const std::optional<glm::vec3> w = sample(u_lobe, u);
      if (!w) {
        ++hist[cells];
        continue;
      }
      const glm::dvec3 d(*w);
      const double len = glm::length(d);
      if (!std::isfinite(len) || std::abs(len - 1.0) > 1e-3) {
        ++hist[cells + 1];
        continue;
      }
      // atan2 rather than acos(z): accurate near the poles, where sharp lobes live.
      const double theta = std::atan2(std::hypot(d.x, d.y), d.z);
      double phi = std::atan2(d.y, d.x);
      if (phi < 0.0) phi += 2.0 * kPi;
      // Theta bins are (t0, t1]: a hemisphere sampler may return a direction exactly on
      // the horizon (z = 0, a set of measure zero), which belongs with the upper half.
      const int i = std::clamp(int(std::ceil(theta / kPi * nt)) - 1, 0, nt - 1);
      const int j = std::min(int(phi / (2.0 * kPi) * np), np - 1);
      ++hist[std::size_t(i) * np + j];
    }
  });
  std::vector<std::uint64_t> observed(cells + 2, 0);
  for (const auto& hist : partial)
    for (std::size_t k = 0; k < hist.size(); ++k) observed[k] += hist[k];
  result.rejected = observed[cells];
  const std::uint64_t malformed = observed[cells + 1];

  // 2. Expected frequencies from the integrated pdf; the rejected samples are one more
  //    cell holding the pdf's missing mass.
  const std::vector<double> integral = integrate_pdf_over_bins(pdf, options);
  result.pdf_integral = std::accumulate(integral.begin(), integral.end(), 0.0);
  const double n = double(options.samples);
  std::vector<double> expected(cells + 1);
  for (std::size_t k = 0; k < cells; ++k) expected[k] = n * integral[k];
  expected[cells] = std::max(0.0, n * (1.0 - result.pdf_integral));

  result.threshold = 1.0 - std::pow(1.0 - options.significance, 1.0 / options.runs);
  std::string report = fmt::format("pdf integral {:.6f}, {} rejected samples of {}\n",
                                   result.pdf_integral, result.rejected, options.samples);
  if (malformed > 0) {
    result.report = report + fmt::format("{} samples were not unit vectors\n", malformed);
    return result;
  }

  // 3. Pool cells with expected counts below 5 (Mitsuba's chi2.py): visit cells by
  //    increasing expectation; small ones go into the pool, and while the pool is still
  //    below 5 the next cells join it too.
  std::vector<std::size_t> order(cells + 1);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
  double statistic = 0.0, pool_observed = 0.0, pool_expected = 0.0;
  int dof = 0, pooled = 0;
  for (const std::size_t k : order) {
    const double o = double(observed[k]), e = expected[k];
    if (e <= 0.0) {
      if (o > 0.0) {
        const int i = int(k) / np, j = int(k) % np;
        result.report =
            report + (k == cells ? fmt::format("{} samples rejected but the pdf integrates to 1\n",
                                               observed[k])
                                 : fmt::format("{} samples in bin (theta {}, phi {}) whose "
                                               "integrated pdf is 0\n",
                                               observed[k], i, j));
        return result;
      }
      continue;
    }
    if (e < 5.0 || (pool_expected > 0.0 && pool_expected < 5.0)) {
      pool_observed += o;
      pool_expected += e;
      ++pooled;
    } else {
      statistic += (o - e) * (o - e) / e;
      ++dof;
    }
  }
  if (pool_expected > 0.0) {
    statistic += (pool_observed - pool_expected) * (pool_observed - pool_expected) / pool_expected;
    ++dof;
  }
  dof -= 1;
  result.statistic = statistic;
  result.degrees_of_freedom = dof;
  result.p_value = chi2_survival(statistic, dof);
  result.passed = result.p_value >= result.threshold;

  report += fmt::format("chi2 = {:.2f}, dof = {}, p = {:.4g} (threshold {:.4g}), {} cells pooled\n",
                        statistic, dof, result.p_value, result.threshold, pooled);
  // The worst cells, to make a failure readable.
  std::vector<std::size_t> worst(cells);
  std::iota(worst.begin(), worst.end(), 0);
  auto contribution = [&](std::size_t k) {
    const double e = std::max(expected[k], 1e-12), o = double(observed[k]);
    return (o - e) * (o - e) / e;
  };
  std::sort(worst.begin(), worst.end(),
            [&](std::size_t a, std::size_t b) { return contribution(a) > contribution(b); });
  for (std::size_t w = 0; w < std::min<std::size_t>(5, worst.size()); ++w) {
    const std::size_t k = worst[w];
    report += fmt::format("  bin (theta {}, phi {}): observed {}, expected {:.1f}\n", int(k) / np,
                          int(k) % np, observed[k], expected[k]);
  }
  report +=
      fmt::format("  rejected: observed {}, expected {:.1f}\n", observed[cells], expected[cells]);
  result.report = report;
  return result;
}

double integrate_over_sphere(const std::function<double(glm::vec3)>& f, double tolerance) {
  Chi2Options options;
  options.theta_bins = 2;
  options.phi_bins = 2;
  options.integration_tolerance = tolerance;
  // A near-mirror lobe at grazing incidence (roughness 0.05, mu = 0.05) is ~1e-3 rad wide
  // in theta: finer start cells and deeper refinement than the chi-square bins need
  // (measured: converged to 1e-6 from resolution 16, depth 10 on).
  options.integration_resolution = 16;
  options.integration_max_depth = 11;
  const std::vector<double> bins = integrate_pdf_over_bins(f, options);
  return std::accumulate(bins.begin(), bins.end(), 0.0);
}

double adaptive_simpson(const std::function<double(double)>& f, double a, double b, double eps,
                        int max_depth) {
  struct Rec {
    const std::function<double(double)>& f;
    double step(double a, double b, double fa, double fm, double fb, double whole, double eps,
                int depth) const {
      const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
      const double flm = f(lm), frm = f(rm);
      const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
      const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
      const double delta = left + right - whole;
      if (depth <= 0 || std::abs(delta) <= 15.0 * eps) return left + right + delta / 15.0;
      return step(a, m, fa, flm, fm, left, 0.5 * eps, depth - 1) +
             step(m, b, fm, frm, fb, right, 0.5 * eps, depth - 1);
    }
  };
  const Rec rec{f};
  // Start from 16 panels so that a narrow feature is not skipped by the first estimate.
  constexpr int kPanels = 16;
  double sum = 0.0;
  for (int p = 0; p < kPanels; ++p) {
    const double x0 = a + (b - a) * p / kPanels, x1 = a + (b - a) * (p + 1) / kPanels;
    const double f0 = f(x0), f1 = f(x1), fm = f(0.5 * (x0 + x1));
    sum += rec.step(x0, x1, f0, fm, f1, (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1), eps / kPanels,
                    max_depth);
  }
  return sum;
}

}  // namespace pbrkit::test
