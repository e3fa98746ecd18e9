// The ground truth of multiple scattering (support/microsurface_walk.h, the random walk of
// Heitz et al. 2016) against what is known of it: a white conductor and a non-absorbing
// dielectric lose nothing (albedo 1 up to the walks cut at the order limit), and its first
// scattering order is the single-scattering GGX lobe with the height-correlated Smith G2
// (Heitz et al. 2016, section 5) that core evaluates, computed here from core's own lobe
// (the EnergyTable's VNDF quadrature, the dielectric interface's sampler).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/core/transmission.h"
#include "support/chi2.h"
#include "support/microsurface_walk.h"

namespace pbrkit::test {
namespace {

glm::dvec3 dir(double mu, double phi = 0.0) {
  const double s = std::sqrt(1.0 - mu * mu);
  return {s * std::cos(phi), s * std::sin(phi), mu};
}

// Binomial-like standard error of a fraction p of n walks that each carry weight <= 1.
double fraction_error(double p, double n) {
  return std::sqrt(std::max(p * (1.0 - p), 1e-12) / n);
}

// Core's single-scattering albedo of an anisotropic white GGX mirror at wo, by VNDF
// quadrature (the estimator G2 / G1, as core/energy.cpp; Hammersley points).
double core_single_scattering_albedo(glm::vec3 wo, float ax, float ay, int n) {
  double sum = 0.0;
  const float G1 = 1.0f / (1.0f + SmithLambdaGGXAniso(wo, ax, ay));
  for (int i = 0; i < n; ++i) {
    const glm::vec2 u = hammersley(std::uint32_t(i), std::uint32_t(n));
    const glm::vec3 h = sample_ggx_visible_normal(wo, u, ax, ay);
    const glm::vec3 wi = reflect_about(wo, h);
    if (!(wi.z > 0.0f)) continue;
    const float G2 =
        1.0f / (1.0f + SmithLambdaGGXAniso(wo, ax, ay) + SmithLambdaGGXAniso(wi, ax, ay));
    sum += double(G2 / G1);
  }
  return sum / n;
}

TEST(MicrosurfaceWalk, WhiteConductorConservesEnergy) {
  const std::uint64_t n = 100000;
  for (double alpha : {0.1, 0.3, 1.0})
    for (double mu : {0.2, 0.7, 1.0}) {
      Microsurface s;
      s.alpha_x = s.alpha_y = alpha;
      const WalkResult r = microsurface_walk(s, dir(mu), n, 3);
      // Every walk carries weight 1 and leaves above: albedo 1 but for the walks cut at the
      // order limit (none expected at these roughnesses).
      EXPECT_EQ(r.transmitted, 0.0);
      EXPECT_NEAR(r.reflected, 1.0, 1e-4) << alpha << " " << mu;
      EXPECT_LT(r.lost, 1e-4);
    }
}

TEST(MicrosurfaceWalk, NonAbsorbingDielectricConservesEnergy) {
  const std::uint64_t n = 100000;
  for (double eta : {1.5, 1.0 / 1.5, 2.4})
    for (double alpha : {0.1, 0.3, 1.0})
      for (double mu : {0.2, 0.7}) {
        Microsurface s;
        s.dielectric = true;
        s.eta = eta;
        s.alpha_x = s.alpha_y = alpha;
        const WalkResult r = microsurface_walk(s, dir(mu), n, 5);
        EXPECT_NEAR(r.total(), 1.0, 1e-4) << eta << " " << alpha << " " << mu;
        EXPECT_GT(r.transmitted, 0.0);
      }
}

TEST(MicrosurfaceWalk, FirstOrderIsCoresSingleScatteringConductor) {
  // The first order of a white conductor is E(mu) of core's lobe (height-correlated G2),
  // isotropic and anisotropic, from several azimuths.
  const std::uint64_t n = 200000;
  struct Case {
    double ax, ay, mu, phi;
  };
  for (const Case c :
       {Case{0.3, 0.3, 0.5, 0.0}, Case{1.0, 1.0, 1.0, 0.0}, Case{0.6, 0.6, 0.15, 0.0},
        Case{1.0, 0.16, 0.5, 0.0}, Case{1.0, 0.16, 0.5, 1.5707963}, Case{0.5, 0.1, 0.3, 0.8}}) {
    Microsurface s;
    s.alpha_x = c.ax;
    s.alpha_y = c.ay;
    const WalkResult r = microsurface_walk(s, dir(c.mu, c.phi), n, 7);
    const double E = core_single_scattering_albedo(glm::vec3(dir(c.mu, c.phi)), float(c.ax),
                                                   float(c.ay), 1 << 16);
    std::printf(
        "conductor alpha %.2f,%.2f mu %.2f phi %.2f: walk order 1 %.4f, core %.4f, "
        "all orders %.4f\n",
        c.ax, c.ay, c.mu, c.phi, r.reflected_single, E, r.reflected);
    EXPECT_NEAR(r.reflected_single, E, 4.0 * fraction_error(E, double(n)) + 5e-4);
  }
  // Isotropic: the same as the EnergyTable's own entry.
  Microsurface s;
  s.alpha_x = s.alpha_y = 0.3;
  const WalkResult r = microsurface_walk(s, dir(0.5), n, 9);
  const glm::vec2 ab =
      EnergyTable::integrate_AB(GeometryModel::kReference, 0.5f, std::sqrt(0.3f), 1 << 16);
  EXPECT_NEAR(r.reflected_single, ab.x + ab.y, 4.0 * fraction_error(ab.x + ab.y, double(n)) + 5e-4);
}

// Smith's Lambda (isotropic GGX), |tan| form: the same above and below the surface.
double lambda_iso(glm::dvec3 w, double alpha) {
  const double t2 = (1.0 - w.z * w.z) / (w.z * w.z);
  return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * t2));
}

