// KHR_animation_pointer: a material's core factor, an extension's factor (through the
// material schema), a texture transform, a light's intensity, a camera's field of view and
// a node's translation, each animated by pointer and checked at a time worked out by hand;
// the rest pose restores them; bad pointers are refused or ignored as the README asks.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gltf_builder.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit {
namespace {

using json = nlohmann::json;

struct CaptureLog {
  std::vector<std::string> lines;
  LogSink previous;
  CaptureLog() {
    previous = set_log_sink([this](LogLevel, const std::string& m) { lines.push_back(m); });
  }
  ~CaptureLog() { set_log_sink(previous); }
};

// A 1x1 PNG (a white pixel), for a texture to transform.
constexpr const char* kPixel =
    "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAAAAAA6fptVAAAACklEQVR4nGP4DwABAQEA"
    "sTj2FAAAAABJRU5ErkJggg==";

struct PointerFile {
  test::GltfBuilder b;
  PointerFile() {
    json prim = b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, 0);
    const std::vector<float> uv = {0, 0, 1, 0, 0, 1};
    prim["attributes"]["TEXCOORD_0"] = b.accessor(uv.data(), 24, 5126, "VEC2", 3);
    const int mesh = b.mesh({prim});
    b.gltf["images"] = {{{"uri", kPixel}}};
    b.gltf["textures"] = {{{"source", 0}}};
    b.gltf["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    b.gltf["extensionsUsed"] = {"KHR_animation_pointer", "KHR_lights_punctual"};
    b.gltf["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"intensity", 10}}};
    b.gltf["cameras"] = {
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}};
    b.node({{"mesh", mesh}});
    b.node({{"camera", 0}, {"translation", {0, 0, 5}}});
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    const std::vector<float> times = {0.0f, 2.0f};
    const int t = b.accessor(times.data(), 8, 5126, "SCALAR", 2);
    auto values = [&](std::vector<float> v, const char* type, std::size_t count) {
      return b.accessor(v.data(), v.size() * 4, 5126, type, count);
    };
    const int colour = values({1, 1, 1, 1, 0, 0.5f, 1, 1}, "VEC4", 2);
    const int coat = values({0, 1}, "SCALAR", 2);
    const int offset = values({0, 0, 1, 0.5f}, "VEC2", 2);
    const int intensity = values({10, 20}, "SCALAR", 2);
    const int yfov = values({0.5f, 1.0f}, "SCALAR", 2);
    const int move = values({0, 0, 5, 2, 0, 5}, "VEC3", 2);
    json samplers = json::array(), channels = json::array();
    auto channel = [&](int output, const std::string& pointer) {
      samplers.push_back({{"input", t}, {"output", output}});
      channels.push_back({{"sampler", samplers.size() - 1},
                          {"target",
                           {{"path", "pointer"},
                            {"extensions", {{"KHR_animation_pointer", {{"pointer", pointer}}}}}}}});
    };
    channel(colour, "/materials/0/pbrMetallicRoughness/baseColorFactor");
    channel(coat, "/materials/0/extensions/KHR_materials_clearcoat/clearcoatFactor");
    channel(offset,
            "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/"
            "offset");
    channel(intensity, "/extensions/KHR_lights_punctual/lights/0/intensity");
    channel(yfov, "/cameras/0/perspective/yfov");
    channel(move, "/nodes/1/translation");
    channel(coat, "/materials/0/doesNotExist");
    b.gltf["animations"] = {{{"name", "pointers"}, {"samplers", samplers}, {"channels", channels}}};
  }
};

TEST(AnimationPointer, EveryKindOfTargetMovesAndRestsAgain) {
  PointerFile f;
  CaptureLog log;
  Scene s = load_scene(f.b.write("pointers.glb").string());
  // The unknown property is a warning naming its pointer, and the rest is played.
  bool warned = false;
  for (const std::string& l : log.lines) warned |= l.find("/materials/0/doesNotExist") != l.npos;
  EXPECT_TRUE(warned);
  ASSERT_EQ(s.lights.size(), 1u);
  ASSERT_EQ(s.cameras.size(), 1u);
  pose_scene(s, {0, 1.0f});  // halfway through every channel
  const Material& m = s.materials[0];
  EXPECT_FLOAT_EQ(m.base_color_factor.r, 0.5f);
  EXPECT_FLOAT_EQ(m.base_color_factor.g, 0.75f);
  EXPECT_FLOAT_EQ(m.base_color_factor.b, 1.0f);
  ASSERT_TRUE(m.clearcoat);
  EXPECT_FLOAT_EQ(m.clearcoat->factor, 0.5f);
  ASSERT_TRUE(m.base_color_texture.transform);
  EXPECT_FLOAT_EQ(m.base_color_texture.transform->offset.x, 0.5f);
  EXPECT_FLOAT_EQ(m.base_color_texture.transform->offset.y, 0.25f);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 15.0f);
  EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.75f);
  EXPECT_NEAR(s.cameras[0].position().x, 1.0f, 1e-6f);
  // The rest pose: the file's values (a clearcoat of 0 is the absent extension's look).
  pose_scene(s, {});
  EXPECT_FLOAT_EQ(s.materials[0].base_color_factor.g, 1.0f);
  EXPECT_FLOAT_EQ(s.materials[0].clearcoat->factor, 0.0f);
  EXPECT_FLOAT_EQ(s.materials[0].base_color_texture.transform->offset.x, 0.0f);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 10.0f);
  EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.5f);
  EXPECT_NEAR(s.cameras[0].position().x, 0.0f, 1e-6f);
  // Clamped outside the keys, and to the factor's range.
  pose_scene(s, {0, 5.0f});
  EXPECT_FLOAT_EQ(s.materials[0].clearcoat->factor, 1.0f);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 20.0f);
}

