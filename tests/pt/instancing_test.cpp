// Instanced geometry in the path tracer (pt/geometry.h): one mesh placed several times
// renders as the same triangles copied into world space would; an emissive instance
// emits from its own world-space area (irradiance against a quadrature of the emitter);
// a closed volume placed twice absorbs in each instance by its own world-space thickness
// (Beer-Lambert through two slabs); and the geometry's memory follows unique triangles.
// Tolerances come from the measured noise (standard errors of mean residuals).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/ray_offset.h"
#include "pbrkit/util/error.h"
#include "pt/pt_test_util.h"

namespace pbrkit::test {
namespace {

// A mesh with no symmetry a mirror would hide: an irregular pentagonal prism.
Mesh asymmetric_prism() {
  return make_prism({{0.0f, -0.6f}, {0.7f, -0.2f}, {0.5f, 0.5f}, {-0.3f, 0.6f}, {-0.6f, 0.0f}},
                    1.0f);
}

// `mesh` copied into world space by `M`, as a loader that flattens instances would: normals
// by the inverse transpose, tangents by M (handedness flipped by a mirror), and the winding
// reversed under a mirror so that glTF's front faces stay the front (glTF 2.0, 3.7.4: a
// negative determinant makes the world-space winding clockwise).
Mesh flattened(const Mesh& mesh, const glm::mat4& M, bool keep_winding = false) {
  Mesh out = mesh;
  const glm::mat3 L(M);
  const glm::mat3 N = glm::transpose(glm::inverse(L));
  const bool mirror = glm::determinant(L) < 0.0f;
  for (glm::vec3& p : out.positions) p = glm::vec3(M * glm::vec4(p, 1.0f));
  for (glm::vec3& n : out.normals) n = glm::normalize(N * n);
  for (glm::vec4& t : out.tangents) t = glm::vec4(L * glm::vec3(t), mirror ? -t.w : t.w);
  if (mirror && !keep_winding)
    for (std::size_t i = 0; i + 2 < out.indices.size(); i += 3)
      std::swap(out.indices[i + 1], out.indices[i + 2]);
  return out;
}

struct Placement {
  glm::mat4 transform;
  int material;
  int mesh = 0;  // 0: the prism, 1: a sphere (smooth normals, where a wrong normal
                 // transform moves the highlights)
};

std::vector<Placement> placements() {
  using glm::rotate;
  using glm::scale;
  using glm::translate;
  const glm::mat4 I(1.0f);
  return {
      {translate(I, {-2.0f, 0.0f, 0.0f}), 0},
      // a mirror (negative scale along x)
      {translate(I, {1.6f, 0.0f, 0.2f}) * rotate(I, 0.5f, {0, 1, 0}) * scale(I, {-1, 1, 1}), 1},
      // a non-uniform scale
      {translate(I, {0.0f, 0.0f, -2.0f}) * scale(I, {1.6f, 0.5f, 1.0f}), 0},
      // rotated, scaled non-uniformly and mirrored along z
      {translate(I, {-0.3f, 1.4f, 1.2f}) * rotate(I, 0.7f, glm::normalize(glm::vec3(1, 1, 0))) *
           scale(I, {0.7f, 1.3f, -0.9f}),
       1},
      // the sphere, stretched and turned, and mirrored
      {translate(I, {1.8f, 0.6f, -1.2f}) * rotate(I, 0.4f, {0, 0, 1}) *
           scale(I, {1.8f, 0.6f, 1.0f}),
       3, 1},
      {translate(I, {-1.5f, 0.9f, 1.8f}) * scale(I, {-0.6f, 1.5f, 0.8f}), 3, 1},
  };
}

Material single_sided(glm::vec3 base, float metallic, float roughness) {
  return make_material(base, metallic, roughness);
}

// Both scenes: the prism on a floor, lit by a point light and a dim environment.
Scene field(bool instanced, bool keep_winding = false) {
  Scene scene;
  scene.source = instanced ? "test:instanced" : "test:flattened";
  scene.materials.push_back(single_sided({0.8f, 0.5f, 0.3f}, 0.0f, 0.5f));
  scene.materials.push_back(single_sided({0.3f, 0.6f, 0.9f}, 0.6f, 0.3f));
  scene.materials.push_back(single_sided({0.6f, 0.6f, 0.6f}, 0.0f, 1.0f));
  scene.materials.push_back(single_sided({0.9f, 0.8f, 0.5f}, 0.0f, 0.6f));
  const Mesh meshes[2] = {asymmetric_prism(), make_uv_sphere(0.5f, 32, 16)};
  // Materials belong to meshes: one shared mesh per material.
  int shared[4] = {-1, -1, -1, -1};
  for (const Placement& p : placements()) {
    const Mesh& mesh = meshes[p.mesh];
    if (!instanced) {
      add_mesh_instance(scene, flattened(mesh, p.transform, keep_winding), p.material);
    } else if (shared[p.material] < 0) {
      shared[p.material] = add_mesh_instance(scene, mesh, p.material, p.transform);
    } else {
      scene.instances.push_back({shared[p.material], p.transform, -1});
    }
  }
  add_mesh_instance(scene,
                    make_quad({-6.0f, 0.0f, 6.0f}, {12.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -12.0f}), 2);
  Light light;
  light.type = Light::Type::kPoint;
  light.intensity = 30.0f;
  light.position = {2.0f, 4.0f, 3.0f};
  scene.lights.push_back(light);
  Camera camera;
  camera.yfov = 0.9f;
  camera.camera_to_world = glm::inverse(
      glm::lookAt(glm::vec3(0.8f, 3.2f, 4.4f), glm::vec3(0.0f, 0.4f, 0.0f), {0, 1, 0}));
  scene.cameras.push_back(camera);
  return scene;
}

Image render_field(const Scene& scene, std::uint32_t seed) {
  const Environment env = Environment::constant(glm::vec3(0.3f));
  PathTracerSettings s = small_settings(64, 32);
  s.max_bounces = 4;
  s.seed = seed;
  return render_path(scene, &env, scene.cameras[0], s).color;
}

// The largest |mean residual| / standard error over 8x8-pixel blocks of a - b (independent
// renders: the residuals of a block are independent with mean 0 where the images agree).
double worst_block_z(const Image& a, const Image& b) {
  double worst = 0.0;
  for (int by = 0; by < a.height; by += 8)
    for (int bx = 0; bx < a.width; bx += 8) {
      std::vector<double> r;
      for (int y = by; y < by + 8; ++y)
        for (int x = bx; x < bx + 8; ++x) {
          const glm::vec3 d = a.rgb(x, y) - b.rgb(x, y);
          r.push_back(double(d.x + d.y + d.z));
        }
      const ResidualStats s = residual_stats(r);
      worst = std::max(worst, std::fabs(s.mean) / std::max(s.std_error, 1e-6));
    }
  return worst;
}

TEST(PathTracerInstancing, InstancesRenderAsTheirFlattenedCopies) {
  const Scene instanced = field(true);
  const Scene flat = field(false);
  {
    const SceneGeometry g(instanced);
    EXPECT_EQ(g.shared_meshes(), 3u);  // two prism meshes and the sphere, behind instances
    EXPECT_EQ(g.instanced(), 6u);
    const SceneGeometry f(flat);
    EXPECT_EQ(f.shared_meshes(), 0u);  // every mesh used once: flattened
  }
  const Image a = render_field(instanced, 1);
  const Image b = render_field(flat, 2);
  // 64 blocks: under agreement each z is about normal; 5 is far in its tail.
  const double z = worst_block_z(a, b);
  std::printf("instanced vs flattened: worst block |z| = %.2f\n", z);
  EXPECT_LT(z, 5.0);
  // The metric sees an orientation error: the same copies with the mirrored instances'
  // winding kept (their faces turned inside out) differ.
  const Image wrong = render_field(field(false, true), 3);
  const double z_wrong = worst_block_z(a, wrong);
  std::printf("instanced vs inside-out mirrors: worst block |z| = %.2f\n", z_wrong);
  EXPECT_GT(z_wrong, 10.0);
}

TEST(PathTracerInstancing, MirroredAndScaledHitsFaceOutAndHaveWorldAreas) {
  // A unit box placed twice (so it is instanced): mirrored in x, and scaled (2, 3, 0.5).
  Scene scene;
  scene.source = "test:boxes";
  scene.materials.push_back(make_material(glm::vec3(0.5f), 0.0f, 1.0f));
  const glm::mat4 mirror = glm::translate(glm::mat4(1.0f), {-5.0f, 0.0f, 0.0f}) *
                           glm::scale(glm::mat4(1.0f), {-1, 1, 1});
  const glm::mat4 stretch = glm::translate(glm::mat4(1.0f), {5.0f, 0.0f, 0.0f}) *
                            glm::scale(glm::mat4(1.0f), {2, 3, 0.5f});
  const int m = add_mesh_instance(scene, make_box(glm::vec3(-0.5f), glm::vec3(0.5f)), 0, mirror);
  scene.instances.push_back({m, stretch, -1});
  const SceneGeometry g(scene);
  ASSERT_EQ(g.instanced(), 2u);
  double area[2] = {0.0, 0.0};
  for (std::uint32_t i = 0; i < 2; ++i)
    for (std::uint32_t t = 0; t < scene.meshes[0].triangle_count(); ++t)
      area[i] += g.triangle_area(i, t);
  EXPECT_NEAR(area[0], 6.0, 1e-5);
  EXPECT_NEAR(area[1], 2.0 * (2 * 3 + 2 * 0.5 + 3 * 0.5), 1e-4);
  // Rays at each box from +z, +y and -y: the hit's normals face the ray (outward faces).
  for (const float cx : {-5.0f, 5.0f})
    for (const glm::vec3 d : {glm::vec3(0, 0, -1), glm::vec3(0, -1, 0), glm::vec3(0, 1, 0)}) {
      std::uint32_t geom, prim;
      float t, u, v;
      const glm::vec3 o = glm::vec3(cx, 0.1f, 0.05f) - 10.0f * d;
      ASSERT_TRUE(g.intersect(o, d, 100.0f, ~0u, geom, prim, t, u, v));
      const SurfaceHit h = g.resolve(geom, prim, t, u, v);
      EXPECT_EQ(h.geom, cx < 0.0f ? 0u : 1u);
      EXPECT_NEAR(glm::dot(h.ng, -d), 1.0f, 1e-5f) << "box at " << cx << ", ray " << d.y << d.z;
      EXPECT_GT(glm::dot(h.ns, -d), 0.99f);
      // The hit point lies on the ray.
      EXPECT_LT(glm::length(h.p - (o + t * d)), 1e-4f);
    }
}

// An emissive unit square instanced twice with different non-uniform scales; the first,
// facing down at height h over a grey floor, lights it; the second faces away. The floor's
// radiance at each pixel is the integral over the first emitter's world-space rectangle of
// f(wo, wi) Le cos_i cos_l / d^2, by a midpoint rule.
TEST(PathTracerInstancing, ScaledEmissiveInstanceEmitsByItsWorldArea) {
  const float h = 1.0f, Le = 2.0f, rho = 0.5f;
  const glm::vec2 size(1.6f, 0.7f);  // the lit instance's scale in x and y
  Scene scene;
  scene.source = "test:emitters";
  scene.materials.push_back(make_material(glm::vec3(rho), 0.0f, 1.0f));
  // Black and single-sided: seen from above (its back) it is culled and reflects nothing.
  scene.materials.push_back(make_material(glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(Le)));
  add_mesh_instance(scene, make_quad({-20, -20, 0}, {40, 0, 0}, {0, 40, 0}), 0);
  // The unit square at the origin facing -z (edges y then x).
  const int e = add_mesh_instance(
      scene, make_quad({-0.5f, -0.5f, 0.0f}, {0, 1, 0}, {1, 0, 0}), 1,
      glm::translate(glm::mat4(1.0f), {0, 0, h}) * glm::scale(glm::mat4(1.0f), {size, 1.0f}));
  scene.instances.push_back({e,
                             glm::translate(glm::mat4(1.0f), {0, 0, -5}) *
                                 glm::rotate(glm::mat4(1.0f), float(kPi), {1, 0, 0}) *
                                 glm::scale(glm::mat4(1.0f), {3.0f, 0.4f, 1.0f}),
                             -1});
  ASSERT_EQ(SceneGeometry(scene).instanced(), 2u);

  const float half = 0.3f;
  const int n = 16;
  PathTracerSettings s = small_settings(n, 256);
  s.max_bounces = 1;
  const PathTracerResult res = render_path(scene, nullptr, ortho_camera(half, 5.0f), s);

  const Brdf brdf(glm::vec3(rho), 0.0f, 1.0f);
  const int q = 48;
  std::vector<double> r;
  double mean_expected = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float px = ((float(x) + 0.5f) / float(n) * 2.0f - 1.0f) * half;
      const float py = (1.0f - (float(y) + 0.5f) / float(n) * 2.0f) * half;
      double L = 0.0;
      for (int j = 0; j < q; ++j)
        for (int i = 0; i < q; ++i) {
          const glm::vec3 on((float(i) + 0.5f) / float(q) - 0.5f,
                             (float(j) + 0.5f) / float(q) - 0.5f, 0.0f);
          const glm::vec3 to = glm::vec3(on.x * size.x, on.y * size.y, h) - glm::vec3(px, py, 0.0f);
          const float d2 = glm::dot(to, to);
          const glm::vec3 wi = to / std::sqrt(d2);
          const double dA = double(size.x * size.y) / double(q * q);
          L += double(brdf.eval(glm::vec3(0, 0, 1), wi).x) * Le * wi.z * wi.z / d2 * dA;
        }
      mean_expected += L / double(n * n);
      r.push_back(double(res.color.rgb(x, y).x) - L);
    }
  const ResidualStats st = residual_stats(r);
  std::printf("scaled emitter: expected mean %.5f, mean residual %.5f +- %.5f\n", mean_expected,
              st.mean, st.std_error);
  // 0.5% for the pixel footprint (the box filter averages a smooth field; the expectation is
  // taken at the pixel centre).
  EXPECT_LT(std::fabs(st.mean), 4.0 * st.std_error + 5e-3 * mean_expected);
}

// Two slabs from one closed box mesh (thickness d and 2d: the second scaled in z), one
// above the other over an emitter, seen straight down. Each slab transmits
// T = (1 - R)^2 a / (1 - R^2 a^2) and reflects R' = R + (1 - R)^2 R a^2 / (1 - R^2 a^2),
// a = attenuationColor^(thickness / attenuationDistance); the pair, with the light
// reflected between them, T1 T2 / (1 - R1' R2').
TEST(PathTracerInstancing, VolumeInstancesAbsorbEachByItsOwnThickness) {
  const float d = 0.3f, n = 1.5f, D = 0.4f;
  const glm::vec3 color(0.8f, 0.5f, 0.2f), Le(1.0f, 2.0f, 3.0f);
  Material glass = make_material(glm::vec3(1.0f), 0.0f, 0.0f);
  glass.ior = n;
  glass.transmission = TransmissionExtension{};
  glass.transmission->factor = 1.0f;
  glass.volume = VolumeExtension{};
  glass.volume->thickness_factor = 1.0f;
  glass.volume->attenuation_color = color;
  glass.volume->attenuation_distance = D;
  Scene scene;
  scene.source = "test:slabs";
  scene.materials.push_back(glass);
  scene.materials.push_back(make_material(glm::vec3(0.0f), 0.0f, 1.0f, Le, true));
  const int slab =
      add_mesh_instance(scene, make_box(glm::vec3(-50, -50, -d / 2), glm::vec3(50, 50, d / 2)), 0,
                        glm::translate(glm::mat4(1.0f), {0, 0, 1.0f}));
  ASSERT_TRUE(scene.meshes[std::size_t(slab)].closed);
  scene.instances.push_back(
      {slab,
       glm::translate(glm::mat4(1.0f), {0, 0, -0.5f}) * glm::scale(glm::mat4(1.0f), {1, 1, 2}),
       -1});
  add_mesh_instance(scene, make_quad({-50, -50, -3}, {100, 0, 0}, {0, 100, 0}), 1);
  ASSERT_EQ(SceneGeometry(scene).instanced(), 2u);

  PathTracerSettings s = small_settings(16, 64);
  s.max_bounces = 64;
  const PathTracerResult res = render_path(scene, nullptr, ortho_camera(1.0f), s);
  const double R = std::pow((n - 1.0) / (n + 1.0), 2.0);
  for (int c = 0; c < 3; ++c) {
    double T[2], Rs[2];
    for (int k = 0; k < 2; ++k) {
      const double a = std::pow(double(color[c]), (k + 1) * d / D);
      const double q = 1.0 - R * R * a * a;
      T[k] = (1.0 - R) * (1.0 - R) * a / q;
      Rs[k] = R + (1.0 - R) * (1.0 - R) * R * a * a / q;
    }
    const double expected = Le[c] * T[0] * T[1] / (1.0 - Rs[0] * Rs[1]);
    std::vector<double> r;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) r.push_back(double(res.color.rgb(x, y)[c]) - expected);
    const ResidualStats st = residual_stats(r);
    EXPECT_LT(std::fabs(st.mean), 4.0 * st.std_error + 1e-5 * expected)
        << "channel " << c << ": mean residual " << st.mean << " +- " << st.std_error
        << ", expected " << expected;
  }
}

