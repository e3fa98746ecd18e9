// The direction the real-time sheen IBL looks the environment up in (core/sheen.h:
// SheenTable::lobe_angle, sheen_lobe_direction): the tabulated angle against an independent
// brute-force quadrature of the cosine-weighted Charlie lobe's mean, and the image-based
// approximation it serves (E(n.v) times the environment averaged over a cosine lobe about
// that direction) against the lobe integrated over non-uniform analytic environments,
// averaged over a sphere's visible disc as docs/SPLIT_SUM_ERRORS.md measures it, with the
// mirror-direction lookup shown to fail the same bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include "pbrkit/core/sheen.h"

namespace pbrkit {
namespace {

constexpr double kPiD = std::numbers::pi;

// The lobe's mean direction's angle from n (= +z) towards v (in the xz plane, +x) by a
// (theta, phi) midpoint grid over the whole upper hemisphere, in double.
double brute_force_angle(double mu, float r) {
  const glm::dvec3 v(std::sqrt(1.0 - mu * mu), 0.0, mu);
  constexpr int kTheta = 240, kPhi = 480;
  double mx = 0.0, mz = 0.0;
  for (int i = 0; i < kTheta; ++i) {
    const double theta = (i + 0.5) * (kPiD / 2.0) / kTheta;
    const double ct = std::cos(theta), st = std::sin(theta);
    for (int k = 0; k < kPhi; ++k) {
      const double phi = (k + 0.5) * (2.0 * kPiD) / kPhi;
      const glm::dvec3 l(st * std::cos(phi), st * std::sin(phi), ct);
      const glm::dvec3 h = glm::normalize(v + l);
      const double w = double(DistributionCharlie(float(h.z), r)) *
                       double(VisibilityCharlie(float(mu), float(ct), r)) * ct * st;
      mx += w * l.x;
      mz += w * l.z;
    }
  }
  return std::atan2(mx, mz);
}

TEST(SheenLobeAngle, MatchesBruteForceMean) {
  const SheenTable& table = SheenTable::get();
  double worst = 0.0;
  for (float r : {0.07f, 0.12f, 0.3f, 0.45f, 0.6f, 0.83f, 1.0f})
    for (double mu : {0.03, 0.1, 0.26, 0.5, 0.77, 0.95}) {
      const double ref = brute_force_angle(mu, r);
      const double got = table.lobe_angle(float(mu), r);
      worst = std::max(worst, std::abs(got - ref));
      // 0.75 degrees (measured: 0.49, at n.v 0.95): a lookup direction that much off moves a
      // cosine-weighted average of a smooth environment by about 1%. (Not tested: the last
      // cell, n.v > 0.9685, where the mean's angle drops to 0 faster than its bilinear
      // interpolation, e.g. 0.36 rad for 0.46 at n.v 0.98 and roughness 0.3; there the mean
      // is short, the lobe close to a ring about n, and E small.)
      EXPECT_NEAR(got, ref, 0.75 * kPiD / 180.0) << "mu " << mu << " roughness " << r;
      // The lobe back-scatters: its mean lies on the viewer's side of n.
      EXPECT_GT(got, 0.0) << "mu " << mu << " roughness " << r;
    }
  std::printf("lobe angle vs brute force: max |error| %.3f degrees\n", worst * 180.0 / kPiD);
  EXPECT_NEAR(table.lobe_angle(1.0f, 0.5f), 0.0, 1e-6);  // normal incidence: n by symmetry
}

TEST(SheenLobeDirection, TurnsNTowardsV) {
  // In any frame: unit, in the plane of n and v, at lobe_angle from n on v's side.
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
  const glm::vec3 side = glm::normalize(glm::cross(n, glm::vec3(1.0f, 0.0f, 0.0f)));
  const float mu = 0.4f;
  const glm::vec3 v = mu * n + std::sqrt(1.0f - mu * mu) * side;
  const glm::vec3 d = sheen_lobe_direction(n, v, 0.6f);
  EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(d, glm::cross(n, side)), 0.0f, 1e-6f);
  EXPECT_NEAR(std::atan2(glm::dot(d, side), glm::dot(d, n)), SheenTable::get().lobe_angle(mu, 0.6f),
              1e-5f);
  EXPECT_EQ(sheen_lobe_direction(n, n, 0.6f), n);
}

// A unit-sphere midpoint grid in (cos theta, phi): equal solid angles.
struct SphereGrid {
  std::vector<glm::dvec3> dirs;
  double omega = 0.0;
  SphereGrid(int nt, int np) : omega(4.0 * kPiD / (nt * np)) {
    for (int i = 0; i < nt; ++i) {
      const double c = -1.0 + 2.0 * (i + 0.5) / nt, s = std::sqrt(1.0 - c * c);
      for (int k = 0; k < np; ++k) {
        const double p = 2.0 * kPiD * (k + 0.5) / np;
        dirs.emplace_back(s * std::cos(p), s * std::sin(p), c);
      }
    }
  }
};

using Env = std::function<glm::dvec3(const glm::dvec3&)>;

// The sheen lobe's reflected radiance (sheenColor = 1) by quadrature, and its E.
double lobe_radiance(const SphereGrid& g, const Env& env, glm::dvec3 n, glm::dvec3 v, float r,
                     int channel, double* e) {
  const double mu = glm::dot(n, v);
  double sum = 0.0, albedo = 0.0;
  for (const glm::dvec3& l : g.dirs) {
    const double nl = glm::dot(n, l);
    if (nl <= 0.0) continue;
    const double w = double(DistributionCharlie(float(glm::dot(n, glm::normalize(v + l))), r)) *
                     double(VisibilityCharlie(float(mu), float(nl), r)) * nl * g.omega;
    albedo += w;
    sum += w * env(l)[channel];
  }
  *e = albedo;
  return sum;
}

// The environment averaged over a cosine lobe about d (irradiance(d) / pi), by quadrature.
double cosine_average(const SphereGrid& g, const Env& env, glm::dvec3 d, int channel) {
  double sum = 0.0, weight = 0.0;
  for (const glm::dvec3& l : g.dirs) {
    const double c = glm::dot(d, l);
    if (c <= 0.0) continue;
    sum += c * env(l)[channel];
    weight += c;
  }
  return sum / weight;
}

TEST(SheenLobeDirection, ImageBasedSheenMatchesQuadratureOverASphere) {
  // The viewer on +z looks at a sphere (orthographic): its visible disc with n.v > 0.2 on
  // a 10 x 10 pixel grid. Environments: a sun (exp(12 (l.s - 1)), about 16 degrees wide,
  // over a dim constant) behind the viewer, above, and behind the sphere; and an octant
  // probe (each channel bright on one side of one axis), as an orientation test map.
  auto sun = [](glm::dvec3 s) {
    return Env([s](const glm::dvec3& l) {
      return glm::dvec3(std::exp(12.0 * (glm::dot(l, s) - 1.0)) + 0.05);
    });
  };
  const std::vector<std::pair<const char*, Env>> envs = {
      {"sun behind the viewer", sun({0.0, 0.0, 1.0})},
      {"sun above", sun({0.0, 1.0, 0.0})},
      {"sun behind the sphere", sun(glm::normalize(glm::dvec3(0.3, 0.2, -1.0)))},
      {"octant probe", [](const glm::dvec3& l) {
         return glm::dvec3(l.x > 0.0 ? 1.0 : 0.1, l.y > 0.0 ? 1.0 : 0.1, l.z > 0.0 ? 1.0 : 0.1);
       }}};
  const SphereGrid grid(32, 64);
  const glm::dvec3 v(0.0, 0.0, 1.0);
  double worst = 0.0, worst_mirror = 0.0;
  for (float r : {0.3f, 0.6f, 1.0f})
    for (const auto& [name, env] : envs)
      for (int c = 0; c < 3; ++c) {
        double truth = 0.0, lobe = 0.0, mirror = 0.0;
        for (int py = 0; py < 10; ++py)
          for (int px = 0; px < 10; ++px) {
            const double x = -1.0 + (px + 0.5) / 5.0, y = -1.0 + (py + 0.5) / 5.0;
            const double z2 = 1.0 - x * x - y * y;
            if (z2 < 0.04) continue;  // n.v > 0.2
            const glm::dvec3 n(x, y, std::sqrt(z2));
            double e = 0.0;
            truth += lobe_radiance(grid, env, n, v, r, c, &e);
            const glm::dvec3 d(sheen_lobe_direction(glm::vec3(n), glm::vec3(v), r));
            lobe += e * cosine_average(grid, env, d, c);
            mirror += e * cosine_average(grid, env, glm::reflect(-v, n), c);
          }
        const double err = lobe / truth - 1.0, err_mirror = mirror / truth - 1.0;
        worst = std::max(worst, std::abs(err));
        worst_mirror = std::max(worst_mirror, std::abs(err_mirror));
        // 8%: the largest measured is 6.2% (the lobe is not exactly a cosine lobe); the
        // renderer's own SH or irradiance-cube rounding comes on top.
        EXPECT_LT(std::abs(err), 0.08) << name << ", roughness " << r << ", channel " << c;
      }
  std::printf("sphere means: lobe direction within %.3f, mirror direction off by up to %.3f\n",
              worst, worst_mirror);
  // The bound can fail: the same cosine lobe about the mirror direction misses the
  // back-scattered sun.
  EXPECT_GT(worst_mirror, 0.3);
}

}  // namespace
}  // namespace pbrkit
