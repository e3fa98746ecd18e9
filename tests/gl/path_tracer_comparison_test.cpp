// The OpenGL renderer against the path tracer (the ground truth):
//  * one point light, no environment, direct lighting only: both compute the same
//    integral exactly (a delta light needs no sampling), so they agree to within the path
//    tracer's pixel-footprint noise;
//  * the built-in `spheres` scene lit by the environment only: the path tracer restricted
//    to direct environment light (one bounce, the same BRDF) is the truth and the split-sum
//    image must stay within the measured per-sphere bound (see the table printed below
//    and BENCHMARKS.md / the report for where the error comes from).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
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

// The furnace sphere under one point light, GL against the 1-bounce path tracer, with the
// material as `setup` leaves it.
void expect_point_light_agrees(const std::function<void(Scene&, Material&)>& setup) {
  testing::context();
  Scene scene = builtin_scene("furnace");
  Material& m = scene.materials.at(0);
  m.base_color_factor = glm::vec4(0.9f, 0.6f, 0.3f, 1.0f);
  m.metallic_factor = 0.5f;
  m.roughness_factor = 0.4f;
  setup(scene, m);
  Light light;
  light.type = Light::Type::kPoint;
  light.position = glm::vec3(2.0f, 3.0f, 4.0f);
  light.intensity = 40.0f;
  scene.lights.push_back(light);
  constexpr int kSize = 64;
  const Camera camera = select_camera(scene, std::nullopt, 1.0f);

  RenderSettings gl_settings;
  gl_settings.msaa = 1;
  const Image gl = render_headless(scene, camera, kSize, kSize, nullptr, nullptr, gl_settings);

  PathTracerSettings pt;
  pt.width = pt.height = kSize;
  pt.spp = 16;
  pt.noise_threshold = 0.0f;
  pt.max_bounces = 1;
  pt.filter = PixelFilter::kBox;
  const Image truth = render_path(scene, nullptr, camera, pt).color;

  // Interior pixels only: at the silhouette the pixel footprint (path tracer) and the
  // tessellated outline (GL) legitimately differ.
  double sum_rel = 0.0;
  std::vector<double> rels;
  int pixels = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const auto mu = testing::sphere_hit_cosine(testing::pixel_ray(camera, x, y, kSize, kSize),
                                                 glm::vec3(0.0f), 1.0f);
      if (!mu || *mu < 0.3f) continue;
      const glm::vec3 a = gl.rgb(x, y), b = truth.rgb(x, y);
      const double rel = std::abs(double(a.r + a.g + a.b) - double(b.r + b.g + b.b)) /
                         (double(b.r + b.g + b.b) + 0.03);
      sum_rel += rel;
      rels.push_back(rel);
      ++pixels;
    }
  ASSERT_GT(pixels, 500);
  const double mean_rel = sum_rel / pixels;
  std::sort(rels.begin(), rels.end());
  const double p98 = rels[rels.size() * 98 / 100];
  std::printf(
      "point light: %d pixels, mean relative difference %.4f, 98th percentile %.4f, "
      "largest %.4f\n",
      pixels, mean_rel, p98, rels.back());
  // The mean is the test of "the same integral"; a few pixels on the highlight's steep
  // flank differ more because the path tracer averages the pixel's footprint (box filter)
  // where GL shades the pixel centre.
  EXPECT_LT(mean_rel, 0.01);
  EXPECT_LT(p98, 0.03);
}

TEST(GlVersusPathTracer, PointLightAgreesWithinNoise) {
  expect_point_light_agrees([](Scene&, Material&) {});
}