TEST(MicrosurfaceWalk, FirstOrderIsCoresSingleScatteringDielectric) {
  // The first order of a dielectric, split into reflection and transmission. Reflection:
  // the mean weight of core's interface sampler (importance transport). Transmission: in
  // the uncorrelated height model a refracted ray leaves downwards unless the surface below
  // its height blocks it, so the first order's masking-shadowing is
  // int_0^1 u^Lambda(wo) (1 - u)^Lambda(wt) du = B(1 + Lambda(wo), 1 + Lambda(wt)) (Heitz
  // 2014, "Understanding the Masking-Shadowing Function", section 6.2), not the reflection's
  // 1 / (1 + Lambda(wo) + Lambda(wt)) that core (as pbrt-v4 and Walter 2007) uses for both:
  // core's single-scattering transmission is larger than the walk's first order, and its
  // compensation lobe tops up less (MODEL.md's table shows both). Core's visible-normal
  // sampler and Fresnel with the Beta-form weight give the walk's first order.
  const std::uint64_t n = 200000;
  struct Case {
    double alpha, eta, mu;
  };
  for (const Case c : {Case{0.3, 1.5, 0.87}, Case{0.3, 1.0 / 1.5, 0.86}, Case{1.0, 1.5, 0.5},
                       Case{0.6, 1.33, 0.3}}) {
    Microsurface s;
    s.dielectric = true;
    s.eta = c.eta;
    s.alpha_x = s.alpha_y = c.alpha;
    const WalkResult r = microsurface_walk(s, dir(c.mu), n, 11);
    Dielectric d;
    d.eta = float(c.eta);
    d.alpha_x = d.alpha_y = float(c.alpha);
    Pcg32 rng(13);
    double R = 0.0, T = 0.0, T_core = 0.0;
    const int m = 400000;
    const glm::dvec3 wo = dir(c.mu);
    const double lambda_o = lambda_iso(wo, c.alpha);
    for (int k = 0; k < m; ++k) {
      const float ul = rng.next_float();
      const DielectricSample ds =
          dielectric_sample(d, glm::vec3(wo), ul, rng.next_2d(), TransportMode::kImportance);
      if (!ds.valid) continue;
      if (!ds.transmitted) {
        R += ds.weight;
        continue;
      }
      T_core += ds.weight;
      // The sampler's weight is G2 / G1(wo); replace G2 by the Beta form.
      const double lambda_t = lambda_iso(glm::dvec3(ds.wi), c.alpha);
      const double G2 = 1.0 / (1.0 + lambda_o + lambda_t);
      const double beta = std::exp(std::lgamma(1.0 + lambda_o) + std::lgamma(1.0 + lambda_t) -
                                   std::lgamma(2.0 + lambda_o + lambda_t));
      T += ds.weight * beta / G2;
    }
    R /= m;
    T /= m;
    T_core /= m;
    std::printf(
        "dielectric alpha %.2f eta %.3f mu %.2f: walk order 1 R %.4f T %.4f, core R %.4f "
        "T %.4f (Beta G2: T %.4f); all orders R %.4f T %.4f\n",
        c.alpha, c.eta, c.mu, r.reflected_single, r.transmitted_single, R, T_core, T, r.reflected,
        r.transmitted);
    // The sampler's weights are G2 / G1 <= 1, so the same binomial bound covers both.
    EXPECT_NEAR(r.reflected_single, R, 4.0 * fraction_error(R, double(n) * m / (n + m)) + 5e-4);
    EXPECT_NEAR(r.transmitted_single, T, 4.0 * fraction_error(T, double(n) * m / (n + m)) + 5e-4);
  }
}

