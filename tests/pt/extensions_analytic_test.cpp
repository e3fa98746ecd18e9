// The KHR_materials_* extensions in the path tracer, against closed forms: an orthographic
// render of a unit sphere in a uniform environment L sees L a(mu) at each pixel, a the
// material's directional albedo (a convex object never sees itself). Each assertion holds
// the mean residual over the sphere's pixels to 4 standard errors measured from the
// residuals, plus the tessellation allowance of analytic_test.cpp (0.2% of L).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pbrkit/core/bsdf.h"
#include "pbrkit/core/sheen.h"
#include "pbrkit/image/environment.h"
#include "pt/pt_test_util.h"
#include "support/chi2.h"

namespace pbrkit::test {
namespace {

constexpr double kPiD = std::numbers::pi;
constexpr float kHalf = 1.1f;
constexpr float kL = 2.0f;

void expect_sphere_matches(const Material& m, const AlbedoTable& albedo, std::uint32_t spp,
                           const char* what, bool multiscatter = true) {
  const Scene scene = sphere_scene(m);
  const Environment env = Environment::constant(glm::vec3(kL));
  PathTracerSettings settings = small_settings(32, spp);
  settings.brdf.multiscatter = multiscatter;
  const PathTracerResult res = render_path(scene, &env, ortho_camera(kHalf), settings);
  const ResidualStats s = residual_stats(sphere_residuals(res.color, kHalf, kL, albedo, 0.97f));
  ASSERT_GT(s.n, 400u) << what;
  EXPECT_LT(std::fabs(s.mean), 4.0 * s.std_error + 2e-3 * kL)
      << what << ": mean residual " << s.mean << " +- " << s.std_error;
}

// A material whose base reflects nothing: black, non-metallic, and ior 1 (no dielectric
// specular at all, KHR_materials_ior), so what the sphere shows is the layer alone.
Material black_base() {
  Material m = make_material(glm::vec3(0.0f), 0.0f, 0.5f);
  m.ior = 1.0f;
  return m;
}

TEST(PathTracerExtensions, Ior1DielectricIsLambertOnly) {
  // ior 1 removes the specular layer: the sphere is a Lambertian of albedo rho, L rho at
  // every pixel, compensation or not.
  const float rho = 0.5f;
  Material m = make_material(glm::vec3(rho), 0.0f, 0.3f);
  m.ior = 1.0f;
  expect_sphere_matches(m, AlbedoTable::from([&](double) { return double(rho); }), 16, "ior 1.0");
}

TEST(PathTracerExtensions, ClearcoatOverBlackBaseIsTheCoatAlbedo) {
  // L w E_coat(mu), E_coat the directional albedo of the coat lobe w F_c D G / (4 cos cos)
  // (F_c Schlick with F0 0.04, height-correlated Smith), integrated here from the formulas
  // written out, not from the BSDF code.
  const float w = 0.8f, r = 0.3f;
  Material m = black_base();
  m.clearcoat = ClearcoatExtension{};
  m.clearcoat->factor = w;
  m.clearcoat->roughness_factor = r;
  const double a = double(r) * r;
  auto lambda = [a](glm::dvec3 v) {
    return (std::sqrt(1.0 + a * a * (v.x * v.x + v.y * v.y) / (v.z * v.z)) - 1.0) / 2.0;
  };
  const AlbedoTable albedo = AlbedoTable::from(
      [&](double mu) {
        mu = std::max(mu, 0.02);
        const glm::dvec3 V(std::sqrt(1.0 - mu * mu), 0.0, mu);
        return integrate_over_sphere(
            [&](glm::vec3 wi) {
              const glm::dvec3 L(wi);
              if (L.z <= 0.0) return 0.0;
              const glm::dvec3 H = glm::normalize(V + L);
              const double e = (H.x * H.x + H.y * H.y) / (a * a) + H.z * H.z;
              const double D = 1.0 / (kPiD * a * a * e * e);
              const double F = 0.04 + 0.96 * std::pow(1.0 - glm::dot(V, H), 5.0);
              const double G = 1.0 / (1.0 + lambda(V) + lambda(L));
              return w * F * D * G / (4.0 * V.z * L.z) * L.z;
            },
            1e-5);
      },
      32);
  expect_sphere_matches(m, albedo, 64, "clearcoat over black");
}

TEST(PathTracerExtensions, SheenOnlyIsTheSheenAlbedoTable) {
  // L E_sheen(mu, r): the sheen's albedo table (tested against its own quadrature in
  // tests/core/sheen_test.cpp) is what a sheen over nothing reflects.
  const float r = 0.5f;
  Material m = black_base();
  m.sheen = SheenExtension{};
  m.sheen->color_factor = glm::vec3(1.0f);
  m.sheen->roughness_factor = r;
  expect_sphere_matches(
      m, AlbedoTable::from([&](double mu) { return double(SheenTable::get().E(float(mu), r)); }),
      64, "sheen only");
}

TEST(PathTracerExtensions, IridescenceOfZeroThicknessIsTheBaseFresnel) {
  // A film of thickness 0 vanishes (KHR_materials_iridescence: the film's ior fades to the
  // outside's), and what is left is the film model's second interface: the exact Fresnel
  // reflectance into the base, whose ior is taken from its F0, n = (1 + sqrt F0) /
  // (1 - sqrt F0) (the iridescence README's Fresnel0ToIor). So a metal with a 0 nm film is
  // the single-scattering GGX lobe F(v.h) D G2 / (4 cos cos) with that exact F, written out
  // here from the textbook formulas (not through the BSDF code), compensation off. The red
  // channel's F0 of 0.5 (n = 5.83) is where exact Fresnel and Schlick's differ by up to 7%
  // (a metal without the film uses Schlick's): a sphere that ignored the film would fail.
  const glm::vec3 base(0.5f, 0.6f, 0.3f);
  const float r = 0.4f;
  Material m = make_material(base, 1.0f, r);
  m.iridescence = IridescenceExtension{};
  m.iridescence->factor = 1.0f;
  m.iridescence->thickness_min = 0.0f;
  m.iridescence->thickness_max = 0.0f;
  const double a = double(r) * r;
  const double n = (1.0 + std::sqrt(double(base.x))) / (1.0 - std::sqrt(double(base.x)));
  // Hecht, Optics, eq. 4.34 and 4.40: unpolarised reflectance from ior 1 into ior n.
  auto fresnel = [n](double cos_i) {
    const double cos_t = std::sqrt(1.0 - (1.0 - cos_i * cos_i) / (n * n));
    const double rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    const double rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
  };
  auto lambda = [a](glm::dvec3 v) {
    return (std::sqrt(1.0 + a * a * (v.x * v.x + v.y * v.y) / (v.z * v.z)) - 1.0) / 2.0;
  };
  const AlbedoTable albedo = AlbedoTable::from(
      [&](double mu) {
        mu = std::max(mu, 0.02);
        const glm::dvec3 V(std::sqrt(1.0 - mu * mu), 0.0, mu);
        return integrate_over_sphere(
            [&](glm::vec3 wi) {
              const glm::dvec3 L(wi);
              if (L.z <= 0.0) return 0.0;
              const glm::dvec3 H = glm::normalize(V + L);
              const double e = (H.x * H.x + H.y * H.y) / (a * a) + H.z * H.z;
              const double D = 1.0 / (kPiD * a * a * e * e);
              const double G = 1.0 / (1.0 + lambda(V) + lambda(L));
              return fresnel(glm::dot(V, H)) * D * G / (4.0 * V.z * L.z) * L.z;
            },
            1e-5);
      },
      32);
  expect_sphere_matches(m, albedo, 64, "iridescence 0 nm", false);
}

}  // namespace
}  // namespace pbrkit::test