// Every KHR_materials surface extension at once (clearcoat, sheen, ior, specular,
// anisotropy along tangents around the sphere's axis, iridescence), so the fragment
// shader's inputs (factors, the anisotropy frame, the coat normal) are the path tracer's.
TEST(GlVersusPathTracer, PointLightWithExtensionsAgreesWithinNoise) {
  expect_point_light_agrees([](Scene& scene, Material& m) {
    m.ior = 1.8f;
    m.specular = SpecularExtension{0.8f, {}, glm::vec3(1.0f, 0.8f, 0.6f), {}};
    ClearcoatExtension coat;
    coat.factor = 0.7f;
    coat.roughness_factor = 0.15f;
    m.clearcoat = coat;
    SheenExtension sheen;
    sheen.color_factor = glm::vec3(0.3f, 0.6f, 0.9f);
    sheen.roughness_factor = 0.5f;
    m.sheen = sheen;
    AnisotropyExtension aniso;
    aniso.strength = 0.8f;
    aniso.rotation = 0.5f;
    m.anisotropy = aniso;
    IridescenceExtension irid;
    irid.factor = 0.5f;
    m.iridescence = irid;
    for (Mesh& mesh : scene.meshes) {
      mesh.tangents.clear();
      for (const glm::vec3& p : mesh.positions) {
        const glm::vec3 t(-p.z, 0.0f, p.x);
        const float l = glm::length(t);
        mesh.tangents.emplace_back(l > 1e-4f ? t / l : glm::vec3(1.0f, 0.0f, 0.0f), 1.0f);
      }
    }
  });
}

TEST(GlVersusPathTracer, SplitSumSpheresWithinMeasuredBound) {
  testing::context();
  // The built-in spheres moved 3x further apart (same meshes and materials), framed by the
  // automatic camera: at spacing 1 the neighbours hide up to a fifth of each sphere's
  // environment from the 1-bounce path tracer, a visibility effect the split sum (which has
  // no shadowing) cannot show and which is not what this test measures.
  constexpr float kSpread = 3.0f;
  Scene scene = builtin_scene("spheres");
  for (Instance& inst : scene.instances)
    inst.transform[3] = glm::vec4(glm::vec3(inst.transform[3]) * kSpread, 1.0f);
  scene.cameras.clear();
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  BakeOptions bake;
  bake.face_size = 64;
  bake.min_face_size = 4;
  bake.samples = 128;
  bake.irradiance_size = 8;
  bake.lut_size = 16;
  const IblMaps maps = ibl_maps_from_bake(bake_environment(env, bake), env);
  constexpr int kSize = 448;
  const Camera camera = select_camera(scene, std::nullopt, 1.0f);
  RenderSettings gl_settings;
  gl_settings.msaa = 1;
  const Image gl = render_headless(scene, camera, kSize, kSize, &env, &maps, gl_settings);

  PathTracerSettings pt;
  pt.width = pt.height = kSize;
  pt.spp = 32;
  pt.noise_threshold = 0.0f;
  pt.max_bounces = 1;
  pt.filter = PixelFilter::kBox;
  const Image truth = render_path(scene, &env, camera, pt).color;

  // Per sphere: mean radiance (luminance-free sum of RGB) over its pixels, GL vs truth.
  double errors[7][7] = {};
  for (int row = 0; row < 7; ++row)
    for (int col = 0; col < 7; ++col) {
      const glm::vec3 centre = kSpread * glm::vec3(float(col - 3), float(row - 3), 0.0f);
      const testing::SphereSums sums = testing::sphere_sums(gl, truth, camera, centre, 0.4f, 0.2f);
      ASSERT_GE(sums.pixels, 30) << "row " << row << ", column " << col;
      const double sa = sums.a, sb = sums.b;
      errors[row][col] = (sa - sb) / sb;
    }
  std::printf("relative error of the per-sphere mean, GL split sum vs path tracer (1 bounce)\n");
  std::printf("rows: metallic 1 (top) .. 0 (bottom); columns: roughness 0.05 .. 1\n");
  double worst = 0.0, sum = 0.0;
  for (int row = 6; row >= 0; --row) {
    for (int col = 0; col < 7; ++col) {
      std::printf(" %+7.3f", errors[row][col]);
      worst = std::max(worst, std::abs(errors[row][col]));
      sum += std::abs(errors[row][col]);
    }
    std::printf("\n");
  }
  std::printf("mean |error| %.4f, largest %.4f\n", sum / 49.0, worst);
  // Measured (2-core Debian 12, llvmpipe), with the reference model of glTF Appendix B and
  // compensation on (the reference model's default), over each sphere's inner pixels (30 or
  // more at 448 x 448; gl_image_test_util.h's interior_pixel): mean |error| 0.024, largest
  // 0.052 (metallic 0.67, roughness 0.05: a near-mirror of the bright sky). Counting the
  // silhouette pixels, at 224 x 224, it read 0.048 and 0.21: the path tracer's box filter
  // mixes the environment behind a sphere into its silhouette pixels, which GL shades at the
  // centre, most visibly on the mirrors. What remains is the split sum's own: the dielectrics
  // 2-5% bright (the prefilter's n = v = r lobe is rotationally symmetric about r, while the
  // true lobe at high roughness is stretched and tilted towards the normal, and the split
  // sum weights the diffuse by the specular albedo at n.v alone). The bounds, about twice
  // the measurement, leave room for the path tracer's 32-sample noise and another driver.
  EXPECT_LT(sum / 49.0, 0.045);
  EXPECT_LT(worst, 0.1);
}

