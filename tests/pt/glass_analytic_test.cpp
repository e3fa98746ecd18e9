// Glass and liquids in the path tracer (KHR_materials_transmission, _volume, _dispersion,
// _diffuse_transmission) against closed forms. Scenes are built here: a glass sphere in a
// uniform environment (a white furnace: with no absorption every pixel on a smooth sphere
// is L, the eta^2 of entering and leaving cancel), a slab of known thickness in front of an
// emitter (Beer-Lambert times the Fresnel transmittances, with the inner reflections),
// thin-walled sheets, an ior-1 sphere (invisible) and dispersion of Abbe number -> infinity.
// Tolerances: 4 standard errors of the mean residual measured over the pixels, plus the
// tessellation allowance of analytic_test.cpp where a UV sphere is involved.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pbrkit/core/transmission.h"
#include "pbrkit/image/environment.h"
#include "pt/pt_test_util.h"

namespace pbrkit::test {
namespace {

constexpr float kHalf = 1.1f;
constexpr float kL = 2.0f;

Material glass(float roughness, float ior = 1.5f) {
  Material m = make_material(glm::vec3(1.0f), 0.0f, roughness);
  m.ior = ior;
  m.transmission = TransmissionExtension{};
  m.transmission->factor = 1.0f;
  m.volume = VolumeExtension{};
  m.volume->thickness_factor = 1.0f;
  return m;
}

PathTracerSettings deep_settings(int size, std::uint32_t spp, bool multiscatter = true) {
  PathTracerSettings s = small_settings(size, spp);
  s.max_bounces = 64;  // light inside a glass sphere reflects internally a few times
  s.brdf.multiscatter = multiscatter;
  return s;
}

// The mean over the sphere's pixels of (pixel - expected), with its standard error.
ResidualStats furnace(const Material& m, std::uint32_t spp, double expected,
                      bool multiscatter = true) {
  const Scene scene = sphere_scene(m);
  const Environment env = Environment::constant(glm::vec3(kL));
  const PathTracerResult res =
      render_path(scene, &env, ortho_camera(kHalf), deep_settings(32, spp, multiscatter));
  for (int y = 0; y < res.color.height; ++y)
    for (int x = 0; x < res.color.width; ++x) {
      const glm::vec3 c = res.color.rgb(x, y);
      EXPECT_TRUE(std::isfinite(c.x + c.y + c.z));
    }
  return residual_stats(sphere_residuals(
      res.color, kHalf, kL, AlbedoTable::from([&](double) { return expected; }), 0.97f));
}

TEST(PathTracerGlass, SmoothGlassSphereFurnaceConservesEnergy) {
  const ResidualStats s = furnace(glass(0.0f), 64, 1.0);
  ASSERT_GT(s.n, 400u);
  std::printf("smooth glass furnace: mean residual %.5f +- %.5f (L = %.1f)\n", s.mean, s.std_error,
              kL);
  EXPECT_LT(std::fabs(s.mean), 4.0 * s.std_error + 2e-3 * kL);
}

TEST(PathTracerGlass, RoughGlassSphereFurnaceIsWithinOnePercentCompensated) {
  // With the multiple-scattering compensation of the rough interface (Kulla & Conty 2017,
  // core/transmission.h; the multiscatter option, on by default) the sphere keeps its
  // energy: |loss| + 3 standard errors (one-sided 99.9%) within 1% of L, so the test shows
  // that the loss is below 1% rather than that the noise hides it. Without compensation the
  // same sphere loses 25% (the next test).
  const ResidualStats s = furnace(glass(0.55f), 400, 1.0);
  ASSERT_GT(s.n, 400u);
  const double loss = -s.mean / kL, noise = 3.0 * s.std_error / kL;
  std::printf("rough glass (roughness 0.55) furnace, compensated: loss %.4f +- %.4f of L\n", loss,
              s.std_error / kL);
  ASSERT_LT(noise, 0.008);
  EXPECT_LT(std::fabs(loss) + noise, 0.01);
}

TEST(PathTracerGlass, RoughGlassSphereFurnaceLosesTheStatedEnergyUncompensated) {
  // Without compensation a rough interface loses what would scatter more than once among
  // its microfacets (core test: 1.7% per interaction at alpha 0.3 from outside, 13% from
  // inside); a sphere's paths cross it at least twice. MODEL.md states 25.2%.
  const ResidualStats s = furnace(glass(0.55f), 64, 1.0, false);
  ASSERT_GT(s.n, 400u);
  const double loss = -s.mean / kL;
  std::printf("rough glass (roughness 0.55) furnace, uncompensated: loss %.4f +- %.4f of L\n", loss,
              s.std_error / kL);
  EXPECT_NEAR(loss, 0.252, 4.0 * s.std_error / kL);
}

TEST(PathTracerGlass, DiffuseTransmissionFurnaceConservesEnergy) {
  // A white Lambertian half reflector, half transmitter with no specular layer (ior 1):
  // thin, so what goes in comes out; every pixel is L.
  Material m = make_material(glm::vec3(1.0f), 0.0f, 0.5f);
  m.ior = 1.0f;
  m.diffuse_transmission = DiffuseTransmissionExtension{};
  m.diffuse_transmission->factor = 0.5f;
  const ResidualStats s = furnace(m, 32, 1.0);
  ASSERT_GT(s.n, 400u);
  EXPECT_LT(std::fabs(s.mean), 4.0 * s.std_error + 2e-3 * kL) << s.mean << " +- " << s.std_error;
}

// A scene seen straight down -Z by an orthographic camera: `m` on `mesh` (a slab or a
// sheet around z = 0) over an emitting quad at z = -2 (radiance Le, both sides).
struct SlabScene {
  Scene scene;
  glm::vec3 Le{1.0f, 2.0f, 3.0f};
};
SlabScene slab_scene(const Material& m, Mesh mesh, bool with_mesh = true) {
  SlabScene s;
  s.scene.source = "test:slab";
  s.scene.materials.push_back(m);
  s.scene.materials.push_back(make_material(glm::vec3(0.0f), 0.0f, 1.0f, s.Le, true));
  if (with_mesh) add_mesh_instance(s.scene, std::move(mesh), 0);
  add_mesh_instance(s.scene,
                    make_quad(glm::vec3(-50.0f, -50.0f, -2.0f), glm::vec3(100.0f, 0.0f, 0.0f),
                              glm::vec3(0.0f, 100.0f, 0.0f)),
                    1);
  return s;
}

// Every pixel against `expected` (per channel), 4 standard errors of the mean residual.
void expect_uniform(const Image& img, glm::vec3 expected, const char* what) {
  for (int c = 0; c < 3; ++c) {
    std::vector<double> r;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) r.push_back(double(img.rgb(x, y)[c]) - expected[c]);
    const ResidualStats s = residual_stats(r);
    EXPECT_LT(std::fabs(s.mean), 4.0 * s.std_error + 1e-5 * expected[c])
        << what << " channel " << c << ": mean residual " << s.mean << " +- " << s.std_error
        << " expected " << expected[c];
  }
}

TEST(PathTracerGlass, SlabTransmitsBeerLambertTimesFresnel) {
  // Normal incidence through a slab of thickness d: R = ((n - 1) / (n + 1))^2 at each face,
  // a = attenuationColor^(d / attenuationDistance) per crossing, and the light reflected
  // back and forth inside: Le (1 - R)^2 a / (1 - R^2 a^2).
  const float d = 0.5f, n = 1.5f, D = 0.4f;
  const glm::vec3 color(0.8f, 0.5f, 0.2f);
  Material m = glass(0.0f, n);
  m.volume->attenuation_color = color;
  m.volume->attenuation_distance = D;
  SlabScene s = slab_scene(
      m, make_box(glm::vec3(-50.0f, -50.0f, -d / 2.0f), glm::vec3(50.0f, 50.0f, d / 2.0f)));
  const PathTracerResult res =
      render_path(s.scene, nullptr, ortho_camera(1.0f), deep_settings(16, 64));
  const double R = std::pow((n - 1.0) / (n + 1.0), 2.0);
  glm::vec3 expected;
  for (int c = 0; c < 3; ++c) {
    const double a = std::pow(double(color[c]), d / D);
    expected[c] = float(s.Le[c] * (1.0 - R) * (1.0 - R) * a / (1.0 - R * R * a * a));
  }
  std::printf("slab: expected %.5f %.5f %.5f, centre pixel %.5f %.5f %.5f\n", expected.x,
              expected.y, expected.z, res.color.rgb(8, 8).x, res.color.rgb(8, 8).y,
              res.color.rgb(8, 8).z);
  expect_uniform(res.color, expected, "slab");
}

TEST(PathTracerGlass, NestedVolumesTrackTheMediumStack) {
  // An absorbing slab (thickness d_in) inside a clear one (thickness d_out), both of ior n:
  // the inner faces separate equal iors, so they neither reflect nor bend (eta = 1 from the
  // stack's ior, not from vacuum's), and only the inner segment absorbs. The outer faces'
  // inner reflections cross the inner slab twice per round trip:
  // Le (1 - R)^2 a / (1 - R^2 a^2), a = attenuationColor^(d_in / attenuationDistance).
  const float n = 1.5f, d_out = 1.0f, d_in = 0.4f, D = 0.5f;
  const glm::vec3 color(0.9f, 0.6f, 0.3f);
  Material clear = glass(0.0f, n);
  Material tinted = glass(0.0f, n);
  tinted.volume->attenuation_color = color;
  tinted.volume->attenuation_distance = D;
  SlabScene s = slab_scene(clear, make_box(glm::vec3(-50.0f, -50.0f, -d_out / 2.0f),
                                           glm::vec3(50.0f, 50.0f, d_out / 2.0f)));
  s.scene.materials.push_back(tinted);
  add_mesh_instance(
      s.scene,
      make_box(glm::vec3(-40.0f, -40.0f, -d_in / 2.0f), glm::vec3(40.0f, 40.0f, d_in / 2.0f)),
      int(s.scene.materials.size()) - 1);
  const PathTracerResult res =
      render_path(s.scene, nullptr, ortho_camera(1.0f), deep_settings(16, 64));
  const double R = std::pow((n - 1.0) / (n + 1.0), 2.0);
  glm::vec3 expected;
  for (int c = 0; c < 3; ++c) {
    const double a = std::pow(double(color[c]), d_in / D);
    expected[c] = float(s.Le[c] * (1.0 - R) * (1.0 - R) * a / (1.0 - R * R * a * a));
  }
  expect_uniform(res.color, expected, "nested slabs");
}

// The stack of non-absorbing interfaces' transmittance, light reflected back and forth
// between them incoherently: two stacks of transmittance T1, T2 (a lossless stack reflects
// 1 - T from either side) transmit T1 T2 / (1 - (1 - T1)(1 - T2)).
double stack_transmittance(std::initializer_list<double> etas) {
  double T = 1.0;
  for (double eta : etas) {
    const double r = std::pow((eta - 1.0) / (eta + 1.0), 2.0);
    T = T * (1.0 - r) / (1.0 - (1.0 - T) * r);
  }
  return T;
}

TEST(PathTracerGlass, OverlappingVolumesTakeTheInnermostMediumsIor) {
  // A liquid slab (ior 1.33, z in [-0.2, 0.8]) reaching into a glass slab (ior 1.5, z in
  // [-0.5, 0.5]), as the built-in liquid reaches into its glass: seen from above, the path
  // enters the liquid (air/liquid), then the glass (liquid/glass: the glass is now the
  // innermost medium), leaves the liquid's bottom face inside the glass (glass/glass: no
  // interface) and leaves the glass (glass/air). Taking the liquid's own ior on leaving it
  // (as the first version did) bends the path there and made this 21% darker.
  const float n_glass = 1.5f, n_liquid = 1.33f;
  SlabScene s = slab_scene(glass(0.0f, n_glass), make_box(glm::vec3(-50.0f, -50.0f, -0.5f),
                                                          glm::vec3(50.0f, 50.0f, 0.5f)));
  s.scene.materials.push_back(glass(0.0f, n_liquid));
  add_mesh_instance(s.scene,
                    make_box(glm::vec3(-40.0f, -40.0f, -0.2f), glm::vec3(40.0f, 40.0f, 0.8f)),
                    int(s.scene.materials.size()) - 1);
  const PathTracerResult res =
      render_path(s.scene, nullptr, ortho_camera(1.0f), deep_settings(16, 1024));
  const double T = stack_transmittance({n_liquid, n_glass / n_liquid, n_glass});
  expect_uniform(res.color, s.Le * float(T), "overlapping slabs");
}

TEST(PathTracerGlass, ThinWalledSheetsTransmitOneMinusFresnel) {
  // A thin wall (core/transmission.h): no bending, no eta^2, one interface's Fresnel:
  // Le (1 - R). Thin because the material has no volume, or because the mesh is open.
  const float n = 1.5f;
  const double R = std::pow((n - 1.0) / (n + 1.0), 2.0);
  Material no_volume = glass(0.0f, n);
  no_volume.volume.reset();
  Material open_volume = glass(0.0f, n);
  for (int k = 0; k < 2; ++k) {
    Mesh sheet = make_quad(glm::vec3(-50.0f, -50.0f, 0.0f), glm::vec3(100.0f, 0.0f, 0.0f),
                           glm::vec3(0.0f, 100.0f, 0.0f));
    sheet.closed = false;
    SlabScene s = slab_scene(k == 0 ? no_volume : open_volume, std::move(sheet));
    const PathTracerResult res =
        render_path(s.scene, nullptr, ortho_camera(1.0f), deep_settings(16, 32));
    expect_uniform(res.color, s.Le * float(1.0 - R), k == 0 ? "no volume" : "open mesh");
  }
}

TEST(PathTracerGlass, SphereOfIor1IsInvisible) {
  // Nothing reflects and nothing bends at ior 1, rough or smooth: the render equals the
  // render without the sphere (the same camera samples), pixel for pixel.
  SlabScene without = slab_scene(glass(0.0f), make_uv_sphere(0.5f, 64, 32), false);
  const PathTracerResult ref =
      render_path(without.scene, nullptr, ortho_camera(1.0f), deep_settings(16, 4));
  for (float roughness : {0.0f, 0.5f}) {
    SlabScene with = slab_scene(glass(roughness, 1.0f), make_uv_sphere(0.5f, 64, 32));
    const PathTracerResult res =
        render_path(with.scene, nullptr, ortho_camera(1.0f), deep_settings(16, 4));
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x)
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(res.color.rgb(x, y)[c], ref.color.rgb(x, y)[c], 1e-5f)
              << "roughness " << roughness << " pixel " << x << "," << y;
  }
}

