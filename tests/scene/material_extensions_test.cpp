// The KHR_materials_* surface extensions (ior, specular, clearcoat, sheen, anisotropy,
// iridescence, unlit): the loader reads every value of the hand-written
// tests/data/gltf/valid/material_extensions.gltf, applies the READMEs' defaults, and turns
// bad values into errors or clamping warnings that name the JSON path; write_glb writes
// them back so that they load unchanged and pass the Khronos glTF-Validator.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Silences (and records) loader warnings for the duration of a test.
struct CaptureLog {
  std::vector<std::string> lines;
  LogSink previous;
  CaptureLog() {
    previous = set_log_sink([this](LogLevel, const std::string& m) { lines.push_back(m); });
  }
  ~CaptureLog() { set_log_sink(previous); }
};

fs::path fixture() {
  return test::test_data("gltf/valid/material_extensions.gltf");
}

const Material& material(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

// The texture a reference points at was decoded from sRGB (true) or as linear data.
bool srgb(const Scene& s, const TextureRef& ref) {
  EXPECT_TRUE(ref.valid());
  return ref.valid() && s.textures.at(std::size_t(ref.texture)).srgb;
}

// The fixture's transform: offset (0.25, 0.5), rotation 0.5, scale (2, 3).
void expect_fixture_transform(const TextureRef& ref) {
  ASSERT_TRUE(ref.transform.has_value());
  EXPECT_EQ(ref.transform->offset, glm::vec2(0.25f, 0.5f));
  EXPECT_EQ(ref.transform->rotation, 0.5f);
  EXPECT_EQ(ref.transform->scale, glm::vec2(2.0f, 3.0f));
}

TEST(MaterialExtensions, LoaderReadsEveryValueOfTheFixture) {
  const Scene s = load_scene(fixture().string());
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  const Material& m = material(s, "all_extensions");

  EXPECT_FLOAT_EQ(m.ior, 1.45f);

  ASSERT_TRUE(m.specular.has_value());
  EXPECT_FLOAT_EQ(m.specular->factor, 0.7f);
  EXPECT_EQ(m.specular->texture.texcoord, 1);
  expect_fixture_transform(m.specular->texture);
  EXPECT_FALSE(srgb(s, m.specular->texture));
  EXPECT_EQ(m.specular->color_factor, glm::vec3(1.5f, 0.8f, 0.6f));  // above 1 is allowed
  EXPECT_EQ(m.specular->color_texture.texcoord, 0);
  EXPECT_FALSE(m.specular->color_texture.transform.has_value());
  EXPECT_TRUE(srgb(s, m.specular->color_texture));

  ASSERT_TRUE(m.clearcoat.has_value());
  EXPECT_FLOAT_EQ(m.clearcoat->factor, 0.9f);
  EXPECT_EQ(m.clearcoat->texture.texcoord, 1);
  EXPECT_FALSE(srgb(s, m.clearcoat->texture));
  EXPECT_FLOAT_EQ(m.clearcoat->roughness_factor, 0.35f);
  EXPECT_EQ(m.clearcoat->roughness_texture.texcoord, 0);
  expect_fixture_transform(m.clearcoat->roughness_texture);
  EXPECT_FALSE(srgb(s, m.clearcoat->roughness_texture));
  EXPECT_EQ(m.clearcoat->normal_texture.texcoord, 1);
  EXPECT_FALSE(srgb(s, m.clearcoat->normal_texture));
  EXPECT_FLOAT_EQ(m.clearcoat->normal_scale, 0.6f);

  ASSERT_TRUE(m.sheen.has_value());
  EXPECT_EQ(m.sheen->color_factor, glm::vec3(0.2f, 0.4f, 0.6f));
  EXPECT_EQ(m.sheen->color_texture.texcoord, 1);
  EXPECT_TRUE(srgb(s, m.sheen->color_texture));
  EXPECT_FLOAT_EQ(m.sheen->roughness_factor, 0.45f);
  EXPECT_EQ(m.sheen->roughness_texture.texcoord, 0);
  EXPECT_FALSE(srgb(s, m.sheen->roughness_texture));

  ASSERT_TRUE(m.anisotropy.has_value());
  EXPECT_FLOAT_EQ(m.anisotropy->strength, 0.65f);
  EXPECT_FLOAT_EQ(m.anisotropy->rotation, 1.25f);
  EXPECT_EQ(m.anisotropy->texture.texcoord, 1);
  expect_fixture_transform(m.anisotropy->texture);
  EXPECT_FALSE(srgb(s, m.anisotropy->texture));

  ASSERT_TRUE(m.iridescence.has_value());
  EXPECT_FLOAT_EQ(m.iridescence->factor, 0.8f);
  EXPECT_EQ(m.iridescence->texture.texcoord, 0);
  EXPECT_FALSE(srgb(s, m.iridescence->texture));
  EXPECT_FLOAT_EQ(m.iridescence->ior, 1.6f);
  EXPECT_FLOAT_EQ(m.iridescence->thickness_min, 150.0f);
  EXPECT_FLOAT_EQ(m.iridescence->thickness_max, 550.0f);
  EXPECT_EQ(m.iridescence->thickness_texture.texcoord, 1);
  EXPECT_FALSE(srgb(s, m.iridescence->thickness_texture));

  EXPECT_FALSE(m.unlit);
  // One image, used as sRGB colour and as linear data: two decoded textures.
  EXPECT_EQ(s.textures.size(), 2u);

  const Material& unlit = material(s, "unlit");
  EXPECT_TRUE(unlit.unlit);
  EXPECT_EQ(unlit.base_color_factor, glm::vec4(0.2f, 0.6f, 0.9f, 1.0f));
  EXPECT_FALSE(unlit.clearcoat.has_value());
}

// Every value a README gives a default for, as the README gives it.
void expect_readme_defaults(const Material& m) {
  EXPECT_EQ(m.ior, 1.5f);
  ASSERT_TRUE(m.specular.has_value());
  EXPECT_EQ(m.specular->factor, 1.0f);
  EXPECT_EQ(m.specular->color_factor, glm::vec3(1.0f));
  ASSERT_TRUE(m.clearcoat.has_value());
  EXPECT_EQ(m.clearcoat->factor, 0.0f);
  EXPECT_EQ(m.clearcoat->roughness_factor, 0.0f);
  EXPECT_EQ(m.clearcoat->normal_scale, 1.0f);
  ASSERT_TRUE(m.sheen.has_value());
  EXPECT_EQ(m.sheen->color_factor, glm::vec3(0.0f));
  EXPECT_EQ(m.sheen->roughness_factor, 0.0f);
  ASSERT_TRUE(m.anisotropy.has_value());
  EXPECT_EQ(m.anisotropy->strength, 0.0f);
  EXPECT_EQ(m.anisotropy->rotation, 0.0f);
  ASSERT_TRUE(m.iridescence.has_value());
  EXPECT_EQ(m.iridescence->factor, 0.0f);
  EXPECT_EQ(m.iridescence->ior, 1.3f);
  EXPECT_EQ(m.iridescence->thickness_min, 100.0f);
  EXPECT_EQ(m.iridescence->thickness_max, 400.0f);
  for (const TextureRef* ref : m.textures()) EXPECT_FALSE(ref->valid());
  EXPECT_FALSE(m.unlit);
}

TEST(MaterialExtensions, AbsentValuesTakeTheReadmeDefaults) {
  const Scene s = load_scene(fixture().string());
  // Every extension present as an empty object.
  expect_readme_defaults(material(s, "empty_extensions"));
  // No extension at all: none present, ior 1.5.
  const Material& none = material(s, "no_extensions");
  EXPECT_EQ(none.ior, 1.5f);
  EXPECT_FALSE(none.specular || none.clearcoat || none.sheen || none.anisotropy ||
               none.iridescence || none.unlit);
}

TEST(MaterialExtensions, InfoListsNoneAsUnsupported) {
  std::string out;
  ASSERT_EQ(test::run_command(
                test::cli_path().string() + " info --json '" + fixture().string() + "'", &out),
            0)
      << out;
  const json j = json::parse(out.substr(out.find('{')));
  EXPECT_EQ(j["extensions_unsupported"], json::array());
  EXPECT_EQ(j["extensions_used"].size(), 8u);
  EXPECT_EQ(j["warnings"], json::array());
  // Each extension and its values, under the material.
  const json& m = j["material_list"][0];
  EXPECT_EQ(m["name"], "all_extensions");
  EXPECT_NEAR(m["extensions"]["KHR_materials_ior"]["ior"].get<double>(), 1.45, 1e-6);
  EXPECT_NEAR(m["extensions"]["KHR_materials_clearcoat"]["clearcoatFactor"].get<double>(), 0.9,
              1e-6);
  EXPECT_NEAR(
      m["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"]["scale"].get<double>(),
      0.6, 1e-6);
  EXPECT_EQ(m["extensions"]["KHR_materials_anisotropy"]["anisotropyTexture"]["texCoord"], 1);
  EXPECT_NEAR(
      m["extensions"]["KHR_materials_iridescence"]["iridescenceThicknessMaximum"].get<double>(),
      550.0, 1e-6);
  EXPECT_EQ(m["extensions"].size(), 6u);
  EXPECT_EQ(j["material_list"][1]["extensions"], json({{"KHR_materials_unlit", json::object()}}));
  EXPECT_FALSE(j["material_list"][2].contains("extensions"));
}

// The fixture with material 0's extensions replaced by `extensions`, written beside copies
// of its buffer and image.
fs::path variant(const std::string& name, const json& extensions, bool normal_map = true) {
  json g = json::parse(std::ifstream(fixture()));
  g["materials"][0]["extensions"] = extensions;
  if (!normal_map) g["materials"][0].erase("normalTexture");
  const fs::path dir = test::scratch_dir();
  for (const char* file : {"textured_quad.bin", "checker.png"})
    fs::copy_file(test::test_data(std::string("gltf/valid/") + file), dir / file);
  const fs::path path = dir / (name + ".gltf");
  std::ofstream(path) << g.dump(1);
  return path;
}

struct BadCase {
  const char* name;
  json extensions;
  const char* path;  // the JSON path the error must name
  const char* what;  // and a piece of its message
};

TEST(MaterialExtensions, WrongTypesAndNonFiniteValuesAreErrorsNamingTheJsonPath) {
  const json tex = {{"index", 0}};
  const std::vector<BadCase> cases = {
      {"extension_not_object",
       {{"KHR_materials_clearcoat", 3}},
       "materials[0].extensions.KHR_materials_clearcoat",
       "must be an object, not a number"},
      {"unlit_not_object",
       {{"KHR_materials_unlit", "yes"}},
       "materials[0].extensions.KHR_materials_unlit",
       "must be an object, not a string"},
      {"factor_string",
       {{"KHR_materials_clearcoat", {{"clearcoatFactor", "0.5"}}}},
       "materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor",
       "must be a number, not a string"},
      {"factor_array",
       {{"KHR_materials_sheen", {{"sheenRoughnessFactor", {0.5}}}}},
       "materials[0].extensions.KHR_materials_sheen.sheenRoughnessFactor",
       "must be a number, not an array"},
      {"ior_bool",
       {{"KHR_materials_ior", {{"ior", true}}}},
       "materials[0].extensions.KHR_materials_ior.ior",
       "must be a number, not a boolean"},
      {"color_two",
       {{"KHR_materials_sheen", {{"sheenColorFactor", {1, 0.5}}}}},
       "materials[0].extensions.KHR_materials_sheen.sheenColorFactor",
       "must be an array of 3 numbers"},
      {"color_number",
       {{"KHR_materials_specular", {{"specularColorFactor", 1}}}},
       "materials[0].extensions.KHR_materials_specular.specularColorFactor",
       "must be an array of 3 numbers"},
      {"color_element",
       {{"KHR_materials_specular", {{"specularColorFactor", {1, "x", 1}}}}},
       "materials[0].extensions.KHR_materials_specular.specularColorFactor[1]",
       "must be a number"},
      {"strength_overflow",
       {{"KHR_materials_anisotropy", {{"anisotropyStrength", 1e39}}}},
       "materials[0].extensions.KHR_materials_anisotropy.anisotropyStrength",
       "not finite"},
      {"ior_overflow",
       {{"KHR_materials_ior", {{"ior", -1e300}}}},
       "materials[0].extensions.KHR_materials_ior.ior",
       "not finite"},
      {"color_overflow",
       {{"KHR_materials_sheen", {{"sheenColorFactor", {0, 0, 1e39}}}}},
       "materials[0].extensions.KHR_materials_sheen.sheenColorFactor[2]",
       "not finite"},
      {"thickness_overflow",
       {{"KHR_materials_iridescence", {{"iridescenceThicknessMaximum", 1e39}}}},
       "materials[0].extensions.KHR_materials_iridescence.iridescenceThicknessMaximum",
       "not finite"},
      {"texture_number",
       {{"KHR_materials_clearcoat", {{"clearcoatTexture", 5}}}},
       "materials[0].extensions.KHR_materials_clearcoat.clearcoatTexture",
       "must be a textureInfo object"},
      {"texture_no_index",
       {{"KHR_materials_iridescence", {{"iridescenceTexture", json::object()}}}},
       "materials[0].extensions.KHR_materials_iridescence.iridescenceTexture.index",
       "missing or not an integer"},
      {"texture_missing",
       {{"KHR_materials_sheen", {{"sheenColorTexture", {{"index", 9}}}}}},
       "materials[0].extensions.KHR_materials_sheen.sheenColorTexture.index",
       "texture 9 does not exist"},
      {"texcoord_string",
       {{"KHR_materials_specular", {{"specularTexture", {{"index", 0}, {"texCoord", "1"}}}}}},
       "materials[0].extensions.KHR_materials_specular.specularTexture.texCoord",
       "must be an integer"},
      {"normal_scale_string",
       {{"KHR_materials_clearcoat",
         {{"clearcoatNormalTexture", {{"index", 0}, {"scale", "big"}}}}}},
       "materials[0].extensions.KHR_materials_clearcoat.clearcoatNormalTexture.scale",
       "must be a number"},
      {"transform_not_finite",
       {{"KHR_materials_anisotropy",
         {{"anisotropyTexture",
           {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"rotation", 1e39}}}}}}}}}},
       "materials[0].extensions.KHR_materials_anisotropy.anisotropyTexture.extensions."
       "KHR_texture_transform",
       "non-finite"},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path path = variant(c.name, c.extensions);
    try {
      load_scene(path.string());
      ADD_FAILURE() << "loaded";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
      EXPECT_NE(message.find(std::string(c.path) + ":"), std::string::npos) << message;
      EXPECT_NE(message.find(c.what), std::string::npos) << message;
    }
  }
}

