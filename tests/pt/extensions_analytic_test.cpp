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
                           const char* what) {
  const Scene scene = sphere_scene(m);
  const Environment env = Environment::constant(glm::vec3(kL));
  const PathTracerResult res =
      render_path(scene, &env, ortho_camera(kHalf), small_settings(32, spp));
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
  // A film of thickness 0 vanishes: the sphere equals the quadrature of the same material
  // without the film but with the base's exact Fresnel (what iridescence_fresnel returns at
  // thickness 0, tests/core/iridescence_test.cpp). Here the material is a metal, whose
  // albedo the quadrature takes from the layered BSDF with the film set to 0 nm.
  Material m = make_material(glm::vec3(0.9f, 0.6f, 0.3f), 1.0f, 0.4f);
  m.iridescence = IridescenceExtension{};
  m.iridescence->factor = 1.0f;
  m.iridescence->thickness_min = 0.0f;
  m.iridescence->thickness_max = 0.0f;
  SurfaceParams p;
  p.base.base_color = glm::vec3(0.9f, 0.6f, 0.3f);
  p.base.metallic = 1.0f;
  p.base.roughness = 0.4f;
  p.base.iridescence = 1.0f;
  p.base.iridescence_thickness = 0.0f;
  const Bsdf bsdf(p);
  const AlbedoTable albedo = AlbedoTable::from(
      [&](double mu) {
        mu = std::max(mu, 0.02);
        const glm::vec3 wo(float(std::sqrt(1.0 - mu * mu)), 0.0f, float(mu));
        return integrate_over_sphere(
            [&](glm::vec3 wi) { return wi.z > 0.0f ? double(bsdf.eval(wo, wi).x) * wi.z : 0.0; },
            1e-5);
      },
      32);
  expect_sphere_matches(m, albedo, 64, "iridescence 0 nm");
}

}  // namespace
}  // namespace pbrkit::test
