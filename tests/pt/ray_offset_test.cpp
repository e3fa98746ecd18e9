// Robust ray origins (Wachter & Binder 2019): grazing rays leaving a surface must neither
// hit the surface they leave (self-intersection, "shadow acne") nor escape a closed box
// through its edges (leaks), at small and large coordinates.
#include <gtest/gtest.h>

#include <cmath>

#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/ray_offset.h"
#include "pt/pt_test_util.h"

namespace pbrkit::test {
namespace {

void grazing_rays_in_box(glm::vec3 center, float size) {
  Scene scene;
  scene.source = "test:box";
  scene.materials.push_back(make_material(glm::vec3(0.5f), 0.0f, 1.0f));
  add_mesh_instance(scene, make_box(center - glm::vec3(size), center + glm::vec3(size), true), 0);
  const SceneGeometry geometry(scene);
  Pcg32 rng(5);
  int self_hits = 0, escapes = 0, shadowed = 0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    // A point on the floor (y = -size), found by tracing down so that it is exactly what
    // the renderer would compute from barycentrics.
    const glm::vec2 r = rng.next_2d() * 1.998f - 0.999f;
    const glm::vec3 start = center + glm::vec3(r.x * size, 0.0f, r.y * size);
    std::uint32_t g, prim;
    float t, u, v;
    ASSERT_TRUE(geometry.intersect(start, glm::vec3(0, -1, 0), 1e30f, ~0u, g, prim, t, u, v));
    SurfaceHit hit = geometry.resolve(g, prim, t, u, v);
    // Grazing directions: elevation 1e-5 .. 1e-2 rad above the floor, any azimuth.
    const float elevation = std::pow(10.0f, -5.0f + 3.0f * rng.next_float());
    const float phi = 2.0f * kPi * rng.next_float();
    const glm::vec3 d =
        glm::normalize(glm::vec3(std::cos(phi) * std::cos(elevation), std::sin(elevation),
                                 std::sin(phi) * std::cos(elevation)));
    const glm::vec3 o = offset_ray_origin(hit.p, hit.ng);
    if (!geometry.intersect(o, d, 1e30f, ~0u, g, prim, t, u, v)) {
      ++escapes;
      continue;
    }
    const SurfaceHit h2 = geometry.resolve(g, prim, t, u, v);
    // The floor's normal is +Y (inward box); any hit with that normal is a self-hit.
    if (h2.ng.y > 0.5f) ++self_hits;
    // Shadow ray along the floor towards another floor point (both offset): the floor
    // must not shadow itself.
    const glm::vec3 target(0.5f * (hit.p.x + center.x), hit.p.y, 0.5f * (hit.p.z + center.z));
    const glm::vec3 to = offset_ray_origin(target, hit.ng) - o;
    if (glm::length(to) > 1e-3f * size &&
        geometry.occluded(o, glm::normalize(to), glm::length(to) * 0.999f))
      ++shadowed;
  }
  EXPECT_EQ(self_hits, 0) << "of " << n;
  EXPECT_EQ(escapes, 0) << "of " << n;
  EXPECT_EQ(shadowed, 0) << "of " << n;
}

TEST(RayOffset, GrazingRaysNearTheOrigin) {
  grazing_rays_in_box(glm::vec3(0.0f), 1.0f);
}
TEST(RayOffset, GrazingRaysFarFromTheOrigin) {
  grazing_rays_in_box(glm::vec3(3000.0f, -1200.0f, 5000.0f), 10.0f);
}

TEST(RayOffset, OffsetIsTinyAndOnTheRightSide) {
  for (glm::vec3 p :
       {glm::vec3(0.0f), glm::vec3(1.0f, -2.0f, 3.0f), glm::vec3(1e4f, 1e-3f, -5e3f)}) {
    const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 1.0f, -0.2f));
    const glm::vec3 o = offset_ray_origin(p, n);
    EXPECT_GT(glm::dot(o - p, n), 0.0f);
    EXPECT_LT(glm::length(o - p), 1e-3f * std::max(1.0f, glm::length(p)));
  }
}

}  // namespace
}  // namespace pbrkit::test
