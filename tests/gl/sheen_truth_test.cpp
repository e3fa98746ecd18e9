// The sheen's image-based lighting against the path tracer on a row of sheen-dominated
// spheres (the built-in sheen scene's dark rough base under a white sheen of roughness 0.3,
// 0.6 and 1.0) under two non-uniform environments: the built-in city map and an orientation
// test map (coloured longitude bands, a bright top cap, a dark bottom cap: the sheen's rims
// show which side of the environment the lobe gathers from). GL against the path tracer
// restricted to direct environment light (one bounce, the same layered BSDF), per sphere and
// channel (over the pixels with n.v > 0.2 whose whole footprint sees the sphere): the error
// of the mean radiance is held to its measured value
// (docs/SPLIT_SUM_ERRORS.md, "sheen grid"), as ExtensionTruthTable holds the built-in
// scenes, and so is the error of what the sheen adds (the sphere with the sheen less the same
// sphere without it, in each renderer); both are bounded by 15%.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl_image_test_util.h"
#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/load.h"

namespace pbrkit::gl {
namespace {

// The orientation test map of the WebGL peer's make-env.mjs --kind probe, written out here
// (row 0 = +Y): longitude bands blue, green, red, yellow; a white cap above 63 degrees of
// elevation, a dark one below -63; a bright white dot at the image centre.
Environment probe_environment() {
  constexpr int kW = 256, kH = 128;
  Environment env;
  env.map = Image(kW, kH, 3, 0.0f);
  env.source = "probe";
  const glm::vec3 bands[] = {
      {0.1f, 0.1f, 1.0f}, {0.1f, 1.0f, 0.1f}, {1.0f, 0.1f, 0.1f}, {1.0f, 1.0f, 0.1f}};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float u = (float(x) + 0.5f) / kW, v = (float(y) + 0.5f) / kH;
      glm::vec3 c = bands[std::min(3, int(u * 4.0f))];
      if (v < 0.15f) c = glm::vec3(1.5f);
      if (v > 0.85f) c = glm::vec3(0.05f);
      const float du = std::min(std::abs(u - 0.5f), 1.0f - std::abs(u - 0.5f)), dv = v - 0.5f;
      if (du * du * 4.0f + dv * dv < 0.02f * 0.02f) c = glm::vec3(8.0f);
      env.map.set_rgb(x, y, c);
    }
  return env;
}

struct SphereError {
  float sheen_roughness;
  double r, g, b;     ///< (GL - path) / path of the sphere's mean radiance
  double sr, sg, sb;  ///< the same of what the sheen adds to it
};

struct GridCase {
  const char* environment;  ///< "city" or "probe"
  std::vector<SphereError> measured;
};

// Per-sphere mean radiance of both renderers, and the variance of the path tracer's mean.
struct SphereMeans {
  glm::dvec3 gl{0.0}, pt{0.0}, pt_variance{0.0};
};

class SheenGridTruth : public ::testing::TestWithParam<GridCase> {};

TEST_P(SheenGridTruth, PerSphereErrorsAsMeasuredAndSheenWithinBound) {
  testing::context();
  const GridCase& gc = GetParam();
  const Environment env = std::string(gc.environment) == "probe"
                              ? probe_environment()
                              : load_environment_or_default("", 0.0f, 1.0f);
  BakeOptions bake;
  bake.face_size = 64;
  bake.min_face_size = 4;
  bake.samples = 128;
  bake.irradiance_size = 8;
  bake.lut_size = 32;
  const IblMaps maps = ibl_maps_from_bake(bake_environment(env, bake), env);
  constexpr int kWidth = 384, kHeight = 128;
  // The built-in sheen scene's dark base and sphere mesh, three spheres in a row 3 apart
  // (none hides another's environment from the path tracer).
  auto render = [&](bool sheen_on) {
    Scene scene = builtin_scene("sheen");
    const Instance one = scene.instances.front();
    const Mesh mesh = scene.meshes[std::size_t(one.mesh)];  // a copy: meshes grows below
    float radius = 0.0f;
    for (const glm::vec3& p : mesh.positions) radius = std::max(radius, glm::length(p));
    radius *= glm::length(glm::vec3(one.transform[0]));
    scene.instances.clear();
    std::vector<glm::vec3> centres;
    for (std::size_t i = 0; i < gc.measured.size(); ++i) {
      Material m = scene.material_of(mesh);
      m.name = "sheen_" + std::to_string(gc.measured[i].sheen_roughness);
      if (sheen_on) {
        m.sheen.emplace();
        m.sheen->color_factor = glm::vec3(1.0f);
        m.sheen->roughness_factor = gc.measured[i].sheen_roughness;
      }
      scene.materials.push_back(m);
      Mesh copy = mesh;
      copy.material = int(scene.materials.size()) - 1;
      scene.meshes.push_back(copy);
      Instance inst = one;
      centres.emplace_back(3.0f * (float(i) - 0.5f * float(gc.measured.size() - 1)), 0.0f, 0.0f);
      inst.mesh = int(scene.meshes.size()) - 1;
      inst.transform[3] = glm::vec4(centres.back(), 1.0f);
      scene.instances.push_back(inst);
    }
    scene.cameras.clear();
    const Camera camera = select_camera(scene, std::nullopt, float(kWidth) / kHeight);
    RenderSettings gl_settings;
    gl_settings.msaa = 1;
    const Image gl = render_headless(scene, camera, kWidth, kHeight, &env, &maps, gl_settings);
    PathTracerSettings pt;
    pt.width = kWidth;
    pt.height = kHeight;
    pt.spp = 128;
    pt.noise_threshold = 0.0f;
    pt.max_bounces = 1;
    pt.filter = PixelFilter::kBox;
    const PathTracerResult truth = render_path(scene, &env, camera, pt);
    std::vector<SphereMeans> means;
    for (const glm::vec3& centre : centres) {
      SphereMeans m;
      int pixels = 0;
      for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
          const auto mu = testing::sphere_hit_cosine(
              testing::pixel_ray(camera, x, y, kWidth, kHeight), centre, radius);
          if (!mu || *mu < 0.2f) continue;
          // Only pixels whose neighbours see the sphere too: the path tracer's box filter
          // averages over the whole pixel, the GL image (MSAA 1) shades its centre, so a
          // pixel straddling the silhouette mixes in the environment behind the sphere in
          // one image only (with spheres ~8 px in radius, a tenth of the disc).
          bool inside = true;
          for (int dy = -1; dy <= 1 && inside; ++dy)
            for (int dx = -1; dx <= 1 && inside; ++dx)
              inside =
                  testing::sphere_hit_cosine(
                      testing::pixel_ray(camera, x + dx, y + dy, kWidth, kHeight), centre, radius)
                      .has_value();
          if (!inside) continue;
          const std::size_t p = std::size_t(y) * std::size_t(kWidth) + std::size_t(x);
          const double half = double(truth.film.count[p]) / 2.0;
          const glm::dvec3 sum(truth.film.sum[p]), even(truth.film.sum_even[p]);
          const glm::dvec3 diff = (even / half - (sum - even) / half) / 2.0;
          m.gl += glm::dvec3(gl.rgb(x, y));
          m.pt += sum / double(truth.film.count[p]);
          m.pt_variance += diff * diff;
          ++pixels;
        }
      EXPECT_GE(pixels, 50);
      const double n = std::max(pixels, 1);
      m.gl /= n;
      m.pt /= n;
      m.pt_variance /= n * n;
      means.push_back(m);
    }
    return means;
  };
  const std::vector<SphereMeans> with = render(true), without = render(false);

