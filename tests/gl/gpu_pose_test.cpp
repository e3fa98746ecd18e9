// The OpenGL renderer's posing in the vertex shader (gpu_deformation.h, deformation.glsl)
// against posing on the CPU (scene/pose.h's pose_scene), both drawn by the GL renderer: a
// rig written here (two joints, one of them scaled unevenly so that normals need the
// inverse transpose; a smooth skinned and morphed tube, a skinned tube with flat normals,
// a morphed tube on a moving node) posed once by Renderer::set_pose and once by pose_scene
// with its posed meshes uploaded as static geometry. The two rasterise the same triangles
// up to rounding, so they differ only where a pixel's coverage samples land on either side
// of an edge: the coverage's intersection over union is close to 1 and the mean colour
// difference is a small fraction of the mean colour.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/util/error.h"
#include "scene/gltf_builder.h"

namespace pbrkit::gl {
namespace {

using json = nlohmann::json;
constexpr float kPi = 3.14159265358979f;
constexpr int kWidth = 160, kHeight = 160;

int scalar_floats(test::GltfBuilder& b, const std::vector<float>& v) {
  return b.accessor(v.data(), v.size() * 4, 5126, "SCALAR", v.size());
}

// A tube along +y from 0 to 2 about x = `x`: `rings` rings of `segments` vertices, radial
// normals, triangles wound outwards.
struct Tube {
  std::vector<glm::vec3> positions, normals;
  std::vector<std::uint32_t> indices;
  Tube(float x, int rings = 13, int segments = 16, float radius = 0.25f) {
    for (int r = 0; r < rings; ++r)
      for (int s = 0; s < segments; ++s) {
        const float a = 2.0f * kPi * float(s) / float(segments);
        const glm::vec3 n(std::cos(a), 0.0f, -std::sin(a));
        positions.push_back(glm::vec3(x, 2.0f * float(r) / float(rings - 1), 0.0f) + radius * n);
        normals.push_back(n);
      }
    const auto at = [&](int r, int s) { return std::uint32_t(r * segments + s % segments); };
    for (int r = 0; r + 1 < rings; ++r)
      for (int s = 0; s < segments; ++s)
        indices.insert(indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r, s),
                                       at(r + 1, s + 1), at(r + 1, s)});
  }
  // Joint 1's weight rises from 0 to 1 over y in [0.7, 1.3]; joint 0 has the rest.
  void skin(test::GltfBuilder& b, json& prim) const {
    std::vector<std::uint8_t> joints;
    std::vector<glm::vec4> weights;
    for (const glm::vec3& p : positions) {
      const float w1 = std::clamp((p.y - 0.7f) / 0.6f, 0.0f, 1.0f);
      joints.insert(joints.end(), {0, 1, 0, 0});
      weights.push_back({1.0f - w1, w1, 0.0f, 0.0f});
    }
    prim["attributes"]["JOINTS_0"] =
        b.accessor(joints.data(), joints.size(), 5121, "VEC4", positions.size());
    prim["attributes"]["WEIGHTS_0"] = b.floats(weights);
  }
  // One morph target: the upper half pushed out along x and its normals tilted up.
  void morph(test::GltfBuilder& b, json& prim) const {
    std::vector<glm::vec3> dp, dn;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const float k = std::max(0.0f, positions[i].y - 1.0f);
      dp.push_back(glm::vec3(0.3f * k * (normals[i].x + 1.0f), 0.1f * k, 0.2f * k * normals[i].z));
      dn.push_back(glm::vec3(0.0f, 0.4f * k, 0.0f));
    }
    const int pos = b.floats(dp);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : dp) lo = glm::min(lo, p), hi = glm::max(hi, p);
    b.gltf["accessors"][std::size_t(pos)]["min"] = {lo.x, lo.y, lo.z};
    b.gltf["accessors"][std::size_t(pos)]["max"] = {hi.x, hi.y, hi.z};
    prim["targets"] = {{{"POSITION", pos}, {"NORMAL", b.floats(dn)}}};
  }
};