// ---- The table of docs/MODEL.md ("Energy: the ground truth"): compensation off, core's
// compensation and the random walk, printed; the assertions are the decisions it supports.

struct Moments {
  double albedo, xx, yy;
  double elongation() const { return std::sqrt(xx / yy); }
};

// Albedo of a white metal Brdf at wo and the second moments of its reflected energy's
// tangential components (quadrature of eval cos over the hemisphere).
Moments brdf_moments(const Brdf& b, glm::vec3 wo) {
  auto integral = [&](auto weight) {
    return integrate_over_sphere(
        [&](glm::vec3 wi) {
          return wi.z > 0.0f ? double(b.eval(wo, wi).x) * wi.z * weight(wi) : 0.0;
        },
        1e-5);
  };
  const double a = integral([](glm::vec3) { return 1.0; });
  return {a, integral([](glm::vec3 w) { return double(w.x * w.x); }) / a,
          integral([](glm::vec3 w) { return double(w.y * w.y); }) / a};
}

TEST(EnergyGroundTruth, DielectricTableAgainstTheWalk) {
  // Reflected and transmitted albedo (importance transport) of a rough dielectric: core's
  // single scattering, core's Kulla-Conty compensation and the walk (all orders).
  const std::uint64_t n = 200000;
  std::printf("dielectric: alpha eta mu | off R T | Kulla-Conty R T | walk R T\n");
  for (double alpha : {0.3, 1.0})
    for (double eta : {1.5, 1.0 / 1.5})
      for (double mu : {1.0, 0.5, 0.2}) {
        Microsurface s;
        s.dielectric = true;
        s.eta = eta;
        s.alpha_x = s.alpha_y = alpha;
        const WalkResult w = microsurface_walk(s, dir(mu), n, 17);
        double R[2], T[2];
        for (bool ms : {false, true}) {
          Dielectric d;
          d.eta = float(eta);
          d.alpha_x = d.alpha_y = float(alpha);
          if (ms) enable_dielectric_multiscatter(d);
          // The sampler's mean weights (importance transport), split by side; its
          // consistency with eval is DielectricBsdf's and CompensatedDielectric's chi-square
          // and furnace tests.
          Pcg32 rng(23);
          R[ms] = T[ms] = 0.0;
          const int m = 400000;
          for (int k = 0; k < m; ++k) {
            const float ul = rng.next_float();
            const DielectricSample ds = dielectric_sample(d, glm::vec3(dir(mu)), ul, rng.next_2d(),
                                                          TransportMode::kImportance);
            if (ds.valid) (ds.transmitted ? T[ms] : R[ms]) += double(ds.weight) / m;
          }
        }
        std::printf("  %.2f %.3f %.1f | %.4f %.4f | %.4f %.4f | %.4f %.4f\n", alpha, eta, mu, R[0],
                    T[0], R[1], T[1], w.reflected, w.transmitted);
        // The compensated interface conserves energy as the walk does, and splits it between
        // reflection and transmission within a few percent of the walk's split, but for the
        // roughest interface seen from the denser side: there the walk's transmitted share
        // falls from 0.6 at normal incidence to 0.06 at mu 0.2, which a compensation lobe
        // whose split does not depend on mu_o cannot follow (MODEL.md).
        EXPECT_NEAR(R[1] + T[1], w.total(), 4e-3);
        if (alpha < 0.5 || eta > 1.0) {
          EXPECT_NEAR(T[1], w.transmitted, 0.03) << alpha << " " << eta << " " << mu;
        }
        // Uncompensated, the loss is what the walk's higher orders carry.
        EXPECT_GT(w.total() - (R[0] + T[0]), 0.01);
      }
}

