// KHR_node_visibility: a node with `visible: false` and all its descendants (even those
// that say true) are not drawn: no instances, no lights; their cameras stay ("Visibility
// affects neither cameras", README, "Extending Nodes"). A `visible` that is not a boolean
// is an error naming its JSON path.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"
#include "scene/gltf_builder.h"

namespace pbrkit {
namespace {

using nlohmann::json;

json visible(bool v) {
  return {{"KHR_node_visibility", {{"visible", v}}}};
}

// Roots: node 0 (hidden; children 1, which says visible, and 2, with a light and a camera)
// and node 3 (visible by default), each of nodes 0, 1 and 3 drawing the triangle mesh.
struct HiddenTree {
  test::GltfBuilder b;
  HiddenTree() {
    b.gltf["extensionsUsed"] = {"KHR_node_visibility", "KHR_lights_punctual"};
    b.gltf["extensionsRequired"] = {"KHR_node_visibility"};
    b.gltf["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}}};
    b.gltf["cameras"] = {
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
    const int mesh = b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2})});
    b.node({{"mesh", mesh}, {"children", {1, 2}}, {"extensions", visible(false)}});
    b.node({{"mesh", mesh}, {"extensions", visible(true)}});
    const json light = {{"KHR_lights_punctual", {{"light", 0}}}};
    b.node({{"camera", 0}, {"extensions", light}});
    b.node({{"mesh", mesh}, {"translation", {3, 0, 0}}});
    b.gltf["scenes"][0]["nodes"] = {0, 3};
  }
};

TEST(NodeVisibility, AHiddenSubtreeIsNeitherDrawnNorLit) {
  HiddenTree t;
  const Scene s = load_scene(t.b.write("visibility.glb").string());
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.instances[0].node, 3);
  EXPECT_TRUE(s.lights.empty());
  EXPECT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.node_count, 4u);

  // Visible again: every node draws, the light shines.
  t.b.gltf["nodes"][0]["extensions"] = visible(true);
  const Scene shown = load_scene(t.b.write("visibility_shown.glb").string());
  EXPECT_EQ(shown.instances.size(), 3u);
  EXPECT_EQ(shown.lights.size(), 1u);

  // Hiding a child hides only it (and what is below it).
  t.b.gltf["nodes"][1]["extensions"] = visible(false);
  const Scene child = load_scene(t.b.write("visibility_child.glb").string());
  ASSERT_EQ(child.instances.size(), 2u);
  EXPECT_EQ(child.instances[0].node, 0);
  EXPECT_EQ(child.instances[1].node, 3);
}

TEST(NodeVisibility, AVisibleThatIsNotABooleanIsAnError) {
  for (const json& bad : {json(0), json("false"), json(nullptr)}) {
    SCOPED_TRACE(bad.dump());
    HiddenTree t;
    t.b.gltf["nodes"][1]["extensions"]["KHR_node_visibility"]["visible"] = bad;
    const auto path = t.b.write("visibility_bad.glb");
    try {
      load_scene(path.string());
      ADD_FAILURE() << "loaded";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(
                    path.string() + ": nodes[1].extensions.KHR_node_visibility.visible: must be a "
                                    "boolean",
                    0),
                0u)
          << e.what();
    }
  }
  HiddenTree t;
  t.b.gltf["nodes"][2]["extensions"]["KHR_node_visibility"] = true;
  EXPECT_THROW(load_scene(t.b.write("visibility_bad_ext.glb").string()), Error);
}

}  // namespace
}  // namespace pbrkit
