// The light samplers (pt/lights.h, pt/light_bvh.h) on a scene of a few hundred varied
// lights (emissive triangles of many sizes, orientations and powers, some instanced; point
// and spot lights; directional lights): the probability of choosing each light sums to 1,
// a light the BVH never chooses cannot reach the point, the frequencies of sample() match
// the pmf (chi-square), and the pmf a BSDF-sampled hit on an emitter recomputes is the one
// the light sample used (MIS); the BVH's four-child (SSE) evaluation is the scalar
// importance bit for bit. Then renders: with a lone light both samplers give the
// same bits, and on many lights their images agree within the noise.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/light_bvh.h"
#include "pbrkit/pt/lights.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/util/error.h"
#include "pt_test_util.h"
#include "support/chi2.h"

namespace pbrkit::test {
namespace {

glm::vec3 random_unit(Pcg32& rng) {
  const float z = 1.0f - 2.0f * rng.next_float();
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * rng.next_float();
  return {r * std::cos(phi), r * std::sin(phi), z};
}

float log_uniform(Pcg32& rng, float lo, float hi) {
  return lo * std::pow(hi / lo, rng.next_float());
}

Mesh triangle_mesh(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  Mesh m;
  m.name = "emitter";
  m.positions = {a, b, c};
  const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  m.normals = {n, n, n};
  m.indices = {0, 1, 2};
  return m;
}

// A few hundred lights in [-10, 10]^3: 200 emissive triangles (sizes from 5 cm to 2 m,
// random orientations, emission over three decades, a third double-sided), 20 more as
// second instances of some of them (rotated, scaled non-uniformly), 60 point lights, 40
// spots and two directional lights.
Scene many_lights_scene() {
  Scene scene;
  scene.source = "test:many-lights";
  Pcg32 rng(7);
  for (int i = 0; i < 20; ++i) {
    const glm::vec3 e(rng.next_float(), rng.next_float(), rng.next_float());
    Material m = make_material(glm::vec3(0.5f), 0.0f, 0.5f, 0.2f + 0.8f * e, i % 3 == 0);
    m.emissive_strength = log_uniform(rng, 0.1f, 100.0f);
    scene.materials.push_back(m);
  }
  std::vector<int> emitters;
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 c =
        20.0f * glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 10.0f;
    const float s = log_uniform(rng, 0.05f, 2.0f);
    const glm::vec3 a = c + s * random_unit(rng), b = c + s * random_unit(rng),
                    d = c + s * random_unit(rng);
    if (glm::length(glm::cross(b - a, d - a)) < 1e-4f) continue;
    emitters.push_back(add_mesh_instance(scene, triangle_mesh(a, b, d), int(rng.next_u32() % 20)));
  }
  for (int i = 0; i < 20; ++i) {
    Instance inst;
    inst.mesh = emitters[std::size_t(i) * 7];
    glm::mat4 t = glm::translate(glm::mat4(1.0f), glm::vec3(rng.next_float() * 4.0f - 2.0f));
    t = glm::rotate(t, 6.0f * rng.next_float(), random_unit(rng));
    inst.transform = glm::scale(
        t, glm::vec3(0.5f + rng.next_float(), 0.5f + rng.next_float(), 0.5f + rng.next_float()));
    scene.instances.push_back(inst);
  }
  for (int i = 0; i < 100; ++i) {
    Light l;
    l.type = i < 60 ? Light::Type::kPoint : Light::Type::kSpot;
    l.position = 20.0f * glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 10.0f;
    l.color =
        glm::vec3(0.2f) + 0.8f * glm::vec3(rng.next_float(), rng.next_float(), rng.next_float());
    l.intensity = log_uniform(rng, 0.1f, 100.0f);
    l.direction = random_unit(rng);
    l.outer_cone_angle = 0.1f + 1.4f * rng.next_float();
    l.inner_cone_angle = l.outer_cone_angle * rng.next_float();
    scene.lights.push_back(l);
  }
  for (int i = 0; i < 2; ++i) {
    Light l;
    l.type = Light::Type::kDirectional;
    l.direction = random_unit(rng);
    l.intensity = 0.5f + 2.0f * float(i);
    scene.lights.push_back(l);
  }
  return scene;
}

struct Fixture {
  Scene scene = many_lights_scene();
  SceneGeometry geometry{scene};
  LightSet bvh{scene, geometry, nullptr, LightSamplerKind::kBvh};
  LightSet power{scene, geometry, nullptr, LightSamplerKind::kPower};
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

// Shading points spread over (and a little beyond) the lights' box, with random normals;
// every fourth without a normal.
struct Query {
  glm::vec3 p, n;
};
std::vector<Query> queries(int count, std::uint64_t seed) {
  Pcg32 rng(seed);
  std::vector<Query> q;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 p =
        24.0f * glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 12.0f;
    q.push_back({p, i % 4 == 3 ? glm::vec3(0.0f) : random_unit(rng)});
  }
  return q;
}

TEST(LightSampler, SceneHasTheLightsItWasBuiltWith) {
  Fixture& f = fixture();
  EXPECT_EQ(f.bvh.kind(), LightSamplerKind::kBvh);
  // 200 triangles (minus degenerate ones), 20 instances of them, 100 punctual, 2 sun.
  EXPECT_GE(f.bvh.size(), 300u);
  EXPECT_EQ(f.bvh.size(), f.power.size());
}

// The pmf over all lights sums to 1, less (for the BVH) the probability that the traversal
// ends in a subtree none of whose lights reach the point (no light is sampled there, as in
// pbrt-v4): that remainder is checked against the frequency of sample() finding no light
// (and ZeroPmfOnlyWhereTheLightCannotReach checks that such lights cannot contribute).
TEST(LightSampler, PmfSumsToOne) {
  Fixture& f = fixture();
  Pcg32 rng(17);
  double null_total = 0.0, null_expected = 0.0, null_variance = 0.0;
  const int draws = 2000;
  for (const Query& q : queries(200, 11)) {
    double sum_bvh = 0.0, sum_power = 0.0;
    for (std::size_t i = 0; i < f.bvh.size(); ++i) {
      const float p = f.bvh.pmf(q.p, q.n, i);
      ASSERT_GE(p, 0.0f);
      ASSERT_TRUE(std::isfinite(p));
      sum_bvh += double(p);
      sum_power += double(f.power.pmf(q.p, q.n, i));
    }
    EXPECT_NEAR(sum_power, 1.0, 1e-4);
    EXPECT_LE(sum_bvh, 1.0 + 1e-4) << "at " << q.p.x << "," << q.p.y << "," << q.p.z;
    const double p_null = std::max(0.0, 1.0 - sum_bvh);
    for (int k = 0; k < draws; ++k) {
      float p_select = 0.0f;
      if (f.bvh.select(q.p, q.n, rng.next_float(), p_select) < 0) null_total += 1.0;
    }
    null_expected += draws * p_null;
    null_variance += draws * p_null * (1.0 - p_null);
  }
  // Binomial counts: within 5 standard deviations (plus the float slack of the sums).
  EXPECT_NEAR(null_total, null_expected,
              5.0 * std::sqrt(null_variance) + 0.01 * null_expected + 5.0);
  // Most of the probability goes to lights.
  EXPECT_LT(null_expected, 0.2 * 200 * draws);
}

// Without lights that face a way (only point lights) nothing is ever culled: the BVH's
// pmf sums to 1 everywhere.
TEST(LightSampler, PmfSumsToOneForPointLights) {
  Scene scene;
  scene.source = "test:points";
  Pcg32 rng(23);
  for (int i = 0; i < 150; ++i) {
    Light l;
    l.position = 20.0f * glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 10.0f;
    l.intensity = log_uniform(rng, 0.1f, 100.0f);
    scene.lights.push_back(l);
  }
  const SceneGeometry geometry(scene);
  const LightSet bvh(scene, geometry, nullptr, LightSamplerKind::kBvh);
  for (const Query& q : queries(200, 29)) {
    double sum = 0.0;
    for (std::size_t i = 0; i < bvh.size(); ++i) sum += double(bvh.pmf(q.p, q.n, i));
    EXPECT_NEAR(sum, 1.0, 1e-4);
  }
}

// A light the BVH never picks from a point must be one that cannot light it (otherwise the
// estimator would be biased): a single-sided triangle facing away, a spot pointing away.
TEST(LightSampler, ZeroPmfOnlyWhereTheLightCannotReach) {
  Fixture& f = fixture();
  const Scene& scene = f.scene;
  int zeros = 0;
  for (const Query& q : queries(100, 12)) {
    std::size_t light = 0;
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
      const Light& l = scene.lights[i];
      if (l.type == Light::Type::kDirectional) {
        EXPECT_GT(f.bvh.pmf(q.p, q.n, light), 0.0f);
        ++light;
        continue;
      }
      const float p = f.bvh.pmf(q.p, q.n, light++);
      if (p > 0.0f) continue;
      ++zeros;
      ASSERT_EQ(l.type, Light::Type::kSpot) << "a point light with probability 0";
      const float cos_to_p =
          glm::dot(glm::normalize(l.direction), glm::normalize(q.p - l.position));
      EXPECT_LE(cos_to_p, std::cos(l.outer_cone_angle) + 1e-4f) << "spot " << i;
    }
    for (std::uint32_t g = 0; g < f.geometry.meshes().size(); ++g) {
      const WorldMesh& wm = f.geometry.meshes()[g];
      if (!wm.emissive) continue;
      const float p = f.bvh.pmf(q.p, q.n, light++);
      if (p > 0.0f) continue;
      ++zeros;
      ASSERT_FALSE(wm.material->double_sided) << "a double-sided emitter with probability 0";
      for (glm::vec2 uv : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(0.3f)}) {
        const SurfaceHit h = f.geometry.resolve(g, 0, 0.0f, uv.x, uv.y);
        const glm::vec3 to_p = glm::normalize(q.p - h.p);
        EXPECT_LE(glm::dot(h.ng, to_p), 1e-4f) << "emitter " << g << " faces the point";
      }
    }
  }
  EXPECT_GT(zeros, 100);  // the tree does cull lights that face away
}