TEST(EnergyGroundTruth, ConductorAlbedoAgainstTheWalk) {
  // An isotropic metal of F0 1 and 0.5 (Schlick, the walk's Fresnel): albedo without
  // compensation, with core's Kulla-Conty lobe, with Turquin 2019's scaling
  // E_ss (1 + F0 (1 - E) / E) (E the white lobe's albedo), and the walk.
  const std::uint64_t n = 200000;
  std::printf("isotropic metal: alpha F0 mu | off, Kulla-Conty, Turquin, walk\n");
  for (float alpha : {0.3f, 1.0f})
    for (float F0 : {1.0f, 0.5f})
      for (double mu : {1.0, 0.5, 0.2}) {
        Microsurface s;
        s.alpha_x = s.alpha_y = alpha;
        s.F0 = F0;
        const WalkResult w = microsurface_walk(s, dir(mu), n, 29);
        const glm::vec3 wo(dir(mu));
        const float roughness = std::sqrt(alpha);
        const double off =
            brdf_moments(Brdf(glm::vec3(F0), 1.0f, roughness, {BrdfModel::kReference, false}), wo)
                .albedo;
        const double kc =
            brdf_moments(Brdf(glm::vec3(F0), 1.0f, roughness, {BrdfModel::kReference, true}), wo)
                .albedo;
        const double E =
            brdf_moments(Brdf(glm::vec3(1.0f), 1.0f, roughness, {BrdfModel::kReference, false}), wo)
                .albedo;
        const double turquin = off * (1.0 + F0 * (1.0 - E) / E);
        std::printf("  %.1f %.1f %.1f | %.4f %.4f %.4f %.4f\n", alpha, F0, mu, off, kc, turquin,
                    w.reflected);
        // Both compensations are nearer the walk than no compensation; Kulla-Conty stays
        // within 0.035 of it (a little low for the roughest coloured metal), Turquin within
        // 0.05 (high at normal incidence there).
        const double tol = 4.0 * w.reflected_error;
        EXPECT_LT(std::abs(kc - w.reflected), std::abs(off - w.reflected) + tol);
        EXPECT_LT(std::abs(turquin - w.reflected), std::abs(off - w.reflected) + tol);
        EXPECT_NEAR(kc, w.reflected, 0.035 + tol) << alpha << " " << F0 << " " << mu;
        EXPECT_NEAR(turquin, w.reflected, 0.05 + tol) << alpha << " " << F0 << " " << mu;
      }
}

