// Instanced drawing: the instances of one mesh are drawn a run at a time (one
// glDrawElementsInstanced per mesh and winding, their matrices read from the instance
// buffer at uInstanceBase + gl_InstanceID). The same instances, each with a mesh of its own
// (so each drawn alone), must give the same image: both are rasterised from the same
// matrices, so only the draw order differs, which the depth test makes irrelevant.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_context.h"
#include "pbrkit/gl/context.h"
#include "pbrkit/gl/gpu_scene.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::gl {
namespace {

// A 6 x 6 grid of one box, turned, some mirrored (negative x scale) and some squashed,
// under a point light; `shared`: one mesh for all, else a copy per instance.
Scene grid(bool shared) {
  Scene scene;
  scene.source = "test:instanced";
  Material m;
  m.base_color_factor = glm::vec4(0.8f, 0.5f, 0.3f, 1.0f);
  m.metallic_factor = 0.0f;
  m.roughness_factor = 0.5f;
  scene.materials.push_back(m);
  const Mesh box = make_box(glm::vec3(-0.3f), glm::vec3(0.3f));
  if (shared) {
    scene.meshes.push_back(box);
    scene.meshes.back().material = 0;
  }
  for (int i = 0; i < 36; ++i) {
    glm::mat4 t =
        glm::translate(glm::mat4(1.0f), glm::vec3(float(i % 6) - 2.5f, float(i / 6) - 2.5f, 0.0f));
    t = glm::rotate(t, 0.4f + 0.3f * float(i), glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
    glm::vec3 scale(1.0f);
    if (i % 5 == 2) scale.x = -1.0f;
    if (i % 7 == 3) scale *= glm::vec3(1.4f, 0.5f, 1.0f);
    t = glm::scale(t, scale);
    if (shared)
      scene.instances.push_back({0, t, -1});
    else
      add_mesh_instance(scene, box, 0, t);
  }
  Light light;
  light.type = Light::Type::kPoint;
  light.position = glm::vec3(2.0f, 3.0f, 6.0f);
  light.intensity = 60.0f;
  scene.lights.push_back(light);
  return scene;
}

// The grid seen from the front, all of it in the frame.
Camera front_camera() {
  Camera camera;
  camera.yfov = 0.9f;
  camera.camera_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 9.0f));
  return camera;
}

// `scene`, seen from the front, drawn with RenderSettings::software_queue_triangles =
// `limit` and with no limit: the same image, bit for bit, with a good part of it lit.
void expect_same_image_with_queue_limit(const Scene& scene, std::size_t limit) {
  RenderSettings whole;
  whole.msaa = 1;
  whole.software_queue_triangles = 0;
  RenderSettings limited = whole;
  limited.software_queue_triangles = limit;
  constexpr int kSize = 96;
  const Camera camera = front_camera();
  const Image a = render_headless(scene, camera, kSize, kSize, nullptr, nullptr, limited);
  const Image b = render_headless(scene, camera, kSize, kSize, nullptr, nullptr, whole);
  int lit = 0, differ = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      lit += glm::dot(b.rgb(x, y), glm::vec3(1.0f)) > 0.01f;
      differ += a.rgb(x, y) != b.rgb(x, y);
    }
  EXPECT_GT(lit, kSize * kSize / 5);
  EXPECT_EQ(differ, 0) << "queue limit " << limit;
}

TEST(GlInstancedDrawing, InstancesOfOneMeshDrawLikeSeparateMeshes) {
  testing::context();
  const Scene shared = grid(true), separate = grid(false);
  ASSERT_EQ(shared.meshes.size(), 1u);
  ASSERT_EQ(separate.meshes.size(), 36u);
  const Camera camera = front_camera();
  RenderSettings settings;
  settings.msaa = 1;
  constexpr int kSize = 96;
  const Image a = render_headless(shared, camera, kSize, kSize, nullptr, nullptr, settings);
  const Image b = render_headless(separate, camera, kSize, kSize, nullptr, nullptr, settings);
  double largest = 0.0;
  int lit = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec3 pa = a.rgb(x, y), pb = b.rgb(x, y);
      lit += (pb.r + pb.g + pb.b) > 0.01f;
      for (int c = 0; c < 3; ++c)
        largest = std::max(largest, double(std::fabs(pa[c] - pb[c])) / (1e-3 + std::fabs(pb[c])));
    }
  std::printf("instanced vs separate draws: %d lit pixels, largest relative difference %.2e\n", lit,
              largest);
  EXPECT_GT(lit, kSize * kSize / 5);  // the boxes fill a good part of the image
  EXPECT_LT(largest, 1e-5);
}

// On a software rasteriser (llvmpipe, as in CI) the frame draws a run in chunks of at most
// RenderSettings::software_queue_triangles and waits for the rasteriser after each: with a
// limit of two boxes (24 triangles) the runs of 29 and 7 instances are drawn two at a time,
// each chunk from its own first slot, and the image must be the one drawn without chunks (a
// chunk drawn from the run's first slot, or one instance short, would change it).
TEST(GlInstancedDrawing, ChunksOfARunDrawTheSameImage) {
  testing::context();
  std::printf("context: %s, chunked: %s\n", describe_current_context().c_str(),
              is_software_renderer(current_renderer()) ? "yes" : "no (a GPU: no chunks)");
  expect_same_image_with_queue_limit(grid(true), 24);
}

// A mesh of more triangles than the limit is drawn in index ranges of at most that many (a
// limit of 5: each box's 12 triangles as 5, 5 and 2; the glass sphere in front as ranges of
// 5, its back-face pass too), and the image must be the one drawn whole: a range drawn from
// the mesh's first index, or the last short range dropped, leaves faces out, and a back-face
// pass drawn wrong changes what the thick glass refracts.
TEST(GlInstancedDrawing, IndexRangesOfAMeshDrawTheSameImage) {
  testing::context();
  Scene scene = grid(true);
  Material glass;
  glass.base_color_factor = glm::vec4(1.0f);
  glass.metallic_factor = 0.0f;
  glass.roughness_factor = 0.05f;
  glass.transmission = TransmissionExtension{1.0f, {}};
  glass.volume = VolumeExtension{1.5f, {}, 4.0f, glm::vec3(0.9f, 0.7f, 0.5f)};
  scene.materials.push_back(glass);
  const int sphere =
      add_mesh_instance(scene, make_uv_sphere(1.6f, 32, 16), 1,
                        glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.3f, 2.5f)));
  ASSERT_TRUE(scene.meshes[std::size_t(sphere)].closed);  // a volume: the back-face pass runs
  expect_same_image_with_queue_limit(scene, 5);
}

TEST(GlInstancedDrawing, OneRunPerMeshAndWinding) {
  // The shared grid draws in two runs (its 7 mirrored boxes, its 29 others), each with its
  // instances at consecutive slots; the separate one in 36 runs of one.
  testing::context();
  GpuScene shared;
  shared.upload(grid(true));
  ASSERT_EQ(shared.runs.size(), 2u);
  EXPECT_EQ(shared.runs[0].count, 29u);
  EXPECT_EQ(shared.runs[1].count, 7u);
  for (std::size_t slot = 0; slot < 36; ++slot) {
    const std::size_t i = shared.at_slot[slot];
    EXPECT_EQ(shared.slot_of[i], slot);
    EXPECT_EQ(i % 5 == 2, slot >= 29) << "instance " << i;  // the mirrored ones last
  }
  GpuScene separate;
  separate.upload(grid(false));
  EXPECT_EQ(separate.runs.size(), 36u);
}

}  // namespace
}  // namespace pbrkit::gl
