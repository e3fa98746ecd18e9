// The sheen's image-based light from order-2 spherical harmonics (ibl/sheen_sh.h): exact
// (up to the table's interpolation) for an environment of bands 0-2, against a brute-force
// quadrature of the Charlie lobe; and over non-uniform analytic environments (a sun behind
// the viewer, above, behind the sphere; an orientation probe of coloured longitude bands
// and caps) within a stated bound of the lobe integrated exactly, as per-sphere means over
// a sphere's visible disc (docs/SPLIT_SUM_ERRORS.md's measure), with the split sum's
// mirror-direction lookup shown to fail the same bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include "pbrkit/core/sheen.h"
#include "pbrkit/ibl/sheen_sh.h"

namespace pbrkit {
namespace {

constexpr double kPiD = std::numbers::pi;

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

// The irradiance SH of `env` in SH9's convention: radiance coefficients by quadrature,
// times the cosine's A_l = pi, 2 pi / 3, pi / 4 (Ramamoorthi & Hanrahan 2001).
SH9 irradiance_sh(const SphereGrid& g, const Env& env) {
  std::array<glm::dvec3, 9> c{};
  for (const glm::dvec3& d : g.dirs) {
    const glm::dvec3 L = env(d) * g.omega;
    const double y[9] = {0.282095,
                         0.488603 * d.y,
                         0.488603 * d.z,
                         0.488603 * d.x,
                         1.092548 * d.x * d.y,
                         1.092548 * d.y * d.z,
                         0.315392 * (3.0 * d.z * d.z - 1.0),
                         1.092548 * d.x * d.z,
                         0.546274 * (d.x * d.x - d.y * d.y)};
    for (int i = 0; i < 9; ++i) c[std::size_t(i)] += y[i] * L;
  }
  SH9 sh;
  for (int i = 0; i < 9; ++i) {
    const double a = i == 0 ? kPiD : i < 4 ? 2.0 * kPiD / 3.0 : kPiD / 4.0;
    sh[std::size_t(i)] = glm::vec3(c[std::size_t(i)] * a);
  }
  return sh;
}

// The sheen lobe's reflected radiance (sheenColor = 1) by quadrature, and its E.
glm::dvec3 lobe_radiance(const SphereGrid& g, const Env& env, glm::dvec3 n, glm::dvec3 v, float r,
                         double* e) {
  const double mu = glm::dot(n, v);
  glm::dvec3 sum(0.0);
  double albedo = 0.0;
  for (const glm::dvec3& l : g.dirs) {
    const double nl = glm::dot(n, l);
    if (nl <= 0.0) continue;
    const double w = double(DistributionCharlie(float(glm::dot(n, glm::normalize(v + l))), r)) *
                     double(VisibilityCharlie(float(mu), float(nl), r)) * nl * g.omega;
    albedo += w;
    sum += w * env(l);
  }
  *e = albedo;
  return sum;
}

TEST(SheenSh, ExactForAnEnvironmentOfBandsUpToTwo) {
  // L(l) = a polynomial of degree 2 in l (positive): its SH has bands 0-2 only.
  const Env env = [](const glm::dvec3& l) {
    return glm::dvec3(1.0 + 0.6 * l.x + 0.3 * l.y * l.z - 0.2 * l.z * l.z,
                      1.0 - 0.5 * l.z + 0.4 * l.x * l.z, 1.0 + 0.3 * l.y + 0.5 * l.x * l.x);
  };
  const SphereGrid grid(256, 512);
  const SH9 sh = irradiance_sh(grid, env);
  double worst = 0.0;
  for (float r : {0.1f, 0.3f, 0.6f, 1.0f})
    for (double mu : {0.1, 0.4, 0.8, 0.95}) {
      const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, -0.4, 0.8));
      const glm::dvec3 side = glm::normalize(glm::cross(n, glm::dvec3(0.0, 1.0, 0.0)));
      const glm::dvec3 v = mu * n + std::sqrt(1.0 - mu * mu) * side;
      double e = 0.0;
      glm::dvec3 truth = lobe_radiance(grid, env, n, v, r, &e);
      truth /= e;
      const glm::dvec3 got(sheen_sh_radiance(sh, glm::vec3(n), glm::vec3(v), r));
      for (int c = 0; c < 3; ++c) {
        const double rel = got[c] / truth[c] - 1.0;
        worst = std::max(worst, std::abs(rel));
        // 1.5%: the moments' interpolation and both quadratures (measured: 0.8%, where the
        // mean turns fastest, near normal incidence).
        EXPECT_NEAR(rel, 0.0, 0.015) << "mu " << mu << " roughness " << r << " channel " << c;
      }
    }
  std::printf("band-limited environment: largest relative error %.4f\n", worst);
}

