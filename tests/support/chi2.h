#pragma once
// Chi-square goodness-of-fit test of a direction sampler against its pdf, in the style of
// pbrt-v4's bsdfs_test.cpp and Mitsuba 3's chi2.py: bin >= 1e6 samples over
// (theta, phi) of the sphere, integrate the pdf over each bin numerically, merge bins with
// expected counts below 5, and compare with a chi-square distribution. A test that runs
// several configurations uses the Sidak-corrected significance 1 - (1 - alpha)^(1/runs).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit::test {

struct Chi2Options {
  int theta_bins = 10;  ///< uniform in theta over [0, pi]; keep it even so pi/2 is an edge
  int phi_bins = 20;    ///< uniform in phi over [0, 2 pi)
  std::size_t samples = 1000000;
  double significance = 0.01;  ///< before the Sidak correction
  int runs = 1;                ///< number of tests in the family (Sidak correction)
  /// Each bin is first split into integration_resolution^2 cells; every cell is then
  /// refined adaptively (quadtree, 3x3 Gauss-Legendre per cell) until the estimate of the
  /// cell agrees with the sum of its four children to `integration_tolerance` times the
  /// cell's share of the (theta, phi) domain, or to 1e-4 relative. Sharp lobes (alpha ~ 1e-3) are
  /// resolved because GGX's heavy tails make the refinement criterion fire well before the peak.
  int integration_resolution = 4;
  double integration_tolerance = 1e-6;
  int integration_max_depth = 8;
  std::uint64_t seed = 1;
};

struct Chi2Result {
  double statistic = 0.0;
  int degrees_of_freedom = 0;
  double p_value = 0.0;
  double threshold = 0.0;  ///< the Sidak-corrected significance the p-value was held to
  bool passed = false;
  double pdf_integral = 0.0;  ///< the pdf integrated over the sphere (numerically)
  std::size_t rejected = 0;   ///< samples the sampler rejected (nullopt)
  std::string report;         ///< a readable summary for failure messages
};

/// `sample(u_lobe, u)` returns a unit direction or nullopt (a sample the sampler rejected);
/// `pdf(w)` is its density over solid angle (it may integrate to less than 1 when samples
/// can be rejected: the rejected samples then form one more cell whose expected count is
/// samples * (1 - integral of the pdf)). Both functions are called from several threads.
/// Samples are drawn in fixed chunks, each with its own PCG32 stream, so the result does
/// not depend on the thread count.
Chi2Result chi2_sphere_test(const std::function<std::optional<glm::vec3>(float, glm::vec2)>& sample,
                            const std::function<double(glm::vec3)>& pdf,
                            const Chi2Options& options = {});

/// Upper tail probability of the chi-square distribution with `dof` degrees of freedom,
/// Q(dof/2, statistic/2) (regularised upper incomplete gamma function).
double chi2_survival(double statistic, int dof);

/// Pearson's chi-square statistic of histogram counts against expected counts, the cells
/// expected below 5 pooled into one (standard practice). When the pooled cells expect fewer
/// than 5 too they are left out, and `pooled_observed` says what they hold (the caller
/// asserts it is small: nothing where the pdf is ~0).
struct PooledChi2 {
  double statistic = 0.0;
  int degrees_of_freedom = -1;
  double pooled_observed = 0.0, pooled_expected = 0.0;
  bool pooled_counted = false;  ///< the pooled cell entered the statistic
};
PooledChi2 pooled_chi2(const std::vector<double>& observed, const std::vector<double>& expected);

/// The pdf of `options`' (theta, phi) grid integrated over every bin (row-major,
/// theta-major), exactly as chi2_sphere_test computes the expected frequencies.
std::vector<double> integrate_pdf_over_bins(const std::function<double(glm::vec3)>& pdf,
                                            const Chi2Options& options = {});

/// int f(w) dw over the sphere with the same adaptive cubature (2 x 2 bins split at the
/// horizon), to roughly `tolerance` absolute: used for directional albedos.
double integrate_over_sphere(const std::function<double(glm::vec3)>& f, double tolerance = 1e-6);

/// Adaptive 1D quadrature (adaptive Simpson, Lyness 1969) of f over [a, b] in double
/// precision, to absolute tolerance `eps`: used by the tests' brute-force integrals.
double adaptive_simpson(const std::function<double(double)>& f, double a, double b, double eps,
                        int max_depth = 40);

}  // namespace pbrkit::test