TEST(EnergyGroundTruth, AnisotropicLobeAgainstTheWalk) {
  // A white anisotropic metal (roughness 0.4, KHR_materials_anisotropy strength 0.8 and 1)
  // at normal incidence and at mu 0.15: albedo and the reflected lobe's elongation
  // sqrt(<x^2> / <y^2>) for core without compensation, core's compensation (an isotropic
  // Kulla-Conty lobe at the geometric-mean alpha), Turquin 2019's scaling of the
  // single-scattering lobe by 1 + (1 - E) / E (its shape is the uncompensated lobe's, its
  // albedo 1 for white) and the walk.
  const std::uint64_t n = 200000;
  std::printf(
      "anisotropic white metal: strength mu | albedo off, KC, walk | elongation off (= "
      "Turquin), KC, walk\n");
  for (float strength : {0.8f, 1.0f}) {
    const float alpha = 0.16f, ax = alpha + (1.0f - alpha) * strength * strength;
    for (double mu : {1.0, 0.15}) {
      Microsurface s;
      s.alpha_x = ax;
      s.alpha_y = alpha;
      const WalkResult w = microsurface_walk(s, dir(mu, 0.0), n, 19);
      BaseLayer layer;
      layer.base_color = glm::vec3(1.0f);
      layer.metallic = 1.0f;
      layer.roughness = 0.4f;
      layer.anisotropy = strength;
      const glm::vec3 wo(dir(mu, 0.0));
      const Moments off = brdf_moments(Brdf(layer, {BrdfModel::kReference, false}), wo);
      const Moments kc = brdf_moments(Brdf(layer, {BrdfModel::kReference, true}), wo);
      std::printf("  %.1f %.2f | %.4f %.4f %.4f | %.3f %.3f %.3f\n", strength, mu, off.albedo,
                  kc.albedo, w.reflected, off.elongation(), kc.elongation(), w.elongation());
      // What the table shows: multiple scattering rounds the lobe, so the single-scattering
      // lobe's (Turquin's) shape is more than 10% too elongated at normal incidence; core's
      // anisotropic compensation (core/anisotropic_energy.h) keeps the walk's albedo within 1%
      // and its elongation within 5% in the acceptance test's cases; at strength 0.8, between
      // the table's strength nodes, the albedo at normal incidence is 0.988 (its interpolation).
      if (mu == 1.0) {
        EXPECT_GT(off.elongation(), 1.1 * w.elongation());
      }
      EXPECT_NEAR(kc.albedo, w.reflected, 0.015);
      EXPECT_NEAR(kc.elongation(), w.elongation(), 0.05 * w.elongation());
    }
  }
}

// The walk's reflected albedo and elongation with a standard error for the elongation: the
// walks split into `batches` independent streams, the error the spread of the batches'
// elongations over sqrt(batches) (the moments are ratios of sums, so no closed form).
struct WalkFigures {
  double albedo, elongation, elongation_error;
};
WalkFigures walk_figures(const Microsurface& s, glm::dvec3 wo, std::uint64_t paths, int batches) {
  double albedo = 0.0, xx = 0.0, yy = 0.0, sum = 0.0, sum2 = 0.0;
  for (int b = 0; b < batches; ++b) {
    const WalkResult w = microsurface_walk(s, wo, paths / batches, 101 + b);
    albedo += w.reflected / batches;
    xx += w.xx * w.reflected;
    yy += w.yy * w.reflected;
    sum += w.elongation();
    sum2 += w.elongation() * w.elongation();
  }
  const double mean = sum / batches;
  const double var = std::max(sum2 / batches - mean * mean, 0.0) * batches / (batches - 1);
  return {albedo, std::sqrt(xx / yy), std::sqrt(var / batches)};
}