// sample()'s frequencies against pmf() at several points (chi-square, pooled bins with
// expected counts below 5; Sidak-corrected 1% significance over the points).
TEST(LightSampler, SampleFrequenciesMatchPmf) {
  Fixture& f = fixture();
  const std::vector<Query> qs = queries(4, 13);
  const int samples = 200000;
  Pcg32 rng(99);
  for (const Query& q : qs) {
    // One cell per light and a last one for "no light".
    const std::size_t lights = f.bvh.size();
    std::vector<double> observed(lights + 1, 0.0), expected(lights + 1, 0.0);
    for (int s = 0; s < samples; ++s) {
      float p_select = 0.0f;
      const std::int64_t i = f.bvh.select(q.p, q.n, rng.next_float(), p_select);
      observed[i < 0 ? lights : std::size_t(i)] += 1.0;
    }
    double sum = 0.0;
    for (std::size_t i = 0; i < lights; ++i) {
      expected[i] = double(f.bvh.pmf(q.p, q.n, i)) * samples;
      sum += expected[i];
    }
    expected[lights] = std::max(0.0, samples - sum);
    const PooledChi2 c = pooled_chi2(observed, expected);
    const double stat = c.statistic;
    const int dof = c.degrees_of_freedom;
    if (!c.pooled_counted) {
      EXPECT_LT(c.pooled_observed, 5.0 + 5.0 * std::sqrt(5.0));
    }
    ASSERT_GT(dof, 20);
    const double p_value = chi2_survival(stat, dof);
    EXPECT_GT(p_value, 1.0 - std::pow(0.99, 1.0 / double(qs.size())))
        << "chi2 " << stat << " dof " << dof;
  }
}

