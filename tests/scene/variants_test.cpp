// KHR_materials_variants: the root's variants and the primitives' mappings load into
// Scene::variants and Mesh::variant_materials; apply_variant switches exactly the mapped
// primitives and leaves the others at their own material (README, "Mappings"); a variant
// that splits a volume's shell changes Mesh::closed; bad extension JSON is an error naming
// its JSON path.
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/scene/variants.h"
#include "pbrkit/util/error.h"
#include "scene/gltf_builder.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

using nlohmann::json;

json mappings(std::vector<std::pair<int, std::vector<int>>> m) {
  json out = json::array();
  for (const auto& [material, variants] : m)
    out.push_back({{"material", material}, {"variants", variants}});
  return {{"KHR_materials_variants", {{"mappings", out}}}};
}

// Materials red (0), blue (1), green (2); variants "Blue" (0) and "Green" (1). Mesh 0 has a
// primitive mapped to blue / green and one without mappings, all red by default; mesh 1
// (green, placed by two nodes) turns blue under "Green".
struct VariantsFile {
  test::GltfBuilder b;
  VariantsFile() {
    b.gltf["extensionsUsed"] = {"KHR_materials_variants"};
    b.gltf["extensionsRequired"] = {"KHR_materials_variants"};
    b.gltf["materials"] = {{{"name", "red"}}, {{"name", "blue"}}, {{"name", "green"}}};
    b.gltf["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "Blue"}},
                                                                  {{"name", "Green"}}};
    const std::vector<glm::vec3> tri = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    json mapped = b.primitive(tri, {0, 1, 2}, 0);
    mapped["extensions"] = mappings({{1, {0}}, {2, {1}}});
    json green = b.primitive(tri, {0, 1, 2}, 2);
    green["extensions"] = mappings({{1, {1}}});
    b.node({{"mesh", b.mesh({mapped, b.primitive(tri, {0, 1, 2}, 0)})}});
    const int shared = b.mesh({green});
    b.node({{"mesh", shared}});
    b.node({{"mesh", shared}, {"translation", {2, 0, 0}}});
  }
  json& primitive_ext(int mesh, int primitive) {
    return b.gltf["meshes"][std::size_t(mesh)]["primitives"][std::size_t(primitive)]["extensions"]
                 ["KHR_materials_variants"];
  }
};

std::vector<int> materials(const Scene& s) {
  std::vector<int> out;
  for (const Mesh& m : s.meshes) out.push_back(m.material);
  return out;
}

TEST(MaterialVariants, SwitchChangesExactlyTheMappedPrimitives) {
  VariantsFile f;
  Scene s = load_scene(f.b.write("variants.glb").string());
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_EQ(s.variants, (std::vector<std::string>{"Blue", "Green"}));
  EXPECT_EQ(s.active_variant, -1);
  ASSERT_EQ(s.meshes.size(), 3u);
  ASSERT_EQ(s.instances.size(), 4u);
  EXPECT_EQ(materials(s), (std::vector<int>{0, 0, 2}));
  EXPECT_TRUE(s.meshes[1].variant_materials.empty());  // no mappings: nothing to switch

  apply_variant(s, 0);
  EXPECT_EQ(s.active_variant, 0);
  EXPECT_EQ(materials(s), (std::vector<int>{1, 0, 2}));  // mesh 1's "Green" has no "Blue"
  apply_variant(s, 1);
  EXPECT_EQ(materials(s), (std::vector<int>{2, 0, 1}));
  // Both nodes of the shared mesh draw it, so both change.
  EXPECT_EQ(s.instances[2].mesh, s.instances[3].mesh);
  EXPECT_EQ(s.material_of(s.meshes[std::size_t(s.instances[3].mesh)]).name, "blue");
  apply_variant(s, -1);
  EXPECT_EQ(materials(s), (std::vector<int>{0, 0, 2}));
  EXPECT_THROW(apply_variant(s, 2), Error);

  EXPECT_EQ(variant_mesh_count(s, 0), 1u);
  EXPECT_EQ(variant_mesh_count(s, 1), 2u);
}

TEST(MaterialVariants, FindVariantByNameOrIndexListsTheVariantsOtherwise) {
  VariantsFile f;
  const Scene s = load_scene(f.b.write("variants_find.glb").string());
  EXPECT_EQ(find_variant(s, "Green"), 1);
  EXPECT_EQ(find_variant(s, "0"), 0);
  for (const char* bad : {"Red", "2", "-1", "1x", ""}) {
    SCOPED_TRACE(bad);
    try {
      find_variant(s, bad);
      ADD_FAILURE() << "found";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("the scene's variants are 0 'Blue', 1 'Green'"),
                std::string::npos)
          << e.what();
    }
  }
  const Scene none = load_scene("builtin:spheres");
  EXPECT_THROW(find_variant(none, "0"), Error);
}

