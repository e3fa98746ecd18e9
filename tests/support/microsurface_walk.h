#pragma once
// The stochastic microsurface random walk of Heitz, Hanika, d'Eon & Dachsbacher 2016
// ("Multiple-Scattering Microfacet BSDFs with the Smith Model", ACM TOG 35(4)): a ray is
// traced through the statistical GGX microsurface of the Smith model (uncorrelated heights,
// the uniform height distribution of the paper's supplemental code) until it leaves it,
// reflecting (conductor, Schlick Fresnel) or reflecting and refracting (dielectric, exact
// Fresnel) at each microfacet it meets. It is the ground truth for the BSDF's multiple
// scattering: its first order is the single-scattering microfacet BSDF with the
// height-correlated Smith G2 (paper, section 5), and every further order is what the
// single-scattering model loses.
//
// Written independently of core's BSDF (its own Lambda, height sampling, visible-normal
// sampling and Fresnel) so that the tests that compare core with it compare two codes.
// Double precision; a small deterministic RNG so the results are repeatable.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

namespace pbrkit::test {

/// The microsurface: GGX of roughness alpha_x along +X and alpha_y along +Y.
struct Microsurface {
  double alpha_x = 0.5, alpha_y = 0.5;
  bool dielectric = false;
  /// Conductor: Schlick's Fresnel with this F0 (1: a white, lossless conductor).
  double F0 = 1.0;
  /// Dielectric: the ior below the surface over the ior above it.
  double eta = 1.5;
};

/// Energy leaving the microsurface, per unit incident energy (importance transport: no
/// 1 / eta^2 on refraction), as the mean over `paths` walks.
struct WalkResult {
  double reflected = 0.0, transmitted = 0.0;                ///< albedo, all orders
  double reflected_single = 0.0, transmitted_single = 0.0;  ///< the first order alone
  double lost = 0.0;  ///< energy of walks cut at the order limit
  /// Standard errors of `reflected` and `transmitted`.
  double reflected_error = 0.0, transmitted_error = 0.0;
  /// The reflected energy's second moments of the leaving direction's tangential
  /// components, normalised by the reflected energy: the lobe's extent along X and Y.
  double xx = 0.0, yy = 0.0;
  double total() const { return reflected + transmitted; }
  /// Lobe elongation sqrt(<x^2> / <y^2>) of the reflected energy.
  double elongation() const { return std::sqrt(xx / yy); }
};

namespace walk_detail {

// xoshiro-like splitmix64 stream: enough for Monte Carlo, repeatable across platforms.
struct Rng {
  std::uint64_t s;
  double next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return double(z >> 11) * 0x1.0p-53;
  }
};

constexpr double kPi = 3.14159265358979323846;
constexpr double kEscaped = std::numeric_limits<double>::infinity();

// Smith's Lambda for GGX in any direction (Heitz 2014, eq. 86, and its extension below the
// horizon, Lambda(-w) = -1 - Lambda(w), as the 2016 paper's code writes it).
inline double lambda(const Microsurface& s, glm::dvec3 w) {
  if (w.z > 0.9999) return 0.0;
  if (w.z < -0.9999) return -1.0;
  const double sin2 = 1.0 - w.z * w.z;
  const double alpha2 = (w.x * w.x * s.alpha_x * s.alpha_x + w.y * w.y * s.alpha_y * s.alpha_y) /
                        std::max(w.x * w.x + w.y * w.y, 1e-300);
  const double a = w.z / std::sqrt(sin2 * alpha2);  // 1 / (alpha_w tan theta)
  return 0.5 * (-1.0 + (a > 0.0 ? 1.0 : -1.0) * std::sqrt(1.0 + 1.0 / (a * a)));
}

// The uniform height distribution on [-1, 1]: C1 its cumulative, invC1 the inverse.
inline double C1(double h) {
  return std::clamp(0.5 * (h + 1.0), 0.0, 1.0);
}
inline double invC1(double u) {
  return std::clamp(2.0 * u - 1.0, -1.0, 1.0);
}

// The next height along w from height h0, or kEscaped when the ray leaves (Heitz 2016,
// section 4.1: the masking G1(w, h0) = C1(h0)^Lambda(w) is the probability of no
// intersection; the intersection height inverts it).
inline double sample_height(const Microsurface& s, glm::dvec3 w, double h0, double u) {
  if (w.z > 0.9999) return kEscaped;
  if (w.z < -0.9999) return invC1(u * C1(h0));
  if (std::abs(w.z) < 1e-4) return h0;
  const double L = lambda(s, w);
  const double G1 = w.z > 0.0 ? std::pow(C1(h0), L) : 0.0;
  if (u > 1.0 - G1) return kEscaped;
  return invC1(C1(h0) / std::pow(1.0 - u, 1.0 / L));
}

// A visible normal seen from wi (any direction, also below the horizon), Heitz 2018: stretch,
// sample the projected visible region (for wi below the horizon the half disk minus the half
// ellipse, which the same linear map produces), unstretch.
inline glm::dvec3 sample_visible_normal(const Microsurface& s, glm::dvec3 wi, double u1,
                                        double u2) {
  const glm::dvec3 V = glm::normalize(glm::dvec3(s.alpha_x * wi.x, s.alpha_y * wi.y, wi.z));
  const double lensq = V.x * V.x + V.y * V.y;
  const glm::dvec3 T1 =
      lensq > 0.0 ? glm::dvec3(-V.y, V.x, 0.0) / std::sqrt(lensq) : glm::dvec3(1.0, 0.0, 0.0);
  const glm::dvec3 T2 = glm::cross(V, T1);
  const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
  const double t1 = r * std::cos(phi);
  const double sv = 0.5 * (1.0 + V.z);
  const double t2 = (1.0 - sv) * std::sqrt(std::max(0.0, 1.0 - t1 * t1)) + sv * r * std::sin(phi);
  const glm::dvec3 N = t1 * T1 + t2 * T2 + std::sqrt(std::max(0.0, 1.0 - t1 * t1 - t2 * t2)) * V;
  return glm::normalize(glm::dvec3(s.alpha_x * N.x, s.alpha_y * N.y, std::max(N.z, 1e-12)));
}

// Unpolarised Fresnel reflectance of a dielectric, cos_i > 0 on the incident side, eta the
// far side's ior over the incident side's (Born & Wolf 1.5.2).
inline double fresnel(double cos_i, double eta) {
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

}  // namespace walk_detail

/// Walks `paths` rays arriving from `wi` (unit, wi.z > 0, pointing away from the surface)
/// and sums what leaves above (reflected) and below (transmitted), up to `max_order`
/// scattering events per walk.
inline WalkResult microsurface_walk(const Microsurface& s, glm::dvec3 wi, std::uint64_t paths,
                                    std::uint64_t seed = 1, int max_order = 256) {
  using namespace walk_detail;
  Rng rng{seed * 0x2545f4914f6cdd1dull};
  double r_sum = 0.0, r_sq = 0.0, t_sum = 0.0, t_sq = 0.0, xx = 0.0, yy = 0.0;
  WalkResult out;
  for (std::uint64_t p = 0; p < paths; ++p) {
    glm::dvec3 wr = -wi;             // the ray's direction of travel
    double hr = 1.0 + invC1(0.999);  // start above the microsurface
    bool outside = true;             // above the surface (dielectric: in the upper medium)
    double e = 1.0;
    int order = 0;
    bool escaped = false;
    for (; order <= max_order; ++order) {
      // Inside a dielectric the walk is the same one mirrored through the mean plane.
      const double u = rng.next();
      const double h = outside ? sample_height(s, wr, hr, u) : sample_height(s, -wr, -hr, u);
      if (h == kEscaped) {
        escaped = true;
        break;
      }
      if (order == max_order) break;
      hr = outside ? h : -h;
      const glm::dvec3 w = -wr;  // towards where the ray came from
      const double u1 = rng.next(), u2 = rng.next();
      const glm::dvec3 m =
          outside ? sample_visible_normal(s, w, u1, u2) : -sample_visible_normal(s, -w, u1, u2);
      const double wm = glm::dot(w, m);
      if (!s.dielectric) {
        const double c = 1.0 - std::max(wm, 0.0);
        e *= s.F0 + (1.0 - s.F0) * c * c * c * c * c;
        wr = -w + 2.0 * wm * m;
        continue;
      }
      const double eta = outside ? s.eta : 1.0 / s.eta;
      const double F = fresnel(std::max(wm, 0.0), eta);
      if (rng.next() < F) {
        wr = -w + 2.0 * wm * m;
      } else {
        // Snell (pbrt-v4 eq. 9.4), w on m's side: -w / eta + (cos_i / eta - cos_t) m.
        const double cos_t = std::sqrt(std::max(0.0, 1.0 - (1.0 - wm * wm) / (eta * eta)));
        wr = glm::normalize(-w / eta + (wm / eta - cos_t) * m);
        outside = !outside;
      }
    }
    if (!escaped) {
      out.lost += e;
      continue;
    }
    // A walk leaving above has reflected, one leaving below has been transmitted.
    const bool reflected = outside;
    if (reflected) {
      r_sum += e;
      r_sq += e * e;
      xx += e * wr.x * wr.x;
      yy += e * wr.y * wr.y;
      if (order == 1) out.reflected_single += e;
    } else {
      t_sum += e;
      t_sq += e * e;
      if (order == 1) out.transmitted_single += e;
    }
  }
  const double n = double(paths);
  out.reflected = r_sum / n;
  out.transmitted = t_sum / n;
  out.reflected_single /= n;
  out.transmitted_single /= n;
  out.lost /= n;
  out.reflected_error = std::sqrt(std::max(r_sq / n - out.reflected * out.reflected, 0.0) / n);
  out.transmitted_error =
      std::sqrt(std::max(t_sq / n - out.transmitted * out.transmitted, 0.0) / n);
  out.xx = r_sum > 0.0 ? xx / r_sum : 0.0;
  out.yy = r_sum > 0.0 ? yy / r_sum : 0.0;
  return out;
}

}  // namespace pbrkit::test