// MIS: the probability sample() reports for its choice is the one pmf() recomputes, to the
// bit; and for an emissive triangle, the solid-angle pdf of the light sample is the one
// triangle_pdf() computes when a ray from the point hits that triangle (what the
// integrator does when a BSDF-sampled ray finds an emitter).
// Random bounds for the importance tests: boxes from 1 mm to 4 m, cones from a direction to
// the whole sphere, one- and two-sided, emission spreads from 0, powers over six decades.
LightBounds random_bounds(Pcg32& rng) {
  LightBounds l;
  const glm::vec3 c(rng.next_float() * 8.0f - 4.0f, rng.next_float() * 8.0f - 4.0f,
                    rng.next_float() * 8.0f - 4.0f);
  const glm::vec3 half(log_uniform(rng, 1e-3f, 2.0f), log_uniform(rng, 1e-3f, 2.0f),
                       log_uniform(rng, 1e-3f, 2.0f));
  l.lo = c - half;
  l.hi = c + half;
  l.w = random_unit(rng);
  l.phi = log_uniform(rng, 1e-3f, 1e3f);
  l.cos_theta_o = rng.next_float() < 0.3f ? 1.0f : 2.0f * rng.next_float() - 1.0f;
  l.cos_theta_e = rng.next_float() < 0.3f ? 0.0f : rng.next_float();
  l.two_sided = rng.next_float() < 0.3f;
  return l;
}