TEST(MaterialVariants, AVariantThatSplitsAVolumesShellChangesItsClosure) {
  // A box split into two primitives of one volume material closes as one shell; the
  // variant that gives the front a plain material leaves the back open (thin-walled).
  test::GltfBuilder b;
  b.gltf["materials"] = {{{"extensions",
                           {{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
                            {"KHR_materials_volume", {{"thicknessFactor", 1}}}}}},
                         {{"name", "plain"}}};
  b.gltf["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "open"}}};
  const Mesh box = make_box(glm::vec3(-0.3f, 0.0f, -0.2f), glm::vec3(0.3f, 1.2f, 0.2f));
  json front = b.primitive(box.positions, {box.indices.begin(), box.indices.begin() + 6}, 0);
  front["extensions"] = mappings({{1, {0}}});
  const json back = b.primitive(box.positions, {box.indices.begin() + 6, box.indices.end()}, 0);
  b.node({{"mesh", b.mesh({front, back})}});
  Scene s = load_scene(b.write("variants_closure.glb").string());
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_TRUE(s.meshes[0].closed);
  EXPECT_TRUE(s.meshes[1].closed);
  // One warning, for the back under the variant; none for the file's own materials.
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].rfind("meshes[0].primitives[1]: ", 0), 0u) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("while variant 0 ('open') is active"), std::string::npos)
      << s.warnings[0];

  apply_variant(s, 0);
  EXPECT_EQ(s.meshes[0].material, 1);
  EXPECT_EQ(s.meshes[1].material, 0);  // unmapped: its own material, now open
  EXPECT_FALSE(s.meshes[1].closed);
  apply_variant(s, -1);
  EXPECT_TRUE(s.meshes[1].closed);
}

TEST(MaterialVariants, TheWriterKeepsVariantsAndEachPrimitivesOwnMaterial) {
  VariantsFile f;
  Scene s = load_scene(f.b.write("variants_to_write.glb").string());
  apply_variant(s, 1);  // written as the file had it, whichever variant is on
  const auto path = test::scratch_dir() / "variants_written.glb";
  write_glb(s, path, {.flatten_instances = true});
  EXPECT_EQ(test::validate_gltf(path), "");
  Scene back = load_scene(path.string());
  EXPECT_EQ(back.variants, s.variants);
  ASSERT_EQ(back.meshes.size(), 3u);
  EXPECT_EQ(materials(back), (std::vector<int>{0, 0, 2}));
  for (const int v : {0, 1}) {
    apply_variant(s, v);
    apply_variant(back, v);
    EXPECT_EQ(materials(back), materials(s)) << v;
  }
}

std::string load_error(const std::filesystem::path& path) {
  try {
    load_scene(path.string());
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded";
  return "";
}

TEST(MaterialVariants, BadExtensionJsonIsAnErrorNamingItsPath) {
  struct Case {
    const char* name;
    std::function<void(VariantsFile&)> edit;
    std::string where, what;
  };
  const std::string root = "extensions.KHR_materials_variants";
  const std::string prim = "meshes[0].primitives[0].extensions.KHR_materials_variants";
  const std::vector<Case> cases = {
      {"root_not_object",
       [](VariantsFile& f) { f.b.gltf["extensions"]["KHR_materials_variants"] = 1; }, root,
       "must be an object"},
      {"variants_not_array",
       [](VariantsFile& f) {
         f.b.gltf["extensions"]["KHR_materials_variants"]["variants"] = "Blue";
       },
       root + ".variants", "missing or not an array"},
      {"variant_without_name",
       [](VariantsFile& f) {
         f.b.gltf["extensions"]["KHR_materials_variants"]["variants"][1] = json::object();
       },
       root + ".variants[1].name", "missing or not a string"},
      {"mapping_ext_not_object", [](VariantsFile& f) { f.primitive_ext(0, 0) = json::array(); },
       prim, "must be an object"},
      {"mappings_not_array", [](VariantsFile& f) { f.primitive_ext(0, 0)["mappings"] = 3; },
       prim + ".mappings", "missing or not an array"},
      {"mapping_not_object", [](VariantsFile& f) { f.primitive_ext(0, 0)["mappings"][1] = 3; },
       prim + ".mappings[1]", "must be an object"},
      {"material_out_of_range",
       [](VariantsFile& f) { f.primitive_ext(0, 0)["mappings"][1]["material"] = 7; },
       prim + ".mappings[1].material", "material 7 does not exist (3 materials)"},
      {"material_negative",
       [](VariantsFile& f) { f.primitive_ext(0, 0)["mappings"][0]["material"] = -1; },
       prim + ".mappings[0].material", "not a non-negative integer"},
      {"variants_not_array",
       [](VariantsFile& f) { f.primitive_ext(0, 0)["mappings"][0]["variants"] = 0; },
       prim + ".mappings[0].variants", "missing or not an array"},
      {"variant_out_of_range",
       [](VariantsFile& f) {
         f.primitive_ext(0, 0)["mappings"][1]["variants"] = {1, 2};
       },
       prim + ".mappings[1].variants[1]", "variant 2 does not exist (2 variants"},
      {"variant_not_index",
       [](VariantsFile& f) { f.primitive_ext(0, 0)["mappings"][1]["variants"] = {"Green"}; },
       prim + ".mappings[1].variants[0]", "must be a non-negative integer"},
      {"variant_twice",
       [](VariantsFile& f) { f.primitive_ext(0, 0)["mappings"][1]["variants"] = {0}; },
       prim + ".mappings[1].variants[0]", "variant 0 is mapped more than once"},
      {"no_root_variants",
       [](VariantsFile& f) { f.b.gltf["extensions"].erase("KHR_materials_variants"); },
       prim + ".mappings[0].variants[0]", "variant 0 does not exist (0 variants"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    VariantsFile f;
    c.edit(f);
    const auto path = f.b.write(std::string("variants_bad_") + c.name + ".glb");
    const std::string message = load_error(path);
    EXPECT_EQ(message.rfind(path.string() + ": " + c.where + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(c.what), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace pbrkit
