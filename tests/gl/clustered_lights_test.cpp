// Clustered shading of the punctual lights (gl/light_clusters.h): a light of limited range
// adds exactly 0 beyond its range (KHR_lights_punctual's window clamp(1 - (d/r)^4, 0, 1) is
// 0 for d >= r), so shading only the lights binned into a fragment's cluster must give the
// image of the loop over every light, as long as no light that reaches a fragment is
// missing from its cluster. The binning itself is checked against brute force on the CPU.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_context.h"
#include "pbrkit/gl/light_clusters.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/util/error.h"

namespace pbrkit::gl {
namespace {

constexpr int kWidth = 96, kHeight = 64;

// The camera: at (0, 1.2, 3.5) looking down the room (-Z), a little down.
Camera room_camera() {
  Camera camera;
  camera.yfov = 1.0f;
  camera.znear = 0.1f;
  camera.camera_to_world = glm::inverse(glm::lookAt(
      glm::vec3(0.0f, 1.2f, 3.5f), glm::vec3(0.0f, 0.6f, -2.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
  return camera;
}

// A floor, a back wall and a few objects (one metallic, for the lights' highlights).
Scene room() {
  Scene scene;
  scene.source = "test:clustered-lights";
  Material rough;
  rough.base_color_factor = glm::vec4(0.8f, 0.75f, 0.7f, 1.0f);
  rough.metallic_factor = 0.0f;
  rough.roughness_factor = 0.6f;
  Material metal = rough;
  metal.metallic_factor = 1.0f;
  metal.roughness_factor = 0.3f;
  scene.materials = {rough, metal};
  const glm::mat4 id(1.0f);
  add_mesh_instance(scene,
                    make_quad(glm::vec3(-5.0f, 0.0f, 4.0f), glm::vec3(10.0f, 0.0f, 0.0f),
                              glm::vec3(0.0f, 0.0f, -10.0f)),
                    0, id);
  add_mesh_instance(scene,
                    make_quad(glm::vec3(-5.0f, 0.0f, -5.0f), glm::vec3(10.0f, 0.0f, 0.0f),
                              glm::vec3(0.0f, 4.0f, 0.0f)),
                    0, id);
  add_mesh_instance(scene, make_box(glm::vec3(-2.0f, 0.0f, -2.0f), glm::vec3(-1.0f, 1.0f, -1.0f)),
                    0, id);
  add_mesh_instance(scene, make_box(glm::vec3(1.2f, 0.0f, -3.0f), glm::vec3(2.2f, 1.8f, -2.4f)), 0,
                    id);
  add_mesh_instance(scene, make_uv_sphere(0.6f, 24, 12), 1,
                    glm::translate(id, glm::vec3(0.2f, 0.6f, -0.5f)));
  return scene;
}

// `count` point and spot lights (every third a spot) with ranges 0.3 to 2.5 m spread over
// the room, and three placed against the camera: one at the eye (the camera inside its
// sphere), one between the eye and the near plane, one behind the eye reaching past it.
std::vector<Light> ranged_lights(int count) {
  std::mt19937 rng(7);
  auto u = [&](float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng); };
  std::vector<Light> lights;
  for (int i = 0; i < count; ++i) {
    Light l;
    l.type = i % 3 == 2 ? Light::Type::kSpot : Light::Type::kPoint;
    l.position = glm::vec3(u(-4.5f, 4.5f), u(0.05f, 2.8f), u(-4.5f, 3.0f));
    l.color = glm::vec3(u(0.3f, 1.0f), u(0.3f, 1.0f), u(0.3f, 1.0f));
    l.intensity = u(0.3f, 2.0f);
    l.range = u(0.3f, 2.5f);
    l.direction = glm::normalize(glm::vec3(u(-0.5f, 0.5f), -1.0f, u(-0.5f, 0.5f)));
    l.inner_cone_angle = u(0.0f, 0.3f);
    l.outer_cone_angle = l.inner_cone_angle + u(0.1f, 0.6f);
    lights.push_back(l);
  }
  const Camera camera = room_camera();
  const glm::vec3 eye = camera.position(), ahead = camera.forward();
  Light at_eye;
  at_eye.position = eye;
  at_eye.range = 3.0f;
  at_eye.intensity = 0.8f;
  Light inside_near = at_eye;
  inside_near.position = eye + 0.05f * ahead;
  inside_near.range = 2.5f;
  inside_near.color = glm::vec3(1.0f, 0.6f, 0.4f);
  Light behind = at_eye;
  behind.type = Light::Type::kSpot;
  behind.position = eye - 0.5f * ahead;
  behind.direction = ahead;
  behind.outer_cone_angle = 0.5f;
  behind.range = 3.0f;
  lights.insert(lights.begin() + count / 2, {at_eye, inside_near, behind});
  return lights;
}

Image render_lights(Renderer& renderer, const std::vector<Light>& lights, bool clustered) {
  Scene scene = room();
  scene.lights = lights;
  renderer.set_scene(scene);
  RenderSettings settings;
  settings.msaa = 1;
  settings.ibl = false;
  settings.clustered_lights = clustered;
  // 8-pixel tiles: 12 x 8 tiles x 16 slices over the small image, so that the lights
  // straddle many cluster boundaries.
  settings.light_clusters.tile_pixels = 8;
  renderer.render(room_camera(), kWidth, kHeight, settings);
  return renderer.read_back();
}

// The largest relative difference (with a floor of 1e-3 under the denominator) and the
// number of pixels with some light.
struct Comparison {
  double largest = 0.0;
  int lit = 0;
};
Comparison compare(const Image& a, const Image& b) {
  Comparison c;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const glm::vec3 pa = a.rgb(x, y), pb = b.rgb(x, y);
      c.lit += (pb.r + pb.g + pb.b) > 0.01f;
      for (int k = 0; k < 3; ++k)
        c.largest =
            std::max(c.largest, double(std::fabs(pa[k] - pb[k])) / (1e-3 + std::fabs(pb[k])));
    }
  return c;
}

// The tolerance of the image comparisons: both loops add the same non-zero terms (the
// lights a cluster leaves out add exactly 0 in the full loop), in the same order when all
// lights are ranged, in another when the global lights come first; reordering a sum of n
// non-negative floats moves it by at most (n - 1) 2^-24 of itself. The sums here have up to
// ~200 terms: 200 x 6e-8 = 1.2e-5, and the shader compilers may contract the two loops'
// products into fused multiply-adds differently (a few ulps more).
constexpr double kTolerance = 2e-5;

TEST(GlClusteredLights, RangedLightsMatchTheFullLoop) {
  testing::context();
  Renderer renderer;
  const std::vector<Light> lights = ranged_lights(160);
  const Image clustered = render_lights(renderer, lights, true);
  const Image full = render_lights(renderer, lights, false);
  const Comparison c = compare(clustered, full);
  std::printf("%zu ranged lights: %d lit pixels, largest relative difference %.2e\n", lights.size(),
              c.lit, c.largest);
  EXPECT_GT(c.lit, kWidth * kHeight / 2);
  EXPECT_LT(c.largest, kTolerance);

  // The comparison can see a missing light: without the light at the eye, which reaches
  // much of the floor in front of the camera, the image differs far beyond the tolerance.
  std::vector<Light> fewer = lights;
  fewer.erase(fewer.begin() + 80);
  const Comparison d = compare(render_lights(renderer, fewer, true), full);
  EXPECT_GT(d.largest, 1000.0 * kTolerance);
}

TEST(GlClusteredLights, RangedAndUnrangedLightsMatchTheFullLoop) {
  // Lights without a range and a directional one are shaded by every fragment (the global
  // list), before the cluster's.
  testing::context();
  Renderer renderer;
  std::vector<Light> lights = ranged_lights(60);
  Light sun;
  sun.type = Light::Type::kDirectional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  sun.intensity = 0.5f;
  Light bulb;
  bulb.position = glm::vec3(-1.0f, 2.0f, 0.0f);
  bulb.intensity = 2.0f;
  Light spot = bulb;
  spot.type = Light::Type::kSpot;
  spot.position = glm::vec3(1.5f, 2.5f, -1.0f);
  spot.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  lights.insert(lights.begin() + 10, sun);
  lights.insert(lights.begin() + 30, bulb);
  lights.push_back(spot);
  const Image clustered = render_lights(renderer, lights, true);
  const Image full = render_lights(renderer, lights, false);
  const Comparison c = compare(clustered, full);
  std::printf("%zu lights, 3 unranged: %d lit pixels, largest relative difference %.2e\n",
              lights.size(), c.lit, c.largest);
  EXPECT_GT(c.lit, kWidth * kHeight * 3 / 4);  // the sun lights most surfaces
  EXPECT_LT(c.largest, kTolerance);

  // Up to 16 lights the full loop's count is compiled in (shader_permutations.h): the same
  // image through that program, 12 lights with the sun among them.
  const std::vector<Light> twelve(lights.begin(), lights.begin() + 12);
  const Comparison d =
      compare(render_lights(renderer, twelve, true), render_lights(renderer, twelve, false));
  std::printf("12 lights, the sun among them: largest relative difference %.2e\n", d.largest);
  EXPECT_GT(d.lit, kWidth * kHeight * 3 / 4);
  EXPECT_LT(d.largest, kTolerance);

  // Without spot lights the clustered program reads nothing of the lights themselves (LIGHTS
  // 2): the sun's direction comes from beside its entry in the index list.
  std::vector<Light> no_spots;
  for (const Light& l : lights)
    if (l.type != Light::Type::kSpot) no_spots.push_back(l);
  const Comparison e =
      compare(render_lights(renderer, no_spots, true), render_lights(renderer, no_spots, false));
  std::printf("%zu lights without spots: largest relative difference %.2e\n", no_spots.size(),
              e.largest);
  EXPECT_GT(e.lit, kWidth * kHeight * 3 / 4);
  EXPECT_LT(e.largest, kTolerance);
}

ClusterView room_view() {
  const Camera camera = room_camera();
  return {view_matrix(camera),
          projection_matrix(camera, float(kWidth) / float(kHeight)),
          kWidth,
          kHeight,
          camera.znear,
          std::nullopt};
}

// Whether the sphere (world space) overlaps the view-space box: the distance from the
// centre to the box's nearest point, clamped coordinate by coordinate.
bool reaches(const glm::mat4& view, const InfluenceSphere& s, float scale, const glm::vec3& lo,
             const glm::vec3& hi) {
  const glm::vec3 c = glm::vec3(view * glm::vec4(s.center, 1.0f));
  return glm::length(glm::clamp(c, lo, hi) - c) <= s.radius * scale;
}

// Whether the sphere holds a point of cluster (x, y, z) itself (the part of the view
// frustum a fragment of that cluster can be in, which its box encloses loosely): 9 x 9 x 9
// points through the cluster, evenly in pixels and in depth, unprojected with the inverse
// of the frame's projection.
bool holds_a_point(const ClusterView& view, const LightClusters& clusters, const Light& light,
                   int x, int y, int z) {
  const glm::mat4 inverse = glm::inverse(view.projection * view.view);
  const float t = float(clusters.tile_pixels);
  const float d0 = clusters.slice_depth(z), d1 = clusters.slice_depth(z + 1);
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j)
      for (int k = 0; k <= 8; ++k) {
        const float px = std::min((float(x) + float(i) / 8.0f) * t, float(view.width));
        const float py = std::min((float(y) + float(j) / 8.0f) * t, float(view.height));
        const float depth = d0 + (d1 - d0) * float(k) / 8.0f;
        // The NDC depth of view depth `depth`: the projection of (0, 0, -depth).
        const glm::vec4 clip = view.projection * glm::vec4(0.0f, 0.0f, -depth, 1.0f);
        const glm::vec4 ndc(2.0f * px / float(view.width) - 1.0f,
                            2.0f * py / float(view.height) - 1.0f, clip.z / clip.w, 1.0f);
        const glm::vec4 w = inverse * ndc;
        if (glm::length(glm::vec3(w) / w.w - light.position) < *light.range) return true;
      }
  return false;
}

TEST(GlClusteredLights, BinningAgreesWithBruteForce) {
  // Every cluster holds the lights whose sphere reaches into it: none that holds a point of
  // the cluster is missing, none that misses its box by more than 1% of its radius is
  // there. Lights without a range are global and in no cluster, and so are lights that
  // reach more than half the clusters (the binning's rule; checked against the count).
  std::vector<Light> lights = ranged_lights(160);
  Light unranged;
  unranged.position = glm::vec3(0.0f, 2.0f, 0.0f);
  lights.push_back(unranged);
  std::vector<const Light*> pointers;
  for (const Light& l : lights) pointers.push_back(&l);
  const ClusterView view = room_view();
  const LightClusters clusters = bin_lights(pointers, view, {8, 16});
  ASSERT_EQ(clusters.grid, glm::ivec3(12, 8, 16));
  const auto global = [&](std::size_t i) {
    return std::find(clusters.global.begin(), clusters.global.end(), std::uint32_t(i)) !=
           clusters.global.end();
  };
  EXPECT_TRUE(global(lights.size() - 1));
  EXPECT_TRUE(std::is_sorted(clusters.global.begin(), clusters.global.end()));
  std::vector<int> reached(lights.size(), 0);
  std::size_t binned = 0, required = 0;
  for (int z = 0; z < clusters.grid.z; ++z)
    for (int y = 0; y < clusters.grid.y; ++y)
      for (int x = 0; x < clusters.grid.x; ++x) {
        glm::vec3 lo, hi;
        cluster_bounds(clusters, view, x, y, z, lo, hi);
        const auto in = clusters.lights_of(clusters.cluster_index(x, y, z));
        EXPECT_TRUE(std::is_sorted(in.begin(), in.end()));
        binned += in.size();
        for (std::size_t i = 0; i + 1 < lights.size(); ++i) {
          const InfluenceSphere s = *influence_sphere(lights[i]);
          const bool listed = std::find(in.begin(), in.end(), std::uint32_t(i)) != in.end();
          const bool inner = reaches(view.view, s, 1.0f, lo, hi);
          reached[i] += reaches(view.view, s, 1.01f, lo, hi);
          if (global(i)) {
            EXPECT_FALSE(listed) << "global light " << i << " in a cluster";
          } else if (inner && holds_a_point(view, clusters, lights[i], x, y, z)) {
            ++required;
            EXPECT_TRUE(listed) << "light " << i << " missing from cluster " << x << "," << y << ","
                                << z;
          } else if (!reaches(view.view, s, 1.01f, lo, hi)) {
            EXPECT_FALSE(listed) << "light " << i << " in cluster " << x << "," << y << "," << z;
          }
        }
      }
  int ranged_global = 0;
  for (std::size_t i = 0; i + 1 < lights.size(); ++i)
    if (global(i)) {
      ++ranged_global;
      EXPECT_GT(reached[i], clusters.cluster_count() / 2) << "light " << i;
    }
  std::printf("%d of %zu ranged lights global (reaching over half the clusters)\n", ranged_global,
              lights.size() - 1);
  // Most binned pairs were checked as needed (a point of the cluster in the sphere); the
  // rest reach the cluster's box only by its corners or by the 1% margin.
  std::printf("%zu of %zu binned (light, cluster) pairs hold a point of their sphere\n", required,
              binned);
  EXPECT_GT(required, binned / 2);
  // Culling happened: a cluster holds far fewer than all the lights on average.
  const double mean = double(binned) / double(clusters.cluster_count());
  std::printf("%.1f lights per cluster of %d\n", mean, clusters.cluster_count());
  EXPECT_LT(mean, 0.1 * double(lights.size()));
}

TEST(GlClusteredLights, ALightStaysInTheClustersItReaches) {
  // Two lights of range 0.5 m: one 3 m ahead and 1.5 m to the left, one 8 m ahead and 2 m
  // to the right. Each lands only in clusters of its half of the screen and of the slices
  // that reach within its range of its depth (3 m and 8 m along the view direction; 0.51 m
  // allows for the binning's enlargement of the spheres).
  const ClusterView view = room_view();
  const Camera camera = room_camera();
  const glm::vec3 right = glm::vec3(camera.camera_to_world[0]);
  Light left_light, right_light;
  left_light.position = camera.position() + 3.0f * camera.forward() - 1.5f * right;
  right_light.position = camera.position() + 8.0f * camera.forward() + 2.0f * right;
  left_light.range = right_light.range = 0.5f;
  const std::vector<const Light*> pointers{&left_light, &right_light};
  const LightClusters clusters = bin_lights(pointers, view, {8, 16});
  int holding[2] = {0, 0};
  for (int c = 0; c < clusters.cluster_count(); ++c) {
    const int x = c % clusters.grid.x, z = c / (clusters.grid.x * clusters.grid.y);
    for (const std::uint32_t i : clusters.lights_of(c)) {
      ASSERT_LT(i, 2u);
      ++holding[i];
      const float depth = i == 0 ? 3.0f : 8.0f;
      EXPECT_GE(clusters.slice_depth(z + 1), depth - 0.51f) << "light " << i << " slice " << z;
      EXPECT_LE(clusters.slice_depth(z), depth + 0.51f) << "light " << i << " slice " << z;
      if (i == 0) {
        EXPECT_LT(x, clusters.grid.x / 2) << "cluster " << c;
      } else {
        EXPECT_GE(x, clusters.grid.x / 2) << "cluster " << c;
      }
    }
  }
  EXPECT_GT(holding[0], 0);
  EXPECT_GT(holding[1], 0);
  EXPECT_LT(holding[0] + holding[1], clusters.cluster_count() / 10);
  // The slices are exponential in depth: each is the same ratio deeper than the last.
  const float ratio = clusters.slice_depth(1) / clusters.slice_depth(0);
  for (int z = 1; z < clusters.grid.z; ++z)
    EXPECT_NEAR(clusters.slice_depth(z + 1) / clusters.slice_depth(z), ratio, 1e-4f * ratio);
}

TEST(GlClusteredLights, HugeRangesAreGlobalAndBadGridsAreErrors) {
  // A range too large to cut anything (and to bound in float depths) is shaded everywhere;
  // a grid of no pixels, no slices, or more clusters than a frame can hold is an error that
  // says what it got.
  Light huge;
  huge.range = 1e30f;
  const std::vector<const Light*> pointers{&huge};
  const ClusterView view = room_view();
  EXPECT_EQ(bin_lights(pointers, view).global, std::vector<std::uint32_t>{0u});
  EXPECT_THROW(bin_lights(pointers, view, {0, 16}), Error);
  EXPECT_THROW(bin_lights(pointers, view, {16, 0}), Error);
  ClusterView large = view;
  large.width = 65536, large.height = 65536;
  try {
    bin_lights(pointers, large, {1, 16});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("65536x65536"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pbrkit::gl