// Half the points near the box of `near` (often inside its bounding sphere), half anywhere;
// a fifth of them without a normal.
void random_point(Pcg32& rng, const LightBounds& near, glm::vec3& p, glm::vec3& n) {
  p = rng.next_float() < 0.5f
          ? 0.5f * (near.lo + near.hi) + 0.5f * random_unit(rng)
          : glm::vec3(rng.next_float() * 16.0f - 8.0f, rng.next_float() * 16.0f - 8.0f,
                      rng.next_float() * 16.0f - 8.0f);
  n = rng.next_float() < 0.2f ? glm::vec3(0.0f) : random_unit(rng);
}

// The traversal evaluates a node's four children together (one SSE vector); each lane must
// be the scalar light_importance() of its child bit for bit, so that the choice does not
// depend on which path computed it; a lane not in use must be 0.
TEST(LightSampler, BvhFourChildImportanceIsTheScalarOne) {
  Pcg32 rng(41);
  int nonzero = 0, culled = 0;
  for (int t = 0; t < 4000; ++t) {
    const int count = 1 + int(rng.next_u32() % 4);
    LightBounds b[4];
    LightBvh::WideNode node{};
    for (int k = 0; k < count; ++k) {
      b[k] = random_bounds(rng);
      node.set(k, LightBvh::Node::of(b[k]));
    }
    glm::vec3 p, n;
    random_point(rng, b[t % count], p, n);
    float out[4];
    LightBvh::importance4(node, p, n, out);
    for (int k = 0; k < 4; ++k) {
      const float expected = k < count ? light_importance(b[k], p, n) : 0.0f;
      ASSERT_EQ(out[k], expected) << "trial " << t << " lane " << k;
      if (k < count) (expected > 0.0f ? nonzero : culled) += 1;
    }
  }
  EXPECT_GT(nonzero, 5000);
  EXPECT_GT(culled, 100);  // the emission-spread cut-off was exercised
}