TEST(AnimationPointer, VisibilityHidesANodeAndItsChildrenAndComesBack) {
  // Node 0 (a triangle at x in [0, 1]) with child node 1 (a triangle 5 units up, and a
  // light); node 2 (a triangle at x in [10, 11]) hidden by the file. Animation "blink",
  // STEP: node 0 visible until 1 s, then hidden; node 2 hidden until 1 s, then visible.
  test::GltfBuilder b;
  const int mesh = b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2})});
  b.gltf["extensionsUsed"] = {"KHR_animation_pointer", "KHR_node_visibility",
                              "KHR_lights_punctual"};
  b.gltf["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 7}}};
  b.node({{"mesh", mesh}, {"children", {1}}});
  b.gltf["nodes"].push_back({{"mesh", mesh},
                             {"translation", {0, 5, 0}},
                             {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.node({{"mesh", mesh},
          {"translation", {10, 0, 0}},
          {"extensions", {{"KHR_node_visibility", {{"visible", false}}}}}});
  b.gltf["scenes"][0]["nodes"] = {0, 2};
  const std::vector<float> times = {0.0f, 1.0f}, on_off = {1.0f, 0.0f}, off_on = {0.0f, 1.0f};
  const int t = b.accessor(times.data(), 8, 5126, "SCALAR", 2);
  const int a = b.accessor(on_off.data(), 8, 5126, "SCALAR", 2);
  const int c = b.accessor(off_on.data(), 8, 5126, "SCALAR", 2);
  auto visible = [](int node) {
    return json{
        {"path", "pointer"},
        {"extensions",
         {{"KHR_animation_pointer",
           {{"pointer", fmt::format("/nodes/{}/extensions/KHR_node_visibility/visible", node)}}}}}};
  };
  b.gltf["animations"] = {
      {{"name", "blink"},
       {"samplers",
        {{{"input", t}, {"output", a}, {"interpolation", "STEP"}},
         {{"input", t}, {"output", c}, {"interpolation", "STEP"}}}},
       {"channels",
        {{{"sampler", 0}, {"target", visible(0)}}, {{"sampler", 1}, {"target", visible(2)}}}}}};
  CaptureLog quiet;
  Scene s = load_scene(b.write("blink.glb").string());
  ASSERT_EQ(s.instances.size(), 3u);  // every node's mesh kept: the animation shows node 2
  ASSERT_EQ(s.lights.size(), 1u);
  auto shown = [&](int node) {
    for (const Instance& i : s.instances)
      if (i.node == node) return i.transform != glm::mat4(0.0f);
    return false;
  };
  // At rest: the file's visibility.
  EXPECT_TRUE(shown(0));
  EXPECT_TRUE(shown(1));
  EXPECT_FALSE(shown(2));
  EXPECT_FLOAT_EQ(s.world_bounds().max.x, 1.0f);
  pose_scene(s, {0, 0.5f});
  EXPECT_TRUE(shown(0) && shown(1) && !shown(2));
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 7.0f);
  pose_scene(s, {0, 1.5f});  // node 0 hidden, and with it its child and the child's light
  EXPECT_FALSE(shown(0));
  EXPECT_FALSE(shown(1));
  EXPECT_TRUE(shown(2));
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 0.0f);
  EXPECT_FLOAT_EQ(s.world_bounds().min.x, 10.0f);  // the hidden nodes bound nothing
  pose_scene(s, {0, 0.2f});
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 7.0f);
  EXPECT_TRUE(shown(1));
}

TEST(AnimationPointer, BadPointersAreRefusedNamingTheJsonPath) {
  auto refused = [](PointerFile& f, const std::string& in_message) {
    CaptureLog quiet;
    try {
      load_scene(f.b.write("bad_pointer.glb").string());
      ADD_FAILURE() << "loaded; expected an error naming " << in_message;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(in_message), std::string::npos) << e.what();
    }
  };
  {
    PointerFile f;  // a material that does not exist
    f.b.gltf["animations"][0]["channels"][0]["target"]["extensions"]["KHR_animation_pointer"]
            ["pointer"] = "/materials/7/pbrMetallicRoughness/baseColorFactor";
    refused(f, "animations[0].channels[0].target.extensions.KHR_animation_pointer.pointer");
  }
  {
    PointerFile f;  // no pointer string
    f.b.gltf["animations"][0]["channels"][2]["target"]["extensions"]["KHR_animation_pointer"]
            ["pointer"] = 3;
    refused(f, "animations[0].channels[2].target.extensions.KHR_animation_pointer.pointer");
  }
  {
    PointerFile f;  // values of the wrong width: VEC3 for a VEC4 colour
    const std::vector<float> v = {1, 1, 1, 0, 0, 0};
    f.b.gltf["animations"][0]["samplers"][0]["output"] =
        f.b.accessor(v.data(), 24, 5126, "VEC3", 2);
    refused(f, "animations[0].samplers[0].output");
  }
}

}  // namespace
}  // namespace pbrkit
