// Posing loaded glTF files: a two-bone rig at known angles (positions worked out by hand
// below), morph weights, animated cameras and lights, and hostile animation data.
#include "pbrkit/scene/pose.h"

#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gltf_builder.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit {
namespace {

using json = nlohmann::json;
constexpr float kPi = 3.14159265358979f;

struct QuietLog {
  LogSink previous = set_log_sink([](LogLevel, const std::string&) {});
  ~QuietLog() { set_log_sink(previous); }
};

void expect_near(glm::vec3 a, glm::vec3 b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

glm::vec3 world_vertex(const Scene& s, int instance, std::size_t vertex) {
  const Instance& inst = s.instances[std::size_t(instance)];
  return glm::vec3(inst.transform *
                   glm::vec4(s.meshes[std::size_t(inst.mesh)].positions[vertex], 1.0f));
}

int scalar_floats(test::GltfBuilder& b, const std::vector<float>& v) {
  return b.accessor(v.data(), v.size() * 4, 5126, "SCALAR", v.size());
}

// Two joints: joint 0 at the origin, joint 1 one unit up +y as its child. Three vertices:
// (0, 2, 0) bound to joint 1, (0, 0.5, 0) half to each, (1, 0, 0) bound to joint 0.
// Animation "bend": joint 0 turns +90 degrees about z over [0, 1]; joint 1 turns -90.
struct TwoBoneRig {
  test::GltfBuilder b;
  int skinned = -1, joint0 = -1, joint1 = -1;
  TwoBoneRig() {
    json prim = b.primitive({{0, 2, 0}, {0, 0.5f, 0}, {1, 0, 0}}, {0, 1, 2});
    const std::uint8_t joints[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0};
    const std::vector<glm::vec4> weights = {{1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}};
    prim["attributes"]["JOINTS_0"] = b.accessor(joints, 12, 5121, "VEC4", 3);
    prim["attributes"]["WEIGHTS_0"] = b.floats(weights);
    const int mesh = b.mesh({prim});
    // The skinned node's own transform must be ignored (glTF 2.0 section 3.7.3.1): give it one.
    skinned = b.node({{"mesh", mesh}, {"skin", 0}, {"translation", {50, 0, 0}}});
    joint1 = int(b.gltf["nodes"].size()) + 1;
    joint0 = b.node({{"children", {joint1}}});
    b.gltf["nodes"].push_back({{"translation", {0, 1, 0}}});
    // Inverse bind matrices: the inverses of the joints' rest world transforms.
    const std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,
                                    1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
    const int ibm_acc = b.accessor(ibm.data(), ibm.size() * 4, 5126, "MAT4", 2);
    b.gltf["skins"] = {{{"joints", {joint0, joint1}}, {"inverseBindMatrices", ibm_acc}}};
    const int times = scalar_floats(b, {0.0f, 1.0f});
    const float h = std::sqrt(0.5f);
    const std::vector<glm::vec4> r0 = {{0, 0, 0, 1}, {0, 0, h, h}};   // 0 -> +90 about z
    const std::vector<glm::vec4> r1 = {{0, 0, 0, 1}, {0, 0, -h, h}};  // 0 -> -90 about z
    b.gltf["animations"] = {
        {{"name", "bend"},
         {"samplers",
          {{{"input", times}, {"output", b.floats(r0)}},
           {{"input", times}, {"output", b.floats(r1)}}}},
         {"channels",
          {{{"sampler", 0}, {"target", {{"node", joint0}, {"path", "rotation"}}}},
           {{"sampler", 1}, {"target", {{"node", joint1}, {"path", "rotation"}}}}}}}};
  }
};

TEST(Pose, TwoBoneRigAtRestAndBent) {
  TwoBoneRig rig;
  Scene s = load_scene(rig.b.write("two_bone_rig.glb").string());
  ASSERT_TRUE(s.motion);
  ASSERT_EQ(s.instances.size(), 1u);
  // At rest the joint matrices are identities: the vertices are where the file put them,
  // and the skinned node's translation by 50 is ignored.
  expect_near(world_vertex(s, 0, 0), {0, 2, 0});
  expect_near(world_vertex(s, 0, 1), {0, 0.5f, 0});
  EXPECT_EQ(find_animation(s, "bend"), 0);
  EXPECT_EQ(find_animation(s, "0"), 0);
  pose_scene(s, {0, 1.0f});
  // By hand, with R+ (x, y) -> (-y, x) and R- (x, y) -> (y, -x):
  //  (0, 2): joint 1's matrix R+ T(0,1) R- T(0,-1): (0,1) -> R- (1,0) -> T (1,1) -> R+ (-1,1).
  expect_near(world_vertex(s, 0, 0), {-1, 1, 0});
  //  (0, 0.5): joint 0 gives R+ (0,0.5) = (-0.5, 0); joint 1: (0,-0.5) -> R- (-0.5,0) ->
  //  T (-0.5,1) -> R+ (-1,-0.5). Half of each: (-0.75, -0.25).
  expect_near(world_vertex(s, 0, 1), {-0.75f, -0.25f, 0});
  //  (1, 0) on joint 0: R+ (1, 0) = (0, 1).
  expect_near(world_vertex(s, 0, 2), {0, 1, 0});
  // Halfway (t = 0.5): joint 0 at +45, joint 1 at -45; vertex 2 at (cos 45, sin 45).
  pose_scene(s, {0, 0.5f});
  expect_near(world_vertex(s, 0, 2), {std::cos(kPi / 4), std::sin(kPi / 4), 0});
  // Back to rest.
  pose_scene(s, {});
  expect_near(world_vertex(s, 0, 0), {0, 2, 0});
}

TEST(Pose, SkinnedNormalsFollowTheInverseTranspose) {
  // A triangle in the xy plane with normal +z, bound to a joint scaled (2, 1, 1) and then
  // turned: the normal of a plane is turned, never sheared, so it stays +z.
  test::GltfBuilder b;
  json prim = b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  const std::uint8_t joints[12] = {};
  const std::vector<glm::vec4> weights(3, glm::vec4(1, 0, 0, 0));
  const std::vector<glm::vec3> normals(3, glm::vec3(0, 0, 1));
  prim["attributes"]["JOINTS_0"] = b.accessor(joints, 12, 5121, "VEC4", 3);
  prim["attributes"]["WEIGHTS_0"] = b.floats(weights);
  prim["attributes"]["NORMAL"] = b.floats(normals);
  const int mesh = b.mesh({prim});
  b.node({{"mesh", mesh}, {"skin", 0}});
  const int joint = b.node({{"scale", {2, 1, 1}}, {"rotation", {0, 0.38268343, 0, 0.92387953}}});
  b.gltf["skins"] = {{{"joints", {joint}}}};
  const Scene s = load_scene(b.write("skinned_normals.glb").string());
  const Mesh& m = s.meshes[std::size_t(s.instances[0].mesh)];
  // The plane z = 0 scaled in x stays z = 0; turned 45 degrees about y its normal is
  // (sin 45, 0, cos 45).
  expect_near(m.normals[0], {std::sin(kPi / 4), 0, std::cos(kPi / 4)});
  expect_near(world_vertex(s, 0, 1), {2 * std::cos(kPi / 4), 0, -2 * std::sin(kPi / 4)});
}

TEST(Pose, AnimatedMorphWeightsMoveTheVertices) {
  test::GltfBuilder b;
  json prim = b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  const std::vector<glm::vec3> up = {{0, 0, 1}, {0, 0, 0}, {0, 0, 0}};
  const std::vector<glm::vec3> right = {{1, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  prim["targets"] = {{{"POSITION", b.floats(up)}}, {{"POSITION", b.floats(right)}}};
  const int mesh = b.mesh({prim});
  b.gltf["meshes"][std::size_t(mesh)]["weights"] = {0.5, 0.0};
  const int node = b.node({{"mesh", mesh}, {"translation", {0, 0, -3}}});
  const int times = scalar_floats(b, {0.0f, 2.0f});
  const int values = scalar_floats(b, {0.0f, 1.0f, 1.0f, 0.5f});  // (w0, w1) per key
  b.gltf["animations"] = {
      {{"samplers", {{{"input", times}, {"output", values}}}},
       {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "weights"}}}}}}}};
  Scene s = load_scene(b.write("morph_weights.glb").string());
  // At rest: the mesh's default weights (0.5, 0): vertex 0 at z = 0.5, then the node's -3.
  expect_near(world_vertex(s, 0, 0), {0, 0, -2.5f});
  // t = 0.5: weights (0.25, 0.875) by linear interpolation.
  pose_scene(s, {0, 0.5f});
  expect_near(world_vertex(s, 0, 0), {0.875f, 0, -3 + 0.25f});
  expect_near(world_vertex(s, 0, 1), {1, 0, -3});
}