// The built-in `instances` field (10,000 instances of one rock, some mirrored, some
// squashed) lit by the environment only, GL's split sum against the 1-bounce path tracer:
// both must draw the same instances the same way. Compared per tile of 8 x 8 pixels (a
// rock covers a few pixels, so per-object means would be silhouette noise); the glowing
// rock's emission is switched off (GL does not light with emissive surfaces).
TEST(GlVersusPathTracer, InstancesFieldWithinMeasuredBound) {
  testing::context();
  Scene scene = builtin_scene("instances");
  for (Material& m : scene.materials) m.emissive_factor = glm::vec3(0.0f);
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  const IblMaps maps = testing::small_ibl_maps(env);
  constexpr int kSize = 128, kTile = 8;
  const Camera camera = select_camera(scene, std::nullopt, 1.0f);
  RenderSettings gl_settings;
  gl_settings.msaa = 4;
  const Image gl = render_headless(scene, camera, kSize, kSize, &env, &maps, gl_settings);

  PathTracerSettings pt;
  pt.width = pt.height = kSize;
  pt.spp = 16;
  pt.noise_threshold = 0.0f;
  pt.max_bounces = 1;
  pt.filter = PixelFilter::kBox;
  const Image truth = render_path(scene, &env, camera, pt).color;

  std::vector<double> errors;
  for (int ty = 0; ty < kSize / kTile; ++ty)
    for (int tx = 0; tx < kSize / kTile; ++tx) {
      double sa = 0.0, sb = 0.0;
      for (int y = ty * kTile; y < (ty + 1) * kTile; ++y)
        for (int x = tx * kTile; x < (tx + 1) * kTile; ++x) {
          const glm::vec3 a = gl.rgb(x, y), b = truth.rgb(x, y);
          sa += double(a.r + a.g + a.b);
          sb += double(b.r + b.g + b.b);
        }
      errors.push_back((sa - sb) / sb);
    }
  double sum = 0.0, worst = 0.0;
  for (const double e : errors) {
    sum += std::abs(e);
    worst = std::max(worst, std::abs(e));
  }
  const double mean = sum / double(errors.size());
  std::printf(
      "instances: relative error of 8x8 tile means, GL vs path tracer (1 bounce): mean "
      "|error| %.4f, largest %.4f\n",
      mean, worst);
  // Measured (2-core Debian 12, llvmpipe): mean |error| 0.091, largest 0.42, in the nearest
  // rows, where GL's split sum lights the large rocks and the ground between them with the
  // whole environment while the path tracer sees what the neighbours hide (the same
  // visibility effect the spheres test above spreads its spheres to avoid). The bounds
  // leave room for the path tracer's noise.
  EXPECT_LT(mean, 0.12);
  EXPECT_LT(worst, 0.5);
}

}  // namespace
}  // namespace pbrkit::gl