// The rig: joint 0 at the origin, joint 1 at y = 1 its child. Animation "move" over [0, 1]:
// joint 0 turns 30 degrees about z, joint 1 turns -70 degrees about z and scales to
// (1.4, 1, 0.6), the morph weights go from 0 to 1 and the morphed tube's node moves up.
std::filesystem::path rig_file() {
  test::GltfBuilder b;
  const int material = 0;
  b.gltf["materials"] = {{{"pbrMetallicRoughness",
                           {{"baseColorFactor", {0.8, 0.7, 0.6, 1.0}},
                            {"metallicFactor", 0.0},
                            {"roughnessFactor", 0.5}}}}};
  const Tube smooth(0.0f), flat(0.8f), morphed(0.0f);
  json a = b.primitive(smooth.positions, smooth.indices, material);
  a["attributes"]["NORMAL"] = b.floats(smooth.normals);
  smooth.skin(b, a);
  smooth.morph(b, a);
  json f = b.primitive(flat.positions, flat.indices, material);  // no NORMAL: flat normals
  flat.skin(b, f);
  json m = b.primitive(morphed.positions, morphed.indices, material);
  m["attributes"]["NORMAL"] = b.floats(morphed.normals);
  morphed.morph(b, m);
  const int mesh_a = b.mesh({a}), mesh_f = b.mesh({f}), mesh_m = b.mesh({m});
  b.gltf["meshes"][std::size_t(mesh_a)]["weights"] = {0.0};
  b.gltf["meshes"][std::size_t(mesh_m)]["weights"] = {0.0};
  // A skinned node's own transform is ignored (glTF 2.0 section 3.7.3.1): give it one.
  const int node_a = b.node({{"mesh", mesh_a}, {"skin", 0}, {"translation", {5, 0, 0}}});
  b.node({{"mesh", mesh_f}, {"skin", 0}});
  const int node_m = b.node({{"mesh", mesh_m}, {"translation", {-0.8, 0, 0}}});
  const int joint1 = int(b.gltf["nodes"].size()) + 1;
  const int joint0 = b.node({{"children", {joint1}}});
  b.gltf["nodes"].push_back({{"translation", {0, 1, 0}}});
  const std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,
                                  1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  const int ibm_acc = b.accessor(ibm.data(), ibm.size() * 4, 5126, "MAT4", 2);
  b.gltf["skins"] = {{{"joints", {joint0, joint1}}, {"inverseBindMatrices", ibm_acc}}};
  const int times = scalar_floats(b, {0.0f, 1.0f});
  const auto about_z = [](float deg) {
    const float h = 0.5f * deg * kPi / 180.0f;
    return glm::vec4(0, 0, std::sin(h), std::cos(h));
  };
  const std::vector<glm::vec4> r0 = {about_z(0), about_z(30)};
  const std::vector<glm::vec4> r1 = {about_z(0), about_z(-70)};
  const std::vector<glm::vec3> s1 = {{1, 1, 1}, {1.4f, 1.0f, 0.6f}};
  const std::vector<glm::vec3> t_m = {{-0.8f, 0, 0}, {-0.8f, 0.5f, 0}};
  const int w = scalar_floats(b, {0.0f, 1.0f});
  b.gltf["animations"] = {
      {{"name", "move"},
       {"samplers",
        {{{"input", times}, {"output", b.floats(r0)}},
         {{"input", times}, {"output", b.floats(r1)}},
         {{"input", times}, {"output", b.floats(s1)}},
         {{"input", times}, {"output", w}},
         {{"input", times}, {"output", b.floats(t_m)}}}},
       {"channels",
        {{{"sampler", 0}, {"target", {{"node", joint0}, {"path", "rotation"}}}},
         {{"sampler", 1}, {"target", {{"node", joint1}, {"path", "rotation"}}}},
         {{"sampler", 2}, {"target", {{"node", joint1}, {"path", "scale"}}}},
         {{"sampler", 3}, {"target", {{"node", node_a}, {"path", "weights"}}}},
         {{"sampler", 3}, {"target", {{"node", node_m}, {"path", "weights"}}}},
         {{"sampler", 4}, {"target", {{"node", node_m}, {"path", "translation"}}}}}}}};
  return b.write("gpu_pose_rig.glb");
}