// Robust ray origins (ray_offset.h) on an instance: Embree intersects in the mesh's space,
// resolve() computes the point in world space; grazing rays leaving the floor of a closed
// box placed far from the origin, turned and scaled, must neither hit the floor again nor
// leak out through its edges.
TEST(PathTracerInstancing, GrazingRaysOnAFarInstanceNeitherSelfHitNorLeak) {
  Scene scene;
  scene.source = "test:far box";
  scene.materials.push_back(make_material(glm::vec3(0.5f), 0.0f, 1.0f));
  const glm::vec3 centre(3000.0f, -1200.0f, 5000.0f);
  const float size = 10.0f;
  const glm::mat4 M = glm::translate(glm::mat4(1.0f), centre) *
                      glm::rotate(glm::mat4(1.0f), 0.3f, {0, 1, 0}) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(size));
  const int m = add_mesh_instance(scene, make_box(glm::vec3(-1.0f), glm::vec3(1.0f), true), 0, M);
  scene.instances.push_back({m, glm::translate(glm::mat4(1.0f), {0, 100, 0}), -1});
  const SceneGeometry g(scene);
  ASSERT_EQ(g.instanced(), 2u);
  Pcg32 rng(9);
  int self_hits = 0, escapes = 0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const glm::vec2 r = rng.next_2d() * 1.998f - 0.999f;
    const glm::vec3 start = glm::vec3(M * glm::vec4(r.x, 0.0f, r.y, 1.0f));
    std::uint32_t geom, prim;
    float t, u, v;
    ASSERT_TRUE(g.intersect(start, {0, -1, 0}, 1e30f, ~0u, geom, prim, t, u, v));
    const SurfaceHit hit = g.resolve(geom, prim, t, u, v);
    ASSERT_GT(hit.ng.y, 0.99f);  // the floor, facing into the box
    const float elevation = std::pow(10.0f, -5.0f + 3.0f * rng.next_float());
    const float phi = 2.0f * kPi * rng.next_float();
    const glm::vec3 d(std::cos(phi) * std::cos(elevation), std::sin(elevation),
                      std::sin(phi) * std::cos(elevation));
    if (!g.intersect(offset_ray_origin(hit.p, hit.ng), d, 1e30f, ~0u, geom, prim, t, u, v)) {
      ++escapes;
      continue;
    }
    if (g.resolve(geom, prim, t, u, v).ng.y > 0.5f) ++self_hits;
  }
  EXPECT_EQ(self_hits, 0) << "of " << n;
  EXPECT_EQ(escapes, 0) << "of " << n;
}