// With two lights the tree is one node over two lights and pmf(k) is i_k / (i_0 + i_1) of
// the scalar importances.
TEST(LightSampler, BvhOfTwoLightsChoosesByTheirImportance) {
  Pcg32 rng(29);
  int compared = 0, culled = 0;
  for (int t = 0; t < 4000; ++t) {
    const LightBounds b[2] = {random_bounds(rng), random_bounds(rng)};
    const LightBvh bvh({b[0], b[1]});
    ASSERT_EQ(bvh.node_count(), 1u);
    ASSERT_EQ(bvh.depth(), 1);
    glm::vec3 p, n;
    random_point(rng, b[t % 2], p, n);
    const float i0 = light_importance(b[0], p, n), i1 = light_importance(b[1], p, n);
    const float sum = i0 + i1;
    if (!(sum > 0.0f)) {
      EXPECT_EQ(bvh.pmf(p, n, 0), 0.0f);
      EXPECT_EQ(bvh.pmf(p, n, 1), 0.0f);
      ++culled;
      continue;
    }
    const float inv_sum = 1.0f / sum;
    ASSERT_EQ(bvh.pmf(p, n, 0), i0 * inv_sum) << "trial " << t;
    ASSERT_EQ(bvh.pmf(p, n, 1), i1 * inv_sum) << "trial " << t;
    ++compared;
  }
  EXPECT_GT(compared, 2000);
  EXPECT_GT(culled, 0);  // the emission-spread cut-off was exercised
}

TEST(LightSampler, PmfOfTheSampledLightIsTheOneSampleUsed) {
  Fixture& f = fixture();
  Pcg32 rng(5);
  int hits = 0;
  for (const Query& q : queries(3000, 14)) {
    for (const LightSet* set : {&f.bvh, &f.power}) {
      const float u_select = rng.next_float();
      float p_select = 0.0f;
      const std::int64_t i = set->select(q.p, q.n, u_select, p_select);
      if (i < 0) continue;
      if (set == &f.bvh) {
        EXPECT_EQ(p_select, set->pmf(q.p, q.n, std::size_t(i)));
      }
      LightSample ls;
      if (!set->sample(q.p, q.n, u_select, rng.next_2d(), ls) || ls.delta || ls.infinite) continue;
      std::uint32_t geom = 0, prim = 0;
      float t = 0.0f, u = 0.0f, v = 0.0f;
      if (!f.geometry.intersect(q.p, ls.wi, std::numeric_limits<float>::infinity(), 0xffffffffu,
                                geom, prim, t, u, v))
        continue;
      SurfaceHit hit = f.geometry.resolve(geom, prim, t, u, v);
      if (glm::length(hit.p - ls.light_point) > 1e-3f * (1.0f + ls.distance)) continue;  // occluded
      const float pdf = set->triangle_pdf(hit, q.p, q.n);
      EXPECT_NEAR(pdf, ls.pdf, 2e-3f * ls.pdf);
      ++hits;
    }
  }
  EXPECT_GT(hits, 200);
}

// Lights that share one position and cone cannot be told apart by where they are: every
// node's importance is then its power times one common factor, so the BVH must choose in
// proportion to power (the closed form), and the tree over them, split by the median for
// want of a better split, stays shallow.
TEST(LightSampler, CoincidentLightsAreChosenByPower) {
  Pcg32 rng(31);
  std::vector<LightBounds> lights(3000);
  double total = 0.0;
  for (LightBounds& b : lights) {
    b.lo = b.hi = glm::vec3(1.0f, 2.0f, 3.0f);
    b.cos_theta_o = -1.0f;
    b.phi = log_uniform(rng, 0.01f, 100.0f);
    total += double(b.phi);
  }
  const LightBvh bvh(lights);
  // ceil(log2(3000)) = 12 binary levels below the root, two per node of four: 6, and slack.
  EXPECT_LE(bvh.depth(), 7);
  for (const Query& q : queries(10, 37)) {
    double sum = 0.0;
    for (std::uint32_t i = 0; i < lights.size(); ++i) {
      const float p = bvh.pmf(q.p, q.n, i);
      EXPECT_NEAR(p, double(lights[i].phi) / total, 1e-4 * double(lights[i].phi) / total);
      sum += double(p);
    }
    EXPECT_NEAR(sum, 1.0, 1e-4);
  }
}