Scene rig_scene() {
  Scene s = load_scene(rig_file().string());
  Light sun;
  sun.type = Light::Type::kDirectional;
  sun.intensity = 3.0f;
  sun.direction = glm::normalize(glm::vec3(-0.4f, -0.5f, -1.0f));
  s.lights.push_back(sun);
  Light lamp;
  lamp.position = {1.5f, 2.5f, 2.0f};
  lamp.intensity = 8.0f;
  lamp.color = {0.6f, 0.8f, 1.0f};
  s.lights.push_back(lamp);
  return s;
}

RenderSettings settings(DebugChannel channel = DebugChannel::kNone) {
  RenderSettings r;
  r.ibl = false;
  r.debug_channel = channel;
  return r;
}

// Whether a pixel shows a surface (the base-colour channel: the background is black).
std::vector<bool> coverage(const Image& base_color) {
  std::vector<bool> c(base_color.pixel_count());
  for (int y = 0; y < base_color.height; ++y)
    for (int x = 0; x < base_color.width; ++x)
      c[std::size_t(y * base_color.width + x)] = base_color.rgb(x, y).r > 0.4f;
  return c;
}

double iou(const std::vector<bool>& a, const std::vector<bool>& b) {
  std::size_t both = 0, either = 0;
  for (std::size_t i = 0; i < a.size(); ++i) both += a[i] && b[i], either += a[i] || b[i];
  return either ? double(both) / double(either) : 1.0;
}

// The mean over the pixels of |a - b| (R+G+B), over the mean of a's R+G+B.
double relative_mean_difference(const Image& a, const Image& b) {
  double diff = 0.0, sum = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const glm::vec3 d = glm::abs(a.rgb(x, y) - b.rgb(x, y));
      diff += double(d.r + d.g + d.b);
      sum += double(a.rgb(x, y).r + a.rgb(x, y).g + a.rgb(x, y).b);
    }
  return diff / std::max(sum, 1e-12);
}

// The largest |a - b| over the pixels whose 3x3 neighbourhood is covered in both (inside
// the silhouettes, where rasterisation differences cannot reach).
float interior_max_difference(const Image& a, const Image& b, const std::vector<bool>& ca,
                              const std::vector<bool>& cb) {
  float worst = 0.0f;
  for (int y = 1; y + 1 < a.height; ++y)
    for (int x = 1; x + 1 < a.width; ++x) {
      bool inside = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::size_t i = std::size_t((y + dy) * a.width + x + dx);
          inside = inside && ca[i] && cb[i];
        }
      if (!inside) continue;
      const glm::vec3 d = glm::abs(a.rgb(x, y) - b.rgb(x, y));
      worst = std::max({worst, d.r, d.g, d.b});
    }
  return worst;
}

// The frames of one pose: shaded, base colour (coverage), normals.
struct Frames {
  Image shaded, base_color, normal;
};

Frames draw(Renderer& r, const Camera& camera) {
  Frames f;
  r.render(camera, kWidth, kHeight, settings());
  f.shaded = r.read_back();
  r.render(camera, kWidth, kHeight, settings(DebugChannel::kBaseColor));
  f.base_color = r.read_back();
  r.render(camera, kWidth, kHeight, settings(DebugChannel::kNormal));
  f.normal = r.read_back();
  return f;
}

// The CPU's pose, uploaded as static geometry (no motion: nothing to deform).
Frames cpu_posed(const Scene& rest, const PoseTime& pose, const Camera& camera) {
  Scene posed = rest;
  pose_scene(posed, pose);
  posed.motion.reset();
  Renderer r;
  r.set_scene(posed);
  return draw(r, camera);
}

Camera camera_for(const Scene& rest, const PoseTime& pose) {
  Scene posed = rest;
  pose_scene(posed, pose);
  Bounds b = posed.world_bounds();
  b.extend(rest.world_bounds().min), b.extend(rest.world_bounds().max);
  return auto_camera(b, float(kWidth) / float(kHeight));
}

