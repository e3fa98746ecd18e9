#pragma once
// Chi-square goodness-of-fit test of a direction sampler against its pdf, in the style of
// pbrt-v4's bsdfs_test.cpp and Mitsuba 3's chi2.py: bin >= 1e6 samples over
// (theta, phi) of the sphere, integrate the pdf over each bin numerically, merge bins with
// expected counts below 5, and compare with a chi-square distribution. A test that runs
// several configurations uses the Sidak-corrected significance 1 - (1 - alpha)^(1/runs).
#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace pbrkit::test {

struct Chi2Options {
  int theta_bins = 10;
  int phi_bins = 20;
  std::size_t samples = 1000000;
  double significance = 0.01;      ///< before the Sidak correction
  int runs = 1;                    ///< number of tests in the family (Sidak correction)
  int integration_resolution = 8;  ///< per-bin quadrature points per axis (Simpson)
  std::uint64_t seed = 1;
};

struct Chi2Result {
  double statistic = 0.0;
  int degrees_of_freedom = 0;
  double p_value = 0.0;
  bool passed = false;
  std::string report;  ///< a readable summary for failure messages
};

/// `sample(u_lobe, u)` returns a unit direction or nullopt (a sample the sampler rejected);
/// `pdf(w)` is its density over solid angle (it may integrate to less than 1 when samples
/// can be rejected).
Chi2Result chi2_sphere_test(const std::function<std::optional<glm::vec3>(float, glm::vec2)>& sample,
                            const std::function<double(glm::vec3)>& pdf,
                            const Chi2Options& options = {});

/// Upper tail probability of the chi-square distribution with `dof` degrees of freedom.
double chi2_survival(double statistic, int dof);

}  // namespace pbrkit::test