TEST(LightSampler, ParsesItsNames) {
  EXPECT_EQ(parse_light_sampler("bvh"), LightSamplerKind::kBvh);
  EXPECT_EQ(parse_light_sampler("power"), LightSamplerKind::kPower);
  EXPECT_EQ(light_sampler_name(LightSamplerKind::kPower), "power");
  EXPECT_EQ(light_sampler_name(LightSamplerKind::kBvh), "bvh");
  EXPECT_THROW(parse_light_sampler("tree"), Error);
  EXPECT_EQ(PathTracerSettings{}.light_sampler, LightSamplerKind::kBvh);
}

// A grey floor and its camera (looking down at it from above).
Scene floor_scene() {
  Scene scene;
  scene.source = "test:floor";
  scene.materials.push_back(make_material(glm::vec3(0.6f), 0.0f, 0.6f));
  add_mesh_instance(scene, make_quad(glm::vec3(-4, -4, 0), glm::vec3(8, 0, 0), glm::vec3(0, 8, 0)),
                    0);
  return scene;
}

Camera looking_down() {
  Camera c = ortho_camera(4.0f, 6.0f);
  return c;
}

TEST(LightSampler, LoneLightGivesTheSameImageWithEitherSampler) {
  for (int kind = 0; kind < 3; ++kind) {
    Scene scene = floor_scene();
    if (kind == 2) {
      scene.materials.push_back(
          make_material(glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(4.0f, 3.0f, 2.0f)));
      add_mesh_instance(
          scene, triangle_mesh(glm::vec3(-1, -1, 2), glm::vec3(-1, 1, 2.5f), glm::vec3(1, 0, 2)),
          1);  // wound to face the floor
    } else {
      Light l;
      l.type = kind == 0 ? Light::Type::kPoint : Light::Type::kSpot;
      l.position = glm::vec3(0.5f, -0.3f, 2.0f);
      l.direction = glm::normalize(glm::vec3(0.2f, 0.1f, -1.0f));
      l.intensity = 5.0f;
      scene.lights.push_back(l);
    }
    PathTracerSettings s = small_settings(24, 8);
    s.light_sampler = LightSamplerKind::kBvh;
    const PathTracerResult a = render_path(scene, nullptr, looking_down(), s);
    s.light_sampler = LightSamplerKind::kPower;
    const PathTracerResult b = render_path(scene, nullptr, looking_down(), s);
    ASSERT_EQ(a.color.data.size(), b.color.data.size());
    double total = 0.0;
    for (std::size_t i = 0; i < a.color.data.size(); ++i) {
      ASSERT_EQ(a.color.data[i], b.color.data[i]) << "light kind " << kind << " at " << i;
      total += a.color.data[i];
    }
    EXPECT_GT(total, 0.0);  // the light does light the floor
  }
}

