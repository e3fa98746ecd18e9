// Multiple importance sampling: light sampling alone, BSDF sampling alone and their MIS
// combination are three unbiased estimators of the same image, so their means must agree
// within the noise; and MIS (power heuristic) must have the lowest variance on Veach's
// classic failure cases: a glossy surface reflecting an area light (bad for light
// sampling) next to a rough one (bad for BSDF sampling).
#include <gtest/gtest.h>

#include <cmath>

#include "pt/pt_test_util.h"

namespace pbrkit::test {
namespace {

Scene veach_scene() {
  Scene scene;
  scene.source = "test:mis";
  scene.materials.push_back(make_material(glm::vec3(0.9f), 1.0f, 0.12f));  // glossy metal
  scene.materials.push_back(make_material(glm::vec3(0.8f), 0.0f, 1.0f));   // rough
  // A one-sided emitter facing down (-Z): the camera above sees its culled back face.
  scene.materials.push_back(make_material(glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(20.0f)));
  add_mesh_instance(scene, make_quad(glm::vec3(-1, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0, 2, 0)),
                    0);
  add_mesh_instance(scene, make_quad(glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0, 2, 0)),
                    1);
  add_mesh_instance(
      scene, make_quad(glm::vec3(-0.2f, -0.2f, 1.0f), glm::vec3(0, 0.4f, 0), glm::vec3(0.4f, 0, 0)),
      2);
  return scene;
}

struct Estimate {
  Image a, b;              // two independent renders (different seeds)
  double mean = 0.0;       // over pixels and both renders
  double mean_var = 0.0;   // variance of the image mean
  double pixel_var = 0.0;  // average per-pixel variance of one render
};

Estimate render(LightStrategy strategy) {
  const Scene scene = veach_scene();
  PathTracerSettings s;
  s.width = s.height = 24;
  s.spp = 32;
  s.noise_threshold = 0.0f;
  s.max_bounces = 1;
  s.strategy = strategy;
  s.threads = 2;
  Estimate e;
  s.seed = 1;
  e.a = render_path(scene, nullptr, ortho_camera(1.0f), s).color;
  s.seed = 2;
  e.b = render_path(scene, nullptr, ortho_camera(1.0f), s).color;
  const std::size_t n = e.a.pixel_count();
  for (int y = 0; y < e.a.height; ++y)
    for (int x = 0; x < e.a.width; ++x) {
      const double va = e.a.rgb(x, y).x, vb = e.b.rgb(x, y).x;
      e.mean += 0.5 * (va + vb) / double(n);
      // (A - B)^2 / 2 estimates one render's per-pixel variance without bias.
      const double v = 0.5 * (va - vb) * (va - vb);
      e.pixel_var += v / double(n);
      e.mean_var += 0.5 * v / double(n) / double(n);  // variance of (A+B)/2, averaged
    }
  return e;
}

TEST(PathTracerMis, StrategiesAgreeAndMisHasTheLowestVariance) {
  const Estimate mis = render(LightStrategy::kMis);
  const Estimate light = render(LightStrategy::kLightOnly);
  const Estimate bsdf = render(LightStrategy::kBsdfOnly);
  ASSERT_GT(mis.mean, 0.05);
  auto agree = [](const Estimate& p, const Estimate& q) {
    return std::fabs(p.mean - q.mean) < 4.0 * std::sqrt(p.mean_var + q.mean_var);
  };
  EXPECT_TRUE(agree(mis, light)) << mis.mean << " vs light " << light.mean << " +- "
                                 << std::sqrt(mis.mean_var + light.mean_var);
  EXPECT_TRUE(agree(mis, bsdf)) << mis.mean << " vs bsdf " << bsdf.mean << " +- "
                                << std::sqrt(mis.mean_var + bsdf.mean_var);
  EXPECT_TRUE(agree(light, bsdf)) << light.mean << " vs " << bsdf.mean;
  EXPECT_LT(mis.pixel_var, light.pixel_var);
  EXPECT_LT(mis.pixel_var, bsdf.pixel_var);
  RecordProperty("variance_mis", std::to_string(mis.pixel_var));
  RecordProperty("variance_light", std::to_string(light.pixel_var));
  RecordProperty("variance_bsdf", std::to_string(bsdf.pixel_var));
}

}  // namespace
}  // namespace pbrkit::test