TEST(Pose, CamerasAndLightsFollowTheirNodes) {
  test::GltfBuilder b;
  const int mesh = b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2})});
  b.node({{"mesh", mesh}});
  b.gltf["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
  b.gltf["extensionsUsed"] = {"KHR_lights_punctual"};
  b.gltf["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "directional"}}};
  const int cam = b.node({{"camera", 0}, {"translation", {0, 0, 5}}});
  const int light = b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  const int times = scalar_floats(b, {0.0f, 1.0f});
  const std::vector<glm::vec3> path = {{0, 0, 5}, {4, 0, 5}};
  const float h = std::sqrt(0.5f);
  const std::vector<glm::vec4> turn = {{0, 0, 0, 1}, {0, h, 0, h}};  // +90 about y
  b.gltf["animations"] = {
      {{"samplers",
        {{{"input", times}, {"output", b.floats(path)}},
         {{"input", times}, {"output", b.floats(turn)}}}},
       {"channels",
        {{{"sampler", 0}, {"target", {{"node", cam}, {"path", "translation"}}}},
         {{"sampler", 1}, {"target", {{"node", light}, {"path", "rotation"}}}}}}}};
  Scene s = load_scene(b.write("camera_light_motion.glb").string());
  expect_near(s.cameras[0].position(), {0, 0, 5});
  pose_scene(s, {0, 0.25f});
  expect_near(s.cameras[0].position(), {1, 0, 5});
  // -z turned +90 about y is -x.
  expect_near(s.lights[0].direction, {-std::sin(kPi / 8), 0, -std::cos(kPi / 8)});
  pose_scene(s, {0, 1.0f});
  expect_near(s.lights[0].direction, {-1, 0, 0});
}

TEST(Pose, UnknownAnimationListsTheKnownOnes) {
  TwoBoneRig rig;
  const Scene s = load_scene(rig.b.write("two_bone_rig.glb").string());
  try {
    find_animation(s, "walk");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'bend'"), std::string::npos) << e.what();
  }
  Scene copy = s;
  EXPECT_THROW(pose_scene(copy, {3, 0.0f}), Error);
}

// Each hostile edit must be refused with the JSON path it names.
void expect_refused(test::GltfBuilder& b, const std::string& path_in_message) {
  QuietLog quiet;
  try {
    load_scene(b.write("hostile_animation.glb").string());
    FAIL() << "loaded; expected an error naming " << path_in_message;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path_in_message), std::string::npos) << e.what();
  }
}