// The floor under many lights (emissive tiles of different sizes, powers and colours, point
// and spot lights): the BVH sampler's image and the power sampler's agree within their
// noise. Per block of 4 x 4 pixels, z = (mean_bvh - mean_power) / sqrt(var_bvh + var_power),
// the variances of the block means from each pixel's two half buffers (even and odd
// samples: var(mean) ~ (E - O)^2 / 4); independent renders (different seeds). Biased
// sampling (a light left out where it contributes) moves whole regions by many sigma.
TEST(LightSampler, BvhAndPowerImagesAgreeWithinNoise) {
  Scene scene = floor_scene();
  Pcg32 rng(3);
  for (int i = 0; i < 4; ++i) {
    const glm::vec3 e(rng.next_float(), rng.next_float(), rng.next_float());
    scene.materials.push_back(
        make_material(glm::vec3(0.0f), 0.0f, 1.0f, 0.3f + e, i == 0 /* double-sided */));
    scene.materials.back().emissive_strength = log_uniform(rng, 1.0f, 30.0f);
  }
  for (int i = 0; i < 60; ++i) {
    const glm::vec3 c(8.0f * rng.next_float() - 4.0f, 8.0f * rng.next_float() - 4.0f,
                      0.5f + 2.0f * rng.next_float());
    const float s = log_uniform(rng, 0.05f, 0.5f);
    // Tiles facing down (their back to the camera above: it sees the floor's lighting).
    add_mesh_instance(scene, make_quad(c, glm::vec3(0, s, 0), glm::vec3(s, 0, 0)),
                      1 + int(rng.next_u32() % 4));
  }
  for (int i = 0; i < 20; ++i) {
    Light l;
    l.type = i % 2 ? Light::Type::kSpot : Light::Type::kPoint;
    l.position = glm::vec3(8.0f * rng.next_float() - 4.0f, 8.0f * rng.next_float() - 4.0f,
                           0.5f + 2.0f * rng.next_float());
    l.direction =
        glm::normalize(glm::vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, -1.0f));
    l.outer_cone_angle = 0.3f + 0.6f * rng.next_float();
    l.inner_cone_angle = 0.5f * l.outer_cone_angle;
    l.intensity = log_uniform(rng, 0.05f, 2.0f);
    scene.lights.push_back(l);
  }
  PathTracerSettings s = small_settings(32, 64);
  s.max_bounces = 2;
  s.light_sampler = LightSamplerKind::kBvh;
  s.seed = 1;
  const PathTracerResult a = render_path(scene, nullptr, looking_down(), s);
  s.light_sampler = LightSamplerKind::kPower;
  s.seed = 2;
  const PathTracerResult b = render_path(scene, nullptr, looking_down(), s);
  const int block = 4, nb = 32 / block;
  auto block_stats = [&](const Film& film, int bx, int by, double& mean, double& var) {
    mean = var = 0.0;
    for (int y = by * block; y < (by + 1) * block; ++y)
      for (int x = bx * block; x < (bx + 1) * block; ++x) {
        const std::size_t i = std::size_t(y) * 32 + std::size_t(x);
        const double n = film.count[i];
        const glm::dvec3 sum(film.sum[i]), even(film.sum_even[i]);
        const double m = (sum.x + sum.y + sum.z) / n;
        const double e = (even.x + even.y + even.z) / (n / 2);
        const double o = (sum.x + sum.y + sum.z - (even.x + even.y + even.z)) / (n / 2);
        mean += m;
        var += 0.25 * (e - o) * (e - o);
      }
    const double k = double(block * block);
    mean /= k;
    var /= k * k;
  };
  double z2 = 0.0, worst = 0.0, mean_a = 0.0, mean_b = 0.0;
  for (int by = 0; by < nb; ++by)
    for (int bx = 0; bx < nb; ++bx) {
      double ma, va, mb, vb;
      block_stats(a.film, bx, by, ma, va);
      block_stats(b.film, bx, by, mb, vb);
      const double z = (ma - mb) / std::sqrt(va + vb);
      z2 += z * z;
      worst = std::max(worst, std::fabs(z));
      mean_a += ma;
      mean_b += mb;
    }
  const int blocks = nb * nb;
  EXPECT_GT(mean_a, 0.0);
  // sum z^2 ~ chi-square with `blocks` degrees of freedom (a little wider: each variance is
  // itself estimated from 16 pixels).
  EXPECT_GT(chi2_survival(z2, blocks), 1e-3) << "sum z^2 " << z2 << " over " << blocks;
  EXPECT_LT(worst, 5.0);
  EXPECT_NEAR(mean_a / mean_b, 1.0, 0.03);
}

}  // namespace
}  // namespace pbrkit::test