// Alpha through instances: shadow rays skip alpha geometry in the opaque query and find it
// in the transmittance loop (pt/geometry.h's ray masks, set on each instance too). Two
// instances of one blended sheet (alpha 0.25, facing down) between a point light and a
// floor: the floor's irradiance is I cos / d^2 times (1 - 0.25)^2.
TEST(PathTracerInstancing, BlendedInstancesTransmitTheirShareOfShadowRays) {
  Scene scene;
  scene.source = "test:blended sheets";
  scene.materials.push_back(make_material(glm::vec3(0.8f), 0.0f, 1.0f));
  Material sheet = make_material(glm::vec3(0.0f), 0.0f, 1.0f);
  sheet.alpha_mode = AlphaMode::kBlend;
  sheet.base_color_factor.a = 0.25f;
  scene.materials.push_back(sheet);
  add_mesh_instance(scene, make_quad({-5, -5, 0}, {10, 0, 0}, {0, 10, 0}), 0);
  // Facing -z: the camera above sees their culled backs, the floor their fronts.
  const int m = add_mesh_instance(scene, make_quad({-5, -5, 0}, {0, 10, 0}, {10, 0, 0}), 1,
                                  glm::translate(glm::mat4(1.0f), {0, 0, 0.6f}));
  scene.instances.push_back({m,
                             glm::translate(glm::mat4(1.0f), {0, 0, 1.1f}) *
                                 glm::scale(glm::mat4(1.0f), {0.8f, 1.2f, 1.0f}),
                             -1});
  ASSERT_EQ(SceneGeometry(scene).instanced(), 2u);
  Light light;
  light.type = Light::Type::kPoint;
  light.intensity = 10.0f;
  light.position = {0.3f, -0.2f, 1.5f};
  scene.lights.push_back(light);
  const int n = 16;
  const float half = 1.0f;
  PathTracerSettings s = small_settings(n, 64);
  s.max_bounces = 1;
  const PathTracerResult res = render_path(scene, nullptr, ortho_camera(half), s);
  const Brdf brdf(glm::vec3(0.8f), 0.0f, 1.0f);
  std::vector<double> r;
  double peak = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      double expected = 0.0;
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          const glm::vec3 p(((float(x) + (float(i) + 0.5f) / 4.0f) / float(n) * 2.0f - 1.0f) * half,
                            (1.0f - (float(y) + (float(j) + 0.5f) / 4.0f) / float(n) * 2.0f) * half,
                            0.0f);
          const glm::vec3 to = light.position - p;
          const float d2 = glm::dot(to, to);
          const glm::vec3 wi = to / std::sqrt(d2);
          expected += brdf.eval(glm::vec3(0, 0, 1), wi).x * light.intensity * wi.z / d2 *
                      (0.75 * 0.75) / 16.0;
        }
      peak = std::max(peak, expected);
      r.push_back(double(res.color.rgb(x, y).x) - expected);
    }
  const ResidualStats st = residual_stats(r);
  EXPECT_LT(std::fabs(st.mean), 4.0 * st.std_error + 1e-3 * peak)
      << "mean residual " << st.mean << " +- " << st.std_error << ", peak " << peak;
}

