// Thin-film Fresnel (core/iridescence.h) against closed forms written independently here: the
// textbook Fresnel equations for the film-free limits, and the exact single-wavelength Airy
// reflectance (complex amplitudes, every order) integrated over the spectrum against the
// CIE 1931 matching functions, for the interference itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <vector>

#include "pbrkit/core/iridescence.h"

namespace pbrkit {
namespace {

constexpr double kPiD = std::numbers::pi;

// ---- Written out from the textbooks in double (not through iridescence.cpp) ----

// Normal-incidence reflectance of ior n against ior 1: ((n - 1) / (n + 1))^2.
double f0_of_ior(double n) {
  return (n - 1.0) * (n - 1.0) / ((n + 1.0) * (n + 1.0));
}

// The exact unpolarised Fresnel reflectance from ior 1 into a dielectric of ior n at incidence
// cos_i (Hecht, Optics, eq. 4.34 and 4.40): Rs = ((cos_i - n cos_t) / (cos_i + n cos_t))^2,
// Rp = ((n cos_i - cos_t) / (n cos_i + cos_t))^2, R = (Rs + Rp) / 2, n sin_t = sin_i.
double fresnel_dielectric(double cos_i, double n) {
  const double sin_t2 = (1.0 - cos_i * cos_i) / (n * n);
  const double cos_t = std::sqrt(1.0 - sin_t2);
  const double rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
  const double rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// CIE 1931 2-degree matching functions, the multi-lobe piecewise-Gaussian fits of Wyman,
// Sloan & Shirley 2013, "Simple Analytic Approximations to the CIE XYZ Color Matching
// Functions" (JCGT 2(2)), section 2.2: each lobe a exp(-t^2 / 2), t = (lambda - mu) / sigma with
// sigma taken left or right of mu. Within a few percent of the tabulated functions, and a
// different fit (over wavelength, not in Fourier space) from Belcour & Barla's.
double lobe(double lambda, double a, double mu, double sigma_left, double sigma_right) {
  const double t = (lambda - mu) / (lambda < mu ? sigma_left : sigma_right);
  return a * std::exp(-0.5 * t * t);
}
double cie_x(double l) {
  return lobe(l, 1.056, 599.8, 37.9, 31.0) + lobe(l, 0.362, 442.0, 16.0, 26.7) -
         lobe(l, 0.065, 501.1, 20.4, 26.2);
}
double cie_y(double l) {
  return lobe(l, 0.821, 568.8, 46.9, 40.5) + lobe(l, 0.286, 530.9, 16.3, 31.1);
}
double cie_z(double l) {
  return lobe(l, 1.217, 437.0, 11.8, 36.0) + lobe(l, 0.681, 459.0, 26.0, 13.8);
}

// CIE XYZ to linear Rec.709 (IEC 61966-2-1), row by row.
glm::dvec3 xyz_to_rec709(glm::dvec3 c) {
  return {3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z,
          -0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z,
          0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z};
}

// Reflectance of a film of ior n2 and thickness d (nm) on a dielectric of ior n3, from ior 1,
// at one wavelength (nm), unpolarised: the textbook thin-film formula (Born & Wolf, 1.6.4)
//   r = (r12 + r23 e^{2 i beta}) / (1 + r12 r23 e^{2 i beta}),  beta = 2 pi n2 d cos_2 / lambda,
// for each polarisation with complex amplitudes, R = (|r_s|^2 + |r_p|^2) / 2.
double airy_reflectance(double cos1, double n2, double n3, double d, double lambda) {
  using C = std::complex<double>;
  const double sin1_2 = 1.0 - cos1 * cos1;
  const double cos2 = std::sqrt(1.0 - sin1_2 / (n2 * n2));
  const double cos3 = std::sqrt(1.0 - sin1_2 / (n3 * n3));
  const double beta = 2.0 * kPiD * n2 * d * cos2 / lambda;
  const C phase = std::exp(C(0.0, 2.0 * beta));
  const auto film = [&](double r12, double r23) {
    const C r = (r12 + r23 * phase) / (1.0 + r12 * r23 * phase);
    return std::norm(r);
  };
  // s: (n_i cos_i - n_t cos_t) / (n_i cos_i + n_t cos_t); p: (n_t cos_i - n_i cos_t) / (n_t cos_i +
  // n_i cos_t).
  const double r12s = (cos1 - n2 * cos2) / (cos1 + n2 * cos2);
  const double r23s = (n2 * cos2 - n3 * cos3) / (n2 * cos2 + n3 * cos3);
  const double r12p = (n2 * cos1 - cos2) / (n2 * cos1 + cos2);
  const double r23p = (n3 * cos2 - n2 * cos3) / (n3 * cos2 + n2 * cos3);
  return 0.5 * (film(r12s, r23s) + film(r12p, r23p));
}

// The film's colour: the Airy reflectance integrated against the matching functions every
// 1 nm over 360-830 nm, in Rec.709, each channel divided by the same integral of a
// reflectance of 1, so a reflectance constant over the spectrum is itself in every channel.
glm::dvec3 spectral_film_rgb(double cos1, double n2, double n3, double d) {
  glm::dvec3 xyz(0.0), white(0.0);
  for (double l = 360.0; l <= 830.0; l += 1.0) {
    const glm::dvec3 cmf(cie_x(l), cie_y(l), cie_z(l));
    xyz += airy_reflectance(cos1, n2, n3, d, l) * cmf;
    white += cmf;
  }
  return xyz_to_rec709(xyz) / xyz_to_rec709(white);
}

// (a) At thickness 0 the film is gone: exactly the Fresnel reflectance of the base's ior.
TEST(Iridescence, ThicknessZeroIsTheExactFresnelOfTheBase) {
  const double iors[] = {1.33, 1.5, 1.8, 2.4, 3.5};
  const double cosines[] = {1.0, 0.9, 0.7, 0.5, 0.3, 0.1, 0.02, 0.0};
  for (float film_ior : {1.3f, 1.8f, 2.5f}) {
    for (double n : iors) {
      for (double c : cosines) {
        const glm::vec3 F0(float(f0_of_ior(n)), float(f0_of_ior(n * 1.1)),
                           float(f0_of_ior(n * 1.2)));
        const glm::vec3 F = iridescence_fresnel(float(c), film_ior, 0.0f, F0);
        const double expected[] = {fresnel_dielectric(c, n), fresnel_dielectric(c, n * 1.1),
                                   fresnel_dielectric(c, n * 1.2)};
        for (int k = 0; k < 3; ++k) {
          // float rounding of F0 -> ior -> amplitudes: a few ulp.
          EXPECT_NEAR(F[k], expected[k], 2e-6 + 2e-5 * expected[k])
              << "n " << n << " channel " << k << " cos " << c << " film " << film_ior;
        }
      }
    }
  }
  // A metal's baseColor as F0 (gold-like) is a dielectric of the ior that F0 gives; F0 = 1
  // is clamped to 0.9999 (an ior of 39999).
  const glm::vec3 gold(1.0f, 0.782f, 0.344f);
  for (double c : cosines) {
    const glm::vec3 F = iridescence_fresnel(float(c), 1.5f, 0.0f, gold);
    for (int k = 0; k < 3; ++k) {
      const double s = std::sqrt(std::min(double(gold[k]), 0.9999));
      const double n = (1.0 + s) / (1.0 - s);
      const double expected = fresnel_dielectric(c, n);
      EXPECT_NEAR(F[k], expected, 2e-6 + 1e-4 * expected) << "channel " << k << " cos " << c;
    }
  }
  // It is not Schlick's approximation: at 80 degrees on glass they differ by 0.03.
  const double c80 = std::cos(80.0 * kPiD / 180.0);
  const double schlick = 0.04 + 0.96 * std::pow(1.0 - c80, 5.0);
  const float F80 = iridescence_fresnel(float(c80), 1.3f, 0.0f, glm::vec3(0.04f)).g;
  EXPECT_GT(std::abs(F80 - schlick), 0.02);
}

// (d) A film of ior 1 is no film, whatever its thickness.
TEST(Iridescence, FilmOfIorOneIsTheBaseFresnel) {
  for (float d : {0.5f, 100.0f, 250.0f, 400.0f, 800.0f, 1200.0f}) {
    for (double n : {1.2, 1.5, 2.0, 4.0}) {
      for (double c : {1.0, 0.8, 0.5, 0.25, 0.05}) {
        const glm::vec3 F = iridescence_fresnel(float(c), 1.0f, d, glm::vec3(float(f0_of_ior(n))));
        const double expected = fresnel_dielectric(c, n);
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(F[k], expected, 2e-6 + 2e-5 * expected)
              << "d " << d << " n " << n << " cos " << c;
        }
      }
    }
  }
}

// (b) Reflectance in [0, 1], finite, over a dense grid including every limit: grazing and
// normal incidence, no film and thick films, F0 of 0 and 1, film iors below and above the
// base's and below the outside's (total reflection). Where both cosines of an interface are 0
// (grazing, equal iors) the amplitudes are 0 / 0; without their guard this test sees NaN.
TEST(Iridescence, ReflectanceWithinZeroAndOne) {
  for (int ic = 0; ic <= 64; ++ic) {
    const float c = float(ic) / 64.0f;
    for (float film_ior : {0.8f, 1.0f, 1.05f, 1.2f, 1.3f, 1.5f, 1.8f, 2.0f, 2.5f, 3.0f}) {
      for (float d : {0.0f, 0.01f, 0.03f, 1.0f, 10.0f, 50.0f, 100.0f, 150.0f, 200.0f, 300.0f,
                      400.0f, 500.0f, 600.0f, 800.0f, 1000.0f, 1200.0f, 2000.0f}) {
        for (const glm::vec3& F0 :
             {glm::vec3(0.0f), glm::vec3(0.02f, 0.04f, 0.08f), glm::vec3(0.5f), glm::vec3(0.9f),
              glm::vec3(0.9999f), glm::vec3(1.0f), glm::vec3(1.0f, 0.782f, 0.344f),
              glm::vec3(0.955f, 0.638f, 0.538f), glm::vec3(0.972f, 0.960f, 0.915f)}) {
          const glm::vec3 F = iridescence_fresnel(c, film_ior, d, F0);
          for (int k = 0; k < 3; ++k) {
            ASSERT_TRUE(std::isfinite(F[k]) && F[k] >= 0.0f && F[k] <= 1.0f)
                << F[k] << ": cos " << c << " film " << film_ior << " d " << d << " F0 " << F0[k];
          }
        }
      }
    }
  }
}

// The incoherent (thick-film) limit of the film's reflectance, without interference: per
// polarisation R12 + T^2 R23 / (1 - R12 R23), the sum of the intensities of every bounce.
double incoherent_reflectance(double cos1, double n2, double n3) {
  const double sin1_2 = 1.0 - cos1 * cos1;
  const double cos2 = std::sqrt(1.0 - sin1_2 / (n2 * n2));
  const double cos3 = std::sqrt(1.0 - sin1_2 / (n3 * n3));
  const auto layer = [](double R12, double R23) {
    return R12 + (1.0 - R12) * (1.0 - R12) * R23 / (1.0 - R12 * R23);
  };
  const auto sq = [](double x) { return x * x; };
  const double Rs = layer(sq((cos1 - n2 * cos2) / (cos1 + n2 * cos2)),
                          sq((n2 * cos2 - n3 * cos3) / (n2 * cos2 + n3 * cos3)));
  const double Rp = layer(sq((n2 * cos1 - cos2) / (n2 * cos1 + cos2)),
                          sq((n3 * cos2 - n2 * cos3) / (n3 * cos2 + n2 * cos3)));
  return 0.5 * (Rs + Rp);
}

// At grazing incidence every interface reflects everything (exact Fresnel: r = -1 at cos = 0).
TEST(Iridescence, GrazingIncidenceReflectsEverything) {
  for (float film_ior : {1.2f, 1.5f, 2.5f}) {
    for (float d : {0.1f, 100.0f, 400.0f, 1200.0f}) {
      for (float F0 : {0.0f, 0.04f, 0.9f}) {
        EXPECT_EQ(iridescence_fresnel(0.0f, film_ior, d, glm::vec3(F0)), glm::vec3(1.0f))
            << film_ior << " " << d << " " << F0;
      }
    }
  }
  // No film, a base: the base's interface alone.
  EXPECT_EQ(iridescence_fresnel(0.0f, 1.5f, 0.0f, glm::vec3(0.04f)), glm::vec3(1.0f));
  // No film, no base (ior 1 everywhere): nothing reflects, at any angle.
  for (float c : {0.0f, 0.5f, 1.0f}) {
    EXPECT_EQ(iridescence_fresnel(c, 1.0f, 400.0f, glm::vec3(0.0f)), glm::vec3(0.0f)) << c;
  }
}

// (c) The interference against an independent path: the exact Airy reflectance integrated over
// the spectrum (spectral_film_rgb). Belcour & Barla's method differs from it by its fit of
// the matching functions as four Gaussians in Fourier space, whose error grows with the OPD
// (against the integral of the CIE functions its normalised sensitivity is off by up to 0.02
// for OPD <= 1200 nm and 0.07 up to 4000 nm), and by summing three orders of the series.
// That error scales with the interference itself, so the tolerance is a fraction of the
// swing of the film's spectral reflectance (max - min over 380-780 nm): 8%, against a
// measured worst of 7.1% (3.7% at 200 nm, 6.1% at 400 nm, 7.1% at 600 nm); absolute
// differences are at most 0.03.
TEST(Iridescence, MatchesSpectralAiryIntegration) {
  struct Case {
    double film_ior, base_ior;
  };
  // Dielectric films on dielectric bases, and on bases of F0 0.51 and 0.82 (metal-like
  // reflectances, where the third order of the series matters).
  const Case cases[] = {{1.3, 1.5}, {1.8, 1.5}, {2.0, 1.33}, {1.5, 2.4}, {1.8, 6.0}, {1.5, 20.0}};
  int discriminating = 0, count = 0;
  for (double d : {200.0, 400.0, 600.0}) {
    double worst = 0.0;
    for (const Case& k : cases) {
      for (double c : {1.0, 0.8, 0.5}) {
        const glm::dvec3 expected = spectral_film_rgb(c, k.film_ior, k.base_ior, d);
        const glm::vec3 F = iridescence_fresnel(float(c), float(k.film_ior), float(d),
                                                glm::vec3(float(f0_of_ior(k.base_ior))));
        double lo = 1.0, hi = 0.0;
        for (double l = 380.0; l <= 780.0; l += 1.0) {
          lo = std::min(lo, airy_reflectance(c, k.film_ior, k.base_ior, d, l));
          hi = std::max(hi, airy_reflectance(c, k.film_ior, k.base_ior, d, l));
        }
        const double tolerance = 0.08 * (hi - lo);
        const double incoherent = incoherent_reflectance(c, k.film_ior, k.base_ior);
        double interference = 0.0;
        for (int ch = 0; ch < 3; ++ch) {
          EXPECT_NEAR(F[ch], expected[ch], tolerance)
              << "film " << k.film_ior << " base " << k.base_ior << " d " << d << " cos " << c
              << " channel " << ch;
          worst = std::max(worst, std::abs(F[ch] - expected[ch]) / (hi - lo));
          interference = std::max(interference, std::abs(expected[ch] - incoherent));
        }
        // The film's colour is far from its incoherent reflectance: the test sees interference.
        if (interference > 3.0 * tolerance) ++discriminating;
        ++count;
      }
    }
    std::printf("d %.0f nm: worst difference %.3f of the spectral swing\n", d, worst);
  }
  EXPECT_GE(discriminating, count * 3 / 4);
}

}  // namespace
}  // namespace pbrkit
