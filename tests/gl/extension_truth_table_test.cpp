// The split-sum error of each KHR_materials_* extension (issue 11): every built-in
// extension scene (a control sphere and a sweep per row) rendered by the OpenGL renderer
// and by the path tracer restricted to direct environment light (one bounce, the same
// layered BSDF), the per-sphere relative error of the mean radiance printed as a table
// (docs/SPLIT_SUM_ERRORS.md records them) and held to the bound measured for that scene.
//
// As in path_tracer_comparison_test.cpp the spheres are moved apart (3x) so no sphere
// hides another's environment from the path tracer, which the split sum cannot show.
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

struct TruthCase {
  const char* scene;
  double mean_bound;   ///< bound on the mean |error| over the scene's spheres
  double worst_bound;  ///< bound on the largest |error|
};

class ExtensionTruthTable : public ::testing::TestWithParam<TruthCase> {};

TEST_P(ExtensionTruthTable, SplitSumWithinMeasuredBound) {
  testing::context();
  const TruthCase& tc = GetParam();
  constexpr float kSpread = 3.0f;
  Scene scene = builtin_scene(tc.scene);
  // Sphere centres and radii (world), then spread apart.
  std::vector<glm::vec3> centres;
  std::vector<float> radii;
  for (Instance& inst : scene.instances) {
    const Mesh& mesh = scene.meshes[std::size_t(inst.mesh)];
    float r = 0.0f;
    for (const glm::vec3& p : mesh.positions) r = std::max(r, glm::length(p));
    r *= glm::length(glm::vec3(inst.transform[0]));
    inst.transform[3] = glm::vec4(glm::vec3(inst.transform[3]) * kSpread, 1.0f);
    centres.push_back(glm::vec3(inst.transform[3]));
    radii.push_back(r);
  }
  scene.cameras.clear();
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  BakeOptions bake;
  bake.face_size = 64;
  bake.min_face_size = 4;
  bake.samples = 128;
  bake.irradiance_size = 8;
  bake.lut_size = 32;
  const IblMaps maps = ibl_maps_from_bake(bake_environment(env, bake), env);
  constexpr int kWidth = 384, kHeight = 224;
  const Camera camera = select_camera(scene, std::nullopt, float(kWidth) / kHeight);
  RenderSettings gl_settings;
  gl_settings.msaa = 1;
  const Image gl = render_headless(scene, camera, kWidth, kHeight, &env, &maps, gl_settings);

  PathTracerSettings pt;
  pt.width = kWidth;
  pt.height = kHeight;
  pt.spp = 32;
  pt.noise_threshold = 0.0f;
  pt.max_bounces = 1;
  pt.filter = PixelFilter::kBox;
  const Image truth = render_path(scene, &env, camera, pt).color;

  std::printf("%s: relative error of the per-sphere mean, GL split sum vs path tracer (1 bounce)\n",
              tc.scene);
  double worst = 0.0, sum = 0.0;
  int counted = 0;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const testing::SphereSums sums =
        testing::sphere_sums(gl, truth, camera, centres[i], radii[i], 0.2f);
    const double sa = sums.a, sb = sums.b;
    const int n = sums.pixels;
    const Material& m = scene.material_of(scene.meshes[std::size_t(scene.instances[i].mesh)]);
    if (n < 50 || !(sb > 0.0)) {
      std::printf("  %-28s (too few pixels: %d)\n", m.name.c_str(), n);
      continue;
    }
    const double e = (sa - sb) / sb;
    std::printf("  %-28s %+7.3f  (%d px)\n", m.name.c_str(), e, n);
    worst = std::max(worst, std::abs(e));
    sum += std::abs(e);
    ++counted;
  }
  ASSERT_GT(counted, int(centres.size()) / 2);
  std::printf("  mean |error| %.4f, largest %.4f\n", sum / counted, worst);
  EXPECT_LT(sum / counted, tc.mean_bound);
  EXPECT_LT(worst, tc.worst_bound);
}

// Bounds: measured on the 2-core Debian 12 machine with llvmpipe (the tables in
// docs/SPLIT_SUM_ERRORS.md: mean |error| / largest), about 1.5x for the path tracer's noise
// at 32 spp (about 1% per sphere) and the bake's sampling. Anisotropy's split sum is the
// Sample Viewer's bent-reflection approximation of a lobe the path tracer integrates
// exactly: it is 20-100% bright on strongly anisotropic spheres (measured 0.33 / 1.02).
INSTANTIATE_TEST_SUITE_P(Scenes, ExtensionTruthTable,
                         ::testing::Values(TruthCase{"clearcoat", 0.06, 0.15},    // 0.035 / 0.081
                                           TruthCase{"sheen", 0.19, 0.32},        // 0.129 / 0.217
                                           TruthCase{"anisotropy", 0.5, 1.5},     // 0.33 / 1.02
                                           TruthCase{"iridescence", 0.06, 0.18},  // 0.038 / 0.114
                                           TruthCase{"specular", 0.045, 0.12},    // 0.026 / 0.077
                                           TruthCase{"ior", 0.03, 0.08},          // 0.017 / 0.045
                                           TruthCase{"unlit", 0.03, 0.06}),       // 0.018 / 0.036
                         [](const auto& info) { return std::string(info.param.scene); });

}  // namespace
}  // namespace pbrkit::gl