TEST(PathTracerInstancing, MemoryFollowsUniqueTriangles) {
  Scene one, many;
  for (Scene* s : {&one, &many}) {
    s->source = "test:memory";
    s->materials.push_back(make_material(glm::vec3(0.5f), 0.0f, 1.0f));
  }
  const Mesh sphere = make_uv_sphere(1.0f, 64, 32);  // 3,968 triangles
  const int m1 = add_mesh_instance(one, sphere, 0);
  one.instances.push_back({m1, glm::translate(glm::mat4(1.0f), {3, 0, 0}), -1});
  const int m = add_mesh_instance(many, sphere, 0);
  for (int i = 1; i < 1000; ++i)
    many.instances.push_back(
        {m, glm::translate(glm::mat4(1.0f), {3.0f * float(i % 32), 3.0f * float(i / 32), 0}), -1});
  const SceneGeometry g1(one), g1000(many);
  const GeometryMemory e1 = estimate_geometry_memory(one), e1000 = estimate_geometry_memory(many);
  std::printf("BVH of 2 instances: %zu B (peak %zu), of 1000: %zu B (peak %zu)\n", g1.memory().bvh,
              g1.memory().bvh_peak, g1000.memory().bvh, g1000.memory().bvh_peak);
  // What Embree allocated: 998 more instances cost far less than 998 more copies would
  // (the mesh's own BVH is some 100 bytes per triangle, 400 kB).
  EXPECT_LT(g1000.memory().bvh_peak, g1.memory().bvh_peak + 998 * 2048);
  EXPECT_GT(g1.memory().bvh, 3968u * 16);  // the monitor saw the mesh's BVH
  // The estimate bounds what was allocated.
  EXPECT_GE(e1.bvh, g1.memory().bvh_peak);
  EXPECT_GE(e1000.bvh, g1000.memory().bvh_peak);
  EXPECT_GE(e1000.geometry, g1000.memory().geometry);
}