// The acceptance test of an anisotropic multiple-scattering compensation: a white metal's
// compensated lobe against the walk (all orders) at KHR_materials_anisotropy strength 0.5 and
// 1, roughness 0.3, 0.4 and 0.6, viewed along the anisotropy direction at mu 1, 0.5 and 0.15.
// Its directional albedo within 1% of the walk's (1 for white: every walk carries weight 1)
// and its reflected lobe's elongation sqrt(<x^2> / <y^2>) within 5%, the latter widened by 3
// standard errors of the walk's elongation (0.1-0.4% of it at 200 000 walks). The isotropic
// Kulla-Conty lobe at the geometric-mean alpha that came before failed both (albedo
// 0.65-1.02, elongation 1-41% low); core/anisotropic_energy.h's symmetrically scaled,
// broadened lobe plus Kulla-Conty on the rest measures albedo 0.997-1.005 and elongation
// -3.5% .. +3.0% (docs/MODEL.md, "Energy: the ground truth").
TEST(EnergyGroundTruth, AnisotropicCompensationKeepsTheWalksShape) {
  const std::uint64_t n = 200000;
  std::printf(
      "compensated anisotropic white metal: roughness strength mu | albedo KC walk | "
      "elongation off KC walk (+- se) | KC/walk - 1\n");
  for (float roughness : {0.3f, 0.4f, 0.6f})
    for (float strength : {0.5f, 1.0f}) {
      const float alpha = roughness * roughness;
      const float ax = alpha + (1.0f - alpha) * strength * strength;
      for (double mu : {1.0, 0.5, 0.15}) {
        Microsurface s;
        s.alpha_x = ax;
        s.alpha_y = alpha;
        const WalkFigures w = walk_figures(s, dir(mu, 0.0), n, 8);
        BaseLayer layer;
        layer.base_color = glm::vec3(1.0f);
        layer.metallic = 1.0f;
        layer.roughness = roughness;
        layer.anisotropy = strength;
        const glm::vec3 wo(dir(mu, 0.0));
        const Moments off = brdf_moments(Brdf(layer, {BrdfModel::kReference, false}), wo);
        const Moments kc = brdf_moments(Brdf(layer, {BrdfModel::kReference, true}), wo);
        std::printf("  %.1f %.1f %.2f | %.4f %.4f | %.3f %.3f %.3f (+- %.3f) | %+.3f\n", roughness,
                    strength, mu, kc.albedo, w.albedo, off.elongation(), kc.elongation(),
                    w.elongation, w.elongation_error, kc.elongation() / w.elongation - 1.0);
        EXPECT_NEAR(kc.albedo, w.albedo, 0.01 * w.albedo)
            << "roughness " << roughness << " strength " << strength << " mu " << mu;
        EXPECT_NEAR(kc.elongation(), w.elongation, 0.05 * w.elongation + 3.0 * w.elongation_error)
            << "roughness " << roughness << " strength " << strength << " mu " << mu;
      }
    }
}

TEST(EnergyGroundTruth, NoSingleIsotropicAlphaGivesTheAnisotropicAlbedo) {
  // Turquin's scaling needs E of the anisotropic lobe. Looked up in the isotropic table
  // (what the renderers have) at one effective alpha, each candidate is far off somewhere on
  // the grid: the geometric, arithmetic and quadratic means and the projected alpha along wo.
  const EnergyTable& t = EnergyTable::get(GeometryModel::kReference);
  const char* names[] = {"geometric mean", "arithmetic mean", "RMS", "projected along wo"};
  double worst[4] = {0.0, 0.0, 0.0, 0.0};
  for (float ax : {0.3f, 0.7f, 1.0f})
    for (float ay : {0.02f, 0.16f, 0.4f})
      for (float mu : {1.0f, 0.6f, 0.3f, 0.1f})
        for (float phi : {0.0f, 0.785f, 1.5708f}) {
          const double E = core_single_scattering_albedo(glm::vec3(dir(mu, phi)), ax, ay, 1 << 13);
          const float c2 = std::cos(phi) * std::cos(phi), s2 = 1.0f - c2;
          const float candidates[] = {std::sqrt(ax * ay), 0.5f * (ax + ay),
                                      std::sqrt(0.5f * (ax * ax + ay * ay)),
                                      std::sqrt(c2 * ax * ax + s2 * ay * ay)};
          for (int k = 0; k < 4; ++k)
            worst[k] = std::max(worst[k], std::abs(t.E(mu, std::sqrt(candidates[k])) / E - 1.0));
        }
  for (int k = 0; k < 4; ++k) {
    std::printf("isotropic E at the %s alpha: worst relative error %.2f\n", names[k], worst[k]);
    EXPECT_GT(worst[k], 0.2) << names[k];
  }
}

}  // namespace
}  // namespace pbrkit::test