struct ClampCase {
  const char* name;
  json extensions;
  const char* path;  // the JSON path the warning must name ("" for no warning)
  std::function<void(const Material&)> check;
};

TEST(MaterialExtensions, OutOfRangeValuesAreClampedWithAWarningNamingTheJsonPath) {
  const std::vector<ClampCase> cases = {
      {"clearcoat_above_1",
       {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.5}}}},
       "materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor",
       [](const Material& m) { EXPECT_EQ(m.clearcoat->factor, 1.0f); }},
      {"clearcoat_roughness_negative",
       {{"KHR_materials_clearcoat", {{"clearcoatRoughnessFactor", -0.5}}}},
       "materials[0].extensions.KHR_materials_clearcoat.clearcoatRoughnessFactor",
       [](const Material& m) { EXPECT_EQ(m.clearcoat->roughness_factor, 0.0f); }},
      {"sheen_roughness_above_1",
       {{"KHR_materials_sheen", {{"sheenRoughnessFactor", 1.25}}}},
       "materials[0].extensions.KHR_materials_sheen.sheenRoughnessFactor",
       [](const Material& m) { EXPECT_EQ(m.sheen->roughness_factor, 1.0f); }},
      {"sheen_color",
       {{"KHR_materials_sheen", {{"sheenColorFactor", {1.5, -1, 0.5}}}}},
       "materials[0].extensions.KHR_materials_sheen.sheenColorFactor",
       [](const Material& m) { EXPECT_EQ(m.sheen->color_factor, glm::vec3(1.0f, 0.0f, 0.5f)); }},
      {"specular_above_1",
       {{"KHR_materials_specular", {{"specularFactor", 2}}}},
       "materials[0].extensions.KHR_materials_specular.specularFactor",
       [](const Material& m) { EXPECT_EQ(m.specular->factor, 1.0f); }},
      {"specular_color_negative",
       {{"KHR_materials_specular", {{"specularColorFactor", {-0.5, 3, 1}}}}},
       "materials[0].extensions.KHR_materials_specular.specularColorFactor",
       [](const Material& m) { EXPECT_EQ(m.specular->color_factor, glm::vec3(0.0f, 3.0f, 1.0f)); }},
      {"anisotropy_negative",
       {{"KHR_materials_anisotropy", {{"anisotropyStrength", -0.2}}}},
       "materials[0].extensions.KHR_materials_anisotropy.anisotropyStrength",
       [](const Material& m) { EXPECT_EQ(m.anisotropy->strength, 0.0f); }},
      {"anisotropy_above_1",
       {{"KHR_materials_anisotropy", {{"anisotropyStrength", 1.3}}}},
       "materials[0].extensions.KHR_materials_anisotropy.anisotropyStrength",
       [](const Material& m) { EXPECT_EQ(m.anisotropy->strength, 1.0f); }},
      {"iridescence_above_1",
       {{"KHR_materials_iridescence", {{"iridescenceFactor", 7}}}},
       "materials[0].extensions.KHR_materials_iridescence.iridescenceFactor",
       [](const Material& m) { EXPECT_EQ(m.iridescence->factor, 1.0f); }},
      {"iridescence_ior_below_1",
       {{"KHR_materials_iridescence", {{"iridescenceIor", 0.9}}}},
       "materials[0].extensions.KHR_materials_iridescence.iridescenceIor",
       [](const Material& m) { EXPECT_EQ(m.iridescence->ior, 1.0f); }},
      {"thickness_negative",
       {{"KHR_materials_iridescence", {{"iridescenceThicknessMinimum", -10}}}},
       "materials[0].extensions.KHR_materials_iridescence.iridescenceThicknessMinimum",
       [](const Material& m) { EXPECT_EQ(m.iridescence->thickness_min, 0.0f); }},
      {"ior_between_0_and_1",
       {{"KHR_materials_ior", {{"ior", 0.5}}}},
       "materials[0].extensions.KHR_materials_ior.ior",
       [](const Material& m) { EXPECT_EQ(m.ior, 1.0f); }},
      {"ior_negative",
       {{"KHR_materials_ior", {{"ior", -2}}}},
       "materials[0].extensions.KHR_materials_ior.ior",
       [](const Material& m) { EXPECT_EQ(m.ior, 1.0f); }},
      {"unlit_with_clearcoat",
       {{"KHR_materials_unlit", json::object()},
        {"KHR_materials_clearcoat", {{"clearcoatFactor", 0.5}}}},
       "materials[0].extensions: KHR_materials_unlit must not be combined with "
       "KHR_materials_clearcoat",
       [](const Material& m) {
         EXPECT_TRUE(m.unlit);
         EXPECT_EQ(m.clearcoat->factor, 0.5f);
       }},
      // Allowed values that look odd: no warning.
      {"ior_zero",
       {{"KHR_materials_ior", {{"ior", 0}}}},
       "",
       [](const Material& m) { EXPECT_EQ(m.ior, 0.0f); }},  // the specular-glossiness mode
      {"ior_one",
       {{"KHR_materials_ior", {{"ior", 1}}}},
       "",
       [](const Material& m) { EXPECT_EQ(m.ior, 1.0f); }},
      {"thickness_min_above_max",
       {{"KHR_materials_iridescence",
         {{"iridescenceThicknessMinimum", 500}, {"iridescenceThicknessMaximum", 200}}}},
       "",
       [](const Material& m) {
         EXPECT_EQ(m.iridescence->thickness_min, 500.0f);
         EXPECT_EQ(m.iridescence->thickness_max, 200.0f);
       }},
      {"rotation_large",
       {{"KHR_materials_anisotropy", {{"anisotropyRotation", -7.5}}}},
       "",
       [](const Material& m) { EXPECT_EQ(m.anisotropy->rotation, -7.5f); }},
  };
  for (const ClampCase& c : cases) {
    SCOPED_TRACE(c.name);
    CaptureLog log;
    const Scene s = load_scene(variant(c.name, c.extensions).string());
    const Material& m = material(s, "all_extensions");
    if (std::string(c.path).empty()) {
      EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    } else {
      ASSERT_EQ(s.warnings.size(), 1u);
      EXPECT_EQ(s.warnings[0].rfind(c.path, 0), 0u) << s.warnings[0];
      EXPECT_EQ(log.lines.size(), 1u);
    }
    c.check(m);
  }
}