TEST(PathTracerInstancing, SingularInstancesAreEmptyAndNonFiniteOnesAnError) {
  // A zero scale (glTF's way to hide a node) has no area: nothing to hit, no light; nor has
  // the quad in the XY plane scaled to zero along y. Scaled to zero along z, across its
  // plane, it is still all there (Embree could not invert that transform: it is flattened).
  Scene scene;
  scene.source = "test:hidden";
  scene.materials.push_back(make_material(glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(1.0f)));
  const int m = add_mesh_instance(scene, make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), 0,
                                  glm::scale(glm::mat4(1.0f), {1, 0, 1}));
  scene.instances.push_back({m, glm::scale(glm::mat4(1.0f), glm::vec3(0.0f)), -1});
  {
    Scene flat = scene;
    flat.instances.push_back({m,
                              glm::translate(glm::mat4(1.0f), {0, 0, -1}) *
                                  glm::scale(glm::mat4(1.0f), {0.5f, 1.0f, 0.0f}),
                              -1});
    flat.instances.push_back({m, glm::translate(glm::mat4(1.0f), {0, 0, -9}), -1});
    const SceneGeometry g(flat);
    std::uint32_t geom, prim;
    float t, u, v;
    ASSERT_TRUE(g.intersect({0.2f, 0.5f, 5}, {0, 0, -1}, 100.0f, ~0u, geom, prim, t, u, v));
    EXPECT_EQ(geom, 2u);
    EXPECT_NEAR(t, 6.0f, 1e-5f);
    const SurfaceHit h = g.resolve(geom, prim, t, u, v);
    EXPECT_NEAR(h.ng.z, 1.0f, 1e-6f);
    double area = 0.0;
    for (std::uint32_t k = 0; k < 2; ++k) area += g.triangle_area(2, k);
    EXPECT_NEAR(area, 2.0, 1e-5);  // 2 x 2 scaled by 0.5 along x
    // Past the scaled quad's x extent (0.5) the ray goes on to the instance at z = -9.
    ASSERT_TRUE(g.intersect({0.7f, 0.5f, 5}, {0, 0, -1}, 100.0f, ~0u, geom, prim, t, u, v));
    EXPECT_EQ(geom, 3u);
  }
  {
    const SceneGeometry g(scene);
    std::uint32_t geom, prim;
    float t, u, v;
    EXPECT_FALSE(g.intersect({0, 0, 5}, {0, 0, -1}, 100.0f, ~0u, geom, prim, t, u, v));
    const PathTracerResult res =
        render_path(scene, nullptr, ortho_camera(1.0f), small_settings(8, 4));
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) EXPECT_EQ(res.color.rgb(x, y), glm::vec3(0.0f));
  }
  scene.instances[1].transform[3][0] = std::numeric_limits<float>::quiet_NaN();
  try {
    const SceneGeometry g(scene);
    FAIL() << "built";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test:hidden: instance 1"), std::string::npos) << e.what();
  }
}