  std::printf(
      "sheen grid under %s: (GL - path) / path per sphere, R G B, +- standard error; then of "
      "what the sheen adds\n",
      gc.environment);
  for (std::size_t i = 0; i < gc.measured.size(); ++i) {
    const SphereMeans& a = with[i];
    const SphereMeans& b = without[i];
    const SphereError& want = gc.measured[i];
    const glm::dvec3 expected(want.r, want.g, want.b);
    glm::dvec3 e(0.0), sigma(0.0), es(0.0), sigma_s(0.0);
    for (int c = 0; c < 3; ++c) {
      ASSERT_GT(a.pt[c], 0.0);
      e[c] = (a.gl[c] - a.pt[c]) / a.pt[c];
      sigma[c] = (1.0 + e[c]) * std::sqrt(a.pt_variance[c]) / a.pt[c];
      const double added_pt = a.pt[c] - b.pt[c], added_gl = a.gl[c] - b.gl[c];
      ASSERT_GT(added_pt, 0.0);
      es[c] = (added_gl - added_pt) / added_pt;
      sigma_s[c] = (1.0 + es[c]) * std::sqrt(a.pt_variance[c] + b.pt_variance[c]) / added_pt;
    }
    std::printf(
        "      {%.1ff, %+.3f, %+.3f, %+.3f, %+.3f, %+.3f, %+.3f},  // +- %.3f %.3f %.3f; %.3f "
        "%.3f %.3f\n",
        double(want.sheen_roughness), e.r, e.g, e.b, es.r, es.g, es.b, sigma.r, sigma.g, sigma.b,
        sigma_s.r, sigma_s.g, sigma_s.b);
    for (int c = 0; c < 3; ++c) {
      // Each as measured, within 4 standard errors of the difference of two path-traced
      // estimates plus 1% for the bake and another driver (as ExtensionTruthTable).
      EXPECT_NEAR(e[c], expected[c], 4.0 * std::sqrt(2.0) * sigma[c] + 0.01)
          << "roughness " << want.sheen_roughness << " channel "
          << "RGB"[c];
      const double want_s[3] = {want.sr, want.sg, want.sb};
      EXPECT_NEAR(es[c], want_s[c], 4.0 * std::sqrt(2.0) * sigma_s[c] + 0.01)
          << "sheen's part, roughness " << want.sheen_roughness << " channel "
          << "RGB"[c];
      // The goal: no sphere, and not what the sheen adds, more than 15% off the truth
      // (measured: within 2.6%; the Sample Viewer's lookup was up to 22% and 32% off).
      EXPECT_LT(std::abs(e[c]), 0.15) << "roughness " << want.sheen_roughness << " channel "
                                      << "RGB"[c];
      EXPECT_LT(std::abs(es[c]), 0.15) << "roughness " << want.sheen_roughness << " channel "
                                       << "RGB"[c];
    }
  }
}

// Measured on the 2-core Debian 12 machine with llvmpipe at 128 spp.
INSTANTIATE_TEST_SUITE_P(
    Environments, SheenGridTruth,
    ::testing::Values(GridCase{"city",
                               {{0.3f, -0.018, -0.019, -0.018, -0.016, -0.016, -0.018},
                                {0.6f, -0.009, -0.009, -0.009, -0.004, -0.003, -0.005},
                                {1.0f, -0.009, -0.009, -0.009, -0.003, -0.003, -0.005}}},
                      GridCase{"probe",
                               {{0.3f, -0.007, -0.007, -0.019, +0.001, -0.001, -0.026},
                                {0.6f, +0.004, +0.006, -0.009, +0.006, +0.007, -0.001},
                                {1.0f, +0.008, +0.011, -0.010, +0.000, +0.007, +0.001}}}),
    [](const auto& info) { return std::string(info.param.environment); });

}  // namespace
}  // namespace pbrkit::gl