TEST(SheenSh, SphereMeansWithinBoundOfTheLobeIntegral) {
  // The viewer on +z looks at a sphere (orthographic): its visible disc with n.v > 0.2 on
  // a 10 x 10 pixel grid.
  auto sun = [](glm::dvec3 s) {
    return Env([s](const glm::dvec3& l) {
      return glm::dvec3(std::exp(12.0 * (glm::dot(l, s) - 1.0)) + 0.05);
    });
  };
  auto probe = [](double turn) {
    return Env([turn](const glm::dvec3& l) {
      const double elevation = std::asin(std::clamp(l.y, -1.0, 1.0));
      double u = (std::atan2(l.x, -l.z) + kPiD) / (2.0 * kPiD) + turn;
      u -= std::floor(u);
      const glm::dvec3 bands[4] = {
          {0.1, 0.1, 1.0}, {0.1, 1.0, 0.1}, {1.0, 0.1, 0.1}, {1.0, 1.0, 0.1}};
      if (elevation > 0.35 * kPiD) return glm::dvec3(1.5);
      if (elevation < -0.35 * kPiD) return glm::dvec3(0.05);
      return bands[std::min(3, int(u * 4.0))];
    });
  };
  const std::vector<std::pair<const char*, Env>> envs = {
      {"sun behind the viewer", sun({0.0, 0.0, 1.0})},
      {"sun above", sun({0.0, 1.0, 0.0})},
      {"sun behind the sphere", sun(glm::normalize(glm::dvec3(0.3, 0.2, -1.0)))},
      {"probe", probe(0.0)},
      {"probe turned 45 degrees", probe(0.125)},
      {"probe turned 90 degrees", probe(0.25)}};
  const SphereGrid grid(48, 96);
  const glm::dvec3 v(0.0, 0.0, 1.0);
  double worst = 0.0, worst_mirror = 0.0;
  for (const auto& [name, env] : envs) {
    const SH9 sh = irradiance_sh(grid, env);
    for (float r : {0.3f, 0.6f, 1.0f}) {
      glm::dvec3 truth(0.0), approx(0.0), mirror(0.0);
      for (int py = 0; py < 10; ++py)
        for (int px = 0; px < 10; ++px) {
          const double x = -1.0 + (px + 0.5) / 5.0, y = -1.0 + (py + 0.5) / 5.0;
          const double z2 = 1.0 - x * x - y * y;
          if (z2 < 0.04) continue;  // n.v > 0.2
          const glm::dvec3 n(x, y, std::sqrt(z2));
          double e = 0.0;
          truth += lobe_radiance(grid, env, n, v, r, &e);
          approx += e * glm::dvec3(sheen_sh_radiance(sh, glm::vec3(n), glm::vec3(v), r));
          // The split sum's direction: the environment about R (here through the same SH
          // and the same lobe shape, turned to R's side: t -> -t).
          const glm::dvec3 R = glm::reflect(-v, n);
          const glm::dvec3 mirrored_v = glm::normalize(R);
          mirror += e * glm::dvec3(sheen_sh_radiance(sh, glm::vec3(n), glm::vec3(mirrored_v), r));
        }
      for (int c = 0; c < 3; ++c) {
        const double err = approx[c] / truth[c] - 1.0, err_mirror = mirror[c] / truth[c] - 1.0;
        worst = std::max(worst, std::abs(err));
        worst_mirror = std::max(worst_mirror, std::abs(err_mirror));
        // 8%: the largest measured is printed below (the environments' bands above 2 are
        // what the SH leaves out: the sharp sun and the probe's edges).
        EXPECT_LT(std::abs(err), 0.08) << name << ", roughness " << r << ", channel " << c;
      }
    }
  }
  std::printf("sphere means: SH over the lobe within %.3f; the lobe turned to R off by %.3f\n",
              worst, worst_mirror);
  // The bound can fail: the same lobe turned to the mirror side misses the back-scattered
  // sun.
  EXPECT_GT(worst_mirror, 0.3);
}

}  // namespace
}  // namespace pbrkit