TEST(MaterialExtensions, AnisotropyWithoutTangentsGetsGeneratedTangents) {
  // The README: a primitive without TANGENT gets its tangents computed as for a normal map.
  const Scene with = load_scene(
      variant("anisotropy", {{"KHR_materials_anisotropy", {{"anisotropyStrength", 0.5}}}}, false)
          .string());
  const Scene without =
      load_scene(variant("plain", {{"KHR_materials_ior", {{"ior", 1.4}}}}, false).string());
  ASSERT_FALSE(with.meshes.empty());
  EXPECT_EQ(with.meshes[0].tangents.size(), with.meshes[0].positions.size());
  EXPECT_TRUE(without.meshes[0].tangents.empty());
}

// A scene whose first material uses six extensions with textures (texCoord 1 and
// transforms), and whose second is unlit (the READMEs exclude unlit with the others).
Scene scene_with_every_extension() {
  Scene s;
  s.source = "test";
  Image img(2, 2, 4, 1.0f);
  img.pixel(1, 0)[0] = 0.0f;
  Texture color = Texture::from_linear(img, true);
  color.name = "color";
  Texture data = color;
  data.name = "data";
  data.srgb = false;
  s.textures = {color, data};
  auto ref = [](int texture, int texcoord, bool transformed) {
    TextureRef r;
    r.texture = texture;
    r.texcoord = texcoord;
    if (transformed) r.transform = TextureTransform{{0.125f, 0.75f}, 0.25f, {4.0f, 0.5f}};
    return r;
  };
  Material m;
  m.name = "six";
  m.base_color_factor = {0.5f, 0.4f, 0.3f, 1.0f};
  m.metallic_factor = 0.25f;
  m.roughness_factor = 0.6f;
  // The validator wants the normal map on the texCoord of the clearcoat normal and
  // anisotropy textures (they share its tangent space).
  m.normal_texture = ref(1, 1, false);
  m.ior = 1.7f;
  m.specular = SpecularExtension{0.3f, ref(1, 1, true), {1.25f, 0.5f, 0.75f}, ref(0, 0, false)};
  m.clearcoat =
      ClearcoatExtension{0.6f, ref(1, 0, true), 0.15f, ref(1, 1, false), ref(1, 1, true), 0.8f};
  m.sheen = SheenExtension{{0.3f, 0.2f, 0.1f}, ref(0, 1, true), 0.55f, ref(1, 0, false)};
  m.anisotropy = AnisotropyExtension{0.4f, -0.75f, ref(1, 1, true)};
  m.iridescence =
      IridescenceExtension{0.7f, ref(1, 0, false), 1.45f, 250.0f, 120.0f, ref(1, 1, true)};
  s.materials.push_back(m);
  Material unlit;
  unlit.name = "unlit";
  unlit.base_color_factor = {0.1f, 0.9f, 0.2f, 1.0f};
  unlit.base_color_texture = ref(0, 1, true);
  unlit.unlit = true;
  s.materials.push_back(unlit);
  // A light-weight sphere (with TANGENT: anisotropy needs a tangent space) per material.
  Mesh sphere = make_uv_sphere(0.5f, 8, 4);
  sphere.texcoords1 = sphere.texcoords0;
  add_mesh_instance(s, sphere, 0);
  add_mesh_instance(s, sphere, 1, glm::translate(glm::mat4(1.0f), {2.0f, 0.0f, 0.0f}));
  return s;
}