TEST(PathTracerGlass, DispersionOfInfiniteAbbeNumberIsNoDispersion) {
  // dispersion -> 0 (V_d -> infinity): every channel's ior is the material's, so the only
  // difference is the per-path channel choice, unbiased (E[3 e_c] = 1). A glass sphere over
  // a coloured emitter: the two renders' per-pixel difference has mean 0 within 4 standard
  // errors.
  Material plain = glass(0.1f, 1.5f);
  Material dispersive = plain;
  dispersive.dispersion = DispersionExtension{1e-7f};
  SlabScene a = slab_scene(plain, make_uv_sphere(0.6f, 64, 32));
  SlabScene b = slab_scene(dispersive, make_uv_sphere(0.6f, 64, 32));
  const Environment env = Environment::constant(glm::vec3(0.5f));
  const PathTracerResult ra = render_path(a.scene, &env, ortho_camera(1.0f), deep_settings(24, 64));
  const PathTracerResult rb = render_path(b.scene, &env, ortho_camera(1.0f), deep_settings(24, 64));
  for (int c = 0; c < 3; ++c) {
    std::vector<double> r;
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < 24; ++x)
        r.push_back(double(rb.color.rgb(x, y)[c]) - ra.color.rgb(x, y)[c]);
    const ResidualStats s = residual_stats(r);
    EXPECT_LT(std::fabs(s.mean), 4.0 * s.std_error) << "channel " << c << ": " << s.mean;
    EXPECT_GT(s.std_error, 0.0);  // the channel choice did happen (it adds noise)
  }
}

TEST(PathTracerGlass, BadInputNeverGivesNanOrInf) {
  // ior below 1 and 0, zero and infinite attenuation distances, black attenuation.
  for (float ior : {0.0f, 0.5f, 1.0f, 1e6f})
    for (float dist : {0.0f, 1e-8f, std::numeric_limits<float>::infinity()}) {
      Material m = glass(0.3f, ior);
      m.volume->attenuation_distance = dist;
      m.volume->attenuation_color = glm::vec3(0.0f, 0.5f, 1.0f);
      m.dispersion = DispersionExtension{5.0f};
      const Scene scene = sphere_scene(m);
      const Environment env = Environment::constant(glm::vec3(kL));
      const PathTracerResult res =
          render_path(scene, &env, ortho_camera(kHalf), deep_settings(8, 4));
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
          const glm::vec3 c = res.color.rgb(x, y);
          ASSERT_TRUE(std::isfinite(c.x + c.y + c.z) && c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f)
              << "ior " << ior << " distance " << dist;
        }
    }
}

}  // namespace
}  // namespace pbrkit::test