TEST(PathTracerInstancing, SceneOverTheMemoryLimitIsRefusedWithTheEstimate) {
  Scene scene;
  scene.source = "test:big";
  scene.materials.push_back(make_material(glm::vec3(0.5f), 0.0f, 1.0f));
  add_mesh_instance(scene, make_uv_sphere(1.0f, 256, 128), 0);
  GeometryOptions options;
  options.memory_limit = 1 << 20;  // 1 MB: the sphere's 65 k triangles need several
  try {
    const SceneGeometry g(scene, options);
    FAIL() << "built in " << g.memory().bvh << " bytes";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("test:big"), std::string::npos) << what;
    EXPECT_NE(what.find("estimated"), std::string::npos) << what;
    EXPECT_NE(what.find("1.0 MB is available"), std::string::npos) << what;
  }
  options.memory_limit = 64 << 20;
  EXPECT_NO_THROW(SceneGeometry(scene, options));
}

// A scene that fits the memory limit only in Embree's compact layout is built with it, and
// its rays find what the fast layout's find: the same triangle, at the same distance to
// rounding (both layouts run Embree's Moeller-Trumbore test, the compact one on vertices it
// reads through the index buffer).
TEST(PathTracerInstancing, SceneThatFitsOnlyCompactIsBuiltCompact) {
  Scene scene;
  scene.source = "test:compact";
  scene.materials.push_back(make_material(glm::vec3(0.5f), 0.0f, 1.0f));
  add_mesh_instance(scene, make_uv_sphere(1.0f, 256, 128), 0);
  GeometryOptions fast_options, compact_options;
  fast_options.layout = BvhLayout::kFast;
  compact_options.layout = BvhLayout::kCompact;
  const GeometryMemory fast_estimate = estimate_geometry_memory(scene, fast_options);
  const GeometryMemory compact_estimate = estimate_geometry_memory(scene, compact_options);
  const std::size_t fast_need = fast_estimate.geometry + fast_estimate.bvh;
  const std::size_t compact_need = compact_estimate.geometry + compact_estimate.bvh;
  ASSERT_LT(compact_need, fast_need);

  GeometryOptions limited;  // BvhLayout::kAuto
  limited.memory_limit = (fast_need + compact_need) / 2;
  const SceneGeometry fast(scene, GeometryOptions{});  // no limit: the fast layout
  const SceneGeometry compact(scene, limited);
  EXPECT_FALSE(fast.memory().compact);
  EXPECT_TRUE(compact.memory().compact);
  // What Embree held stays inside the estimate (the monitor refuses more), and the compact
  // layout keeps less than the fast one.
  EXPECT_LE(compact.memory().bvh_peak, compact_estimate.bvh);
  EXPECT_LT(compact.memory().bvh, fast.memory().bvh);

  Pcg32 rng(11);
  int hits = 0, same = 0;
  double worst_t = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 o =
        3.0f * sample_uniform_sphere({rng.next_float(), rng.next_float()}).direction;
    const glm::vec3 target(rng.next_float() * 2.2f - 1.1f, rng.next_float() * 2.2f - 1.1f,
                           rng.next_float() * 2.2f - 1.1f);
    const glm::vec3 d = glm::normalize(target - o);
    std::uint32_t g0, p0, g1, p1;
    float t0, u0, v0, t1, u1, v1;
    const bool h0 = fast.intersect(o, d, 1e30f, ~0u, g0, p0, t0, u0, v0);
    const bool h1 = compact.intersect(o, d, 1e30f, ~0u, g1, p1, t1, u1, v1);
    ASSERT_EQ(h0, h1) << "ray " << i;
    if (!h0) continue;
    ++hits;
    same += p0 == p1;
    worst_t = std::max(worst_t, double(std::fabs(t0 - t1)) / double(t0));
  }
  std::printf("compact layout: %d hits of 20000 rays, %d on the same triangle, worst t %.2e\n",
              hits, same, worst_t);
  EXPECT_GT(hits, 10000);
  EXPECT_GE(same, hits - hits / 1000);  // a ray through an edge may take either neighbour
  EXPECT_LT(worst_t, 1e-5);

  // Held to the fast layout, or under the compact one's estimate, the scene is refused.
  GeometryOptions fast_only = limited;
  fast_only.layout = BvhLayout::kFast;
  EXPECT_THROW(SceneGeometry(scene, fast_only), Error);
  limited.memory_limit = compact_need - compact_need / 10;
  try {
    const SceneGeometry g(scene, limited);
    FAIL() << "built in " << g.memory().bvh << " bytes";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("compact layout"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pbrkit::test