TEST(Pose, HostileAnimationsAreRefusedNamingTheJsonPath) {
  {
    TwoBoneRig rig;  // a channel pointing at a node that does not exist
    rig.b.gltf["animations"][0]["channels"][1]["target"]["node"] = 99;
    expect_refused(rig.b, "animations[0].channels[1].target.node");
  }
  {
    TwoBoneRig rig;  // times not increasing
    const int times = scalar_floats(rig.b, {0.0f, 1.0f, 1.0f});
    const std::vector<glm::vec4> r = {{0, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}};
    rig.b.gltf["animations"][0]["samplers"][0] = {{"input", times}, {"output", rig.b.floats(r)}};
    expect_refused(rig.b, "animations[0].samplers[0].input");
  }
  {
    TwoBoneRig rig;  // a NaN key value
    const std::vector<glm::vec4> r = {{0, 0, 0, 1}, {0, 0, std::nanf(""), 1}};
    rig.b.gltf["animations"][0]["samplers"][1]["output"] = rig.b.floats(r);
    expect_refused(rig.b, "animations[0].samplers[1].output");
  }
  {
    TwoBoneRig rig;  // fewer values than keys
    const std::vector<glm::vec4> r = {{0, 0, 0, 1}};
    rig.b.gltf["animations"][0]["samplers"][1]["output"] = rig.b.floats(r);
    expect_refused(rig.b, "animations[0].samplers[1].output");
  }
  {
    TwoBoneRig rig;  // a joint index beyond the skin's two joints
    const std::uint8_t joints[12] = {1, 0, 0, 0, 0, 7, 0, 0, 0, 0, 0, 0};
    rig.b.gltf["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] =
        rig.b.accessor(joints, 12, 5121, "VEC4", 3);
    expect_refused(rig.b, "meshes[0].primitives[0].attributes.JOINTS_0");
  }
  {
    TwoBoneRig rig;  // a skin joint that is no node
    rig.b.gltf["skins"][0]["joints"][1] = 42;
    expect_refused(rig.b, "skins[0].joints[1]");
  }
  {
    TwoBoneRig rig;  // a cyclic joint hierarchy: joint 1 parents joint 0
    rig.b.gltf["nodes"][std::size_t(rig.joint1)]["children"] = {rig.joint0};
    expect_refused(rig.b, "nodes[");
  }
  {
    TwoBoneRig rig;  // an unknown interpolation
    rig.b.gltf["animations"][0]["samplers"][0]["interpolation"] = "BEZIER";
    expect_refused(rig.b, "animations[0].samplers[0].interpolation");
  }
}

}  // namespace
}  // namespace pbrkit