void expect_same_ref(const Scene& a_scene, const TextureRef& a, const Scene& b_scene,
                     const TextureRef& b, const char* slot) {
  SCOPED_TRACE(slot);
  ASSERT_EQ(a.valid(), b.valid());
  if (!a.valid()) return;
  EXPECT_EQ(a.texcoord, b.texcoord);
  // Same colour space (the loader decodes a source once per colour space).
  EXPECT_EQ(a_scene.textures[std::size_t(a.texture)].srgb,
            b_scene.textures[std::size_t(b.texture)].srgb);
  ASSERT_EQ(a.transform.has_value(), b.transform.has_value());
  if (a.transform) {
    EXPECT_EQ(a.transform->offset, b.transform->offset);
    EXPECT_EQ(a.transform->rotation, b.transform->rotation);
    EXPECT_EQ(a.transform->scale, b.transform->scale);
  }
}

TEST(MaterialExtensions, WriteLoadRoundTripKeepsEveryValueAndPassesTheValidator) {
  const Scene original = scene_with_every_extension();
  const fs::path path = test::scratch_dir() / "extensions.glb";
  write_glb(original, path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
  CaptureLog log;
  const Scene loaded = load_scene(path.string());
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  std::vector<std::string> used = loaded.extensions_used;
  std::sort(used.begin(), used.end());
  EXPECT_EQ(used, (std::vector<std::string>{"KHR_materials_anisotropy", "KHR_materials_clearcoat",
                                            "KHR_materials_ior", "KHR_materials_iridescence",
                                            "KHR_materials_sheen", "KHR_materials_specular",
                                            "KHR_materials_unlit", "KHR_texture_transform"}));
  ASSERT_EQ(loaded.materials.size(), 2u);

  const Material& a = original.materials[0];
  const Material& b = loaded.materials[0];
  EXPECT_EQ(b.ior, 1.7f);
  ASSERT_TRUE(b.specular && b.clearcoat && b.sheen && b.anisotropy && b.iridescence);
  EXPECT_EQ(b.specular->factor, 0.3f);
  EXPECT_EQ(b.specular->color_factor, glm::vec3(1.25f, 0.5f, 0.75f));
  EXPECT_EQ(b.clearcoat->factor, 0.6f);
  EXPECT_EQ(b.clearcoat->roughness_factor, 0.15f);
  EXPECT_EQ(b.clearcoat->normal_scale, 0.8f);
  EXPECT_EQ(b.sheen->color_factor, glm::vec3(0.3f, 0.2f, 0.1f));
  EXPECT_EQ(b.sheen->roughness_factor, 0.55f);
  EXPECT_EQ(b.anisotropy->strength, 0.4f);
  EXPECT_EQ(b.anisotropy->rotation, -0.75f);
  EXPECT_EQ(b.iridescence->factor, 0.7f);
  EXPECT_EQ(b.iridescence->ior, 1.45f);
  EXPECT_EQ(b.iridescence->thickness_min, 250.0f);
  EXPECT_EQ(b.iridescence->thickness_max, 120.0f);
  EXPECT_FALSE(b.unlit);
  const auto ta = a.textures(), tb = b.textures();
  for (std::size_t i = 0; i < ta.size(); ++i)
    expect_same_ref(original, *ta[i], loaded, *tb[i], texture_slot_name(TextureSlot(i)).c_str());

  const Material& u = loaded.materials[1];
  EXPECT_TRUE(u.unlit);
  EXPECT_EQ(u.base_color_factor, glm::vec4(0.1f, 0.9f, 0.2f, 1.0f));
  expect_same_ref(original, original.materials[1].base_color_texture, loaded, u.base_color_texture,
                  "unlit baseColor");
  EXPECT_FALSE(u.specular || u.clearcoat || u.sheen || u.anisotropy || u.iridescence);
  EXPECT_EQ(u.ior, 1.5f);
}

TEST(MaterialExtensions, WriterLeavesOutAbsentExtensionsAndDefaults) {
  Scene s = scene_with_every_extension();
  s.materials[0] = Material{};
  s.materials[0].name = "plain";
  s.materials[0].clearcoat = ClearcoatExtension{};  // present, every value the default
  const fs::path path = test::scratch_dir() / "plain.glb";
  write_glb(s, path);
  EXPECT_EQ(test::validate_gltf(path), "");
  const Scene loaded = load_scene(path.string());
  EXPECT_TRUE(loaded.materials[0].clearcoat.has_value());
  EXPECT_FALSE(loaded.materials[0].sheen.has_value());
  EXPECT_EQ(loaded.materials[0].ior, 1.5f);
  std::vector<std::string> used = loaded.extensions_used;
  std::sort(used.begin(), used.end());
  EXPECT_EQ(used, (std::vector<std::string>{"KHR_materials_clearcoat", "KHR_materials_unlit",
                                            "KHR_texture_transform"}));
}

}  // namespace
}  // namespace pbrkit