TEST(GlGpuPose, TheVertexShadersPoseIsTheCpusPose) {
  testing::context();
  const Scene rest = rig_scene();
  ASSERT_TRUE(rest.motion);
  ASSERT_EQ(rest.motion->deforming.size(), 3u);
  int flat = 0;
  for (const DeformingMesh& d : rest.motion->deforming) flat += d.flat_normals;
  ASSERT_EQ(flat, 1);
  const PoseTime pose{0, 0.8f};
  const Camera camera = camera_for(rest, pose);
  const Frames cpu = cpu_posed(rest, pose, camera);

  Renderer r;
  r.set_scene(rest);
  r.set_pose({0, 0.3f});  // another pose first: set_pose replaces it
  r.set_pose(pose);
  const Frames gpu = draw(r, camera);

  const std::vector<bool> c_cpu = coverage(cpu.base_color), c_gpu = coverage(gpu.base_color);
  EXPECT_GE(iou(c_cpu, c_gpu), 0.99);
  // (llvmpipe gives 1 and 0; flat normals left smooth differ by 0.003)
  EXPECT_LT(relative_mean_difference(cpu.shaded, gpu.shaded), 0.002);
  // Inside the silhouettes the normals agree to rounding (a normal transformed by the
  // matrix instead of its inverse transpose is off by 0.2 under joint 1's scale, flat
  // normals left smooth by 0.6).
  EXPECT_LT(interior_max_difference(cpu.normal, gpu.normal, c_cpu, c_gpu), 0.01f);
  EXPECT_LT(relative_mean_difference(cpu.normal, gpu.normal), 0.002);

  // The pose moved the rig: the rest pose's coverage is far from it.
  const Frames at_rest = cpu_posed(rest, {}, camera);
  EXPECT_LT(iou(coverage(at_rest.base_color), c_gpu), 0.9);
  // Back to the rest pose on the GPU: the CPU's rest pose.
  r.set_pose({});
  const Frames gpu_rest = draw(r, camera);
  EXPECT_GE(iou(coverage(at_rest.base_color), coverage(gpu_rest.base_color)), 0.99);
  EXPECT_LT(relative_mean_difference(at_rest.shaded, gpu_rest.shaded), 0.002);
}

// set_pose deforms from the rest data whatever pose the scene given to set_scene was in:
// a scene pose_scene posed elsewhere draws the same pixels.
TEST(GlGpuPose, SetPoseIgnoresTheVerticesTheSceneWasPosedTo) {
  testing::context();
  const Scene rest = rig_scene();
  const PoseTime pose{0, 0.6f};
  const Camera camera = camera_for(rest, pose);
  Scene elsewhere = rest;
  pose_scene(elsewhere, {0, 0.1f});
  Renderer a, b;
  a.set_scene(rest);
  a.set_pose(pose);
  b.set_scene(elsewhere);
  b.set_pose(pose);
  a.render(camera, kWidth, kHeight, settings());
  b.render(camera, kWidth, kHeight, settings());
  const Image ia = a.read_back(), ib = b.read_back();
  float worst = 0.0f;
  for (std::size_t i = 0; i < ia.data.size(); ++i)
    worst = std::max(worst, std::abs(ia.data[i] - ib.data[i]));
  EXPECT_EQ(worst, 0.0f);
}

TEST(GlGpuPose, SetPoseRefusesWhatPoseSceneRefuses) {
  testing::context();
  const Scene rest = rig_scene();
  Renderer r;
  r.set_scene(rest);
  EXPECT_THROW(r.set_pose({1, 0.0f}), Error);  // one animation
  EXPECT_THROW(r.set_pose({0, std::nanf("")}), Error);
  Scene still;
  r.set_scene(still);
  r.set_pose({});  // the rest pose of a scene without motion: nothing to do
  EXPECT_THROW(r.set_pose({0, 0.0f}), Error);
}

}  // namespace
}  // namespace pbrkit::gl
