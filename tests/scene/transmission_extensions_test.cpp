// The transmission extensions (KHR_materials_transmission, volume, dispersion,
// diffuse_transmission): the loader reads every value of the hand-written
// tests/data/gltf/valid/transmission_extensions.gltf (a tetrahedron of 12 split vertices,
// closed once welded, and the open textured quad), applies the READMEs' defaults, turns
// bad values into errors or warnings that name the file and the JSON path, checks that a
// volume's mesh is closed; write_glb writes them back so that they load unchanged and
// pass the Khronos glTF-Validator; `pbrkit info` lists them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/mesh_closure.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr float kInf = std::numeric_limits<float>::infinity();

struct CaptureLog {
  std::vector<std::string> lines;
  LogSink previous;
  CaptureLog() {
    previous = set_log_sink([this](LogLevel, const std::string& m) { lines.push_back(m); });
  }
  ~CaptureLog() { set_log_sink(previous); }
};

// The fixture's four primitives are two shapes with two materials each, so their faces
// coincide by construction and load_scene warns about that (scene/coincident_faces.h);
// these tests are about the extensions' warnings and leave those aside.
bool coincident_faces_warning(const std::string& w) {
  return w.find("share a plane and an area") != std::string::npos ||
         w.find("shares a plane and an area") != std::string::npos;
}
std::vector<std::string> extension_warnings(const std::vector<std::string>& all) {
  std::vector<std::string> out;
  for (const std::string& w : all)
    if (!coincident_faces_warning(w)) out.push_back(w);
  return out;
}

fs::path fixture() {
  return test::test_data("gltf/valid/transmission_extensions.gltf");
}

const Material& material(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

const Mesh& mesh_with(const Scene& s, const std::string& material_name) {
  for (const Mesh& m : s.meshes)
    if (s.material_of(m).name == material_name) return m;
  throw std::runtime_error("no mesh with " + material_name);
}

bool srgb(const Scene& s, const TextureRef& ref) {
  EXPECT_TRUE(ref.valid());
  return ref.valid() && s.textures.at(std::size_t(ref.texture)).srgb;
}

void expect_fixture_transform(const TextureRef& ref) {
  ASSERT_TRUE(ref.transform.has_value());
  EXPECT_EQ(ref.transform->offset, glm::vec2(0.25f, 0.5f));
  EXPECT_EQ(ref.transform->rotation, 0.5f);
  EXPECT_EQ(ref.transform->scale, glm::vec2(2.0f, 3.0f));
}

TEST(TransmissionExtensions, LoaderReadsEveryValueOfTheFixture) {
  const Scene s = load_scene(fixture().string());
  EXPECT_TRUE(extension_warnings(s.warnings).empty()) << extension_warnings(s.warnings).front();
  const Material& m = material(s, "all_extensions");
  EXPECT_FLOAT_EQ(m.ior, 1.33f);

  ASSERT_TRUE(m.transmission.has_value());
  EXPECT_FLOAT_EQ(m.transmission->factor, 0.8f);
  EXPECT_EQ(m.transmission->texture.texcoord, 1);
  expect_fixture_transform(m.transmission->texture);
  EXPECT_FALSE(srgb(s, m.transmission->texture));

  ASSERT_TRUE(m.volume.has_value());
  EXPECT_FLOAT_EQ(m.volume->thickness_factor, 0.5f);
  EXPECT_EQ(m.volume->thickness_texture.texcoord, 0);
  expect_fixture_transform(m.volume->thickness_texture);
  EXPECT_FALSE(srgb(s, m.volume->thickness_texture));
  EXPECT_FLOAT_EQ(m.volume->attenuation_distance, 0.25f);
  EXPECT_EQ(m.volume->attenuation_color, glm::vec3(0.9f, 0.5f, 0.2f));

  ASSERT_TRUE(m.dispersion.has_value());
  EXPECT_FLOAT_EQ(m.dispersion->dispersion, 0.4f);

  ASSERT_TRUE(m.diffuse_transmission.has_value());
  EXPECT_FLOAT_EQ(m.diffuse_transmission->factor, 0.3f);
  EXPECT_EQ(m.diffuse_transmission->texture.texcoord, 1);
  EXPECT_FALSE(m.diffuse_transmission->texture.transform.has_value());
  EXPECT_FALSE(srgb(s, m.diffuse_transmission->texture));
  EXPECT_EQ(m.diffuse_transmission->color_factor, glm::vec3(0.2f, 0.7f, 0.9f));
  EXPECT_EQ(m.diffuse_transmission->color_texture.texcoord, 0);
  expect_fixture_transform(m.diffuse_transmission->color_texture);
  EXPECT_TRUE(srgb(s, m.diffuse_transmission->color_texture));  // the one colour texture

  // The slots Material::textures() lists (what GL binds and info prints).
  const auto slots = m.textures();
  EXPECT_EQ(slots[std::size_t(TextureSlot::kTransmission)], &m.transmission->texture);
  EXPECT_EQ(slots[std::size_t(TextureSlot::kThickness)], &m.volume->thickness_texture);
  EXPECT_EQ(slots[std::size_t(TextureSlot::kDiffuseTransmission)],
            &m.diffuse_transmission->texture);
  EXPECT_EQ(slots[std::size_t(TextureSlot::kDiffuseTransmissionColor)],
            &m.diffuse_transmission->color_texture);

  // The tetrahedron (12 split vertices) is closed once its positions are welded.
  EXPECT_TRUE(mesh_with(s, "all_extensions").closed);
  EXPECT_EQ(mesh_with(s, "all_extensions").positions.size(), 12u);
  // thicknessFactor 0: thin-walled, on an open quad, doubleSided: no warning.
  const Material& thin = material(s, "thin_walled");
  ASSERT_TRUE(thin.volume.has_value());
  EXPECT_EQ(thin.volume->thickness_factor, 0.0f);
  EXPECT_TRUE(thin.double_sided);
}

TEST(TransmissionExtensions, AbsentValuesTakeTheReadmeDefaults) {
  const Scene s = load_scene(fixture().string());
  const Material& m = material(s, "empty_extensions");
  ASSERT_TRUE(m.transmission && m.volume && m.dispersion && m.diffuse_transmission);
  EXPECT_EQ(m.transmission->factor, 0.0f);          // transmission README, Properties
  EXPECT_EQ(m.volume->thickness_factor, 0.0f);      // volume README, Properties
  EXPECT_EQ(m.volume->attenuation_distance, kInf);  // "default: +Infinity"
  EXPECT_EQ(m.volume->attenuation_color, glm::vec3(1.0f));
  EXPECT_EQ(m.dispersion->dispersion, 0.0f);        // dispersion README
  EXPECT_EQ(m.diffuse_transmission->factor, 0.0f);  // diffuse_transmission schema
  EXPECT_EQ(m.diffuse_transmission->color_factor, glm::vec3(1.0f));
  for (const TextureRef* ref : m.textures()) EXPECT_FALSE(ref->valid());
  const Material& none = material(s, "no_extensions");
  EXPECT_FALSE(none.transmission || none.volume || none.dispersion || none.diffuse_transmission);
  // Only volume meshes are checked; the others keep the default.
  EXPECT_TRUE(mesh_with(s, "no_extensions").closed);
}

TEST(TransmissionExtensions, InfoShowsThemAndListsNoneAsUnsupported) {
  std::string out;
  ASSERT_EQ(test::run_command(
                test::cli_path().string() + " info --json '" + fixture().string() + "'", &out),
            0)
      << out;
  const json j = json::parse(out.substr(out.find('{')));
  EXPECT_EQ(j["extensions_unsupported"], json::array());
  EXPECT_EQ(j["extensions_used"].size(), 6u);
  EXPECT_EQ(extension_warnings(j["warnings"].get<std::vector<std::string>>()),
            std::vector<std::string>{});
  const json& e = j["material_list"][0]["extensions"];
  EXPECT_NEAR(e["KHR_materials_transmission"]["transmissionFactor"].get<double>(), 0.8, 1e-6);
  EXPECT_EQ(e["KHR_materials_transmission"]["transmissionTexture"]["texCoord"], 1);
  EXPECT_NEAR(e["KHR_materials_volume"]["thicknessFactor"].get<double>(), 0.5, 1e-6);
  EXPECT_NEAR(e["KHR_materials_volume"]["attenuationDistance"].get<double>(), 0.25, 1e-6);
  EXPECT_NEAR(e["KHR_materials_volume"]["attenuationColor"][2].get<double>(), 0.2, 1e-6);
  EXPECT_TRUE(e["KHR_materials_volume"]["thicknessTexture"].contains("KHR_texture_transform"));
  EXPECT_NEAR(e["KHR_materials_dispersion"]["dispersion"].get<double>(), 0.4, 1e-6);
  EXPECT_NEAR(
      e["KHR_materials_diffuse_transmission"]["diffuseTransmissionColorFactor"][1].get<double>(),
      0.7, 1e-6);
  EXPECT_TRUE(e["KHR_materials_diffuse_transmission"].contains("diffuseTransmissionColorTexture"));
  // An absent attenuationDistance (infinity) is null: JSON has no infinity.
  EXPECT_TRUE(
      j["material_list"][1]["extensions"]["KHR_materials_volume"]["attenuationDistance"].is_null());

  ASSERT_EQ(
      test::run_command(test::cli_path().string() + " info '" + fixture().string() + "'", &out), 0);
  EXPECT_NE(out.find("transmission 0.8, volume thickness 0.5 attenuation (0.9, 0.5, 0.2) at 0.25"
                     ", dispersion 0.4 (Abbe 50), diffuse transmission 0.3 (0.2, 0.7, 0.9)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("volume thickness 0 attenuation (1, 1, 1) at inf (thin-walled)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("unsupported (ignored): none"), std::string::npos) << out;
}

// The fixture with material `index`'s extensions replaced by `extensions` (and `edit`
// applied to the whole JSON), written beside copies of its buffer and image.
fs::path variant(const std::string& name, const json& extensions, int index = 0,
                 const std::function<void(json&)>& edit = {}) {
  json g = json::parse(std::ifstream(fixture()));
  g["materials"][std::size_t(index)]["extensions"] = extensions;
  if (edit) edit(g);
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

TEST(TransmissionExtensions, WrongTypesAndNonFiniteValuesAreErrorsNamingTheJsonPath) {
  const std::string m = "materials[0].extensions.";
  const std::vector<BadCase> cases = {
      {"transmission_not_object",
       {{"KHR_materials_transmission", {1}}},
       "materials[0].extensions.KHR_materials_transmission",
       "must be an object, not an array"},
      {"volume_not_object",
       {{"KHR_materials_volume", true}},
       "materials[0].extensions.KHR_materials_volume",
       "must be an object, not a boolean"},
      {"transmission_factor_string",
       {{"KHR_materials_transmission", {{"transmissionFactor", "1"}}}},
       "materials[0].extensions.KHR_materials_transmission.transmissionFactor",
       "must be a number, not a string"},
      {"thickness_overflow",
       {{"KHR_materials_volume", {{"thicknessFactor", 1e39}}}},
       "materials[0].extensions.KHR_materials_volume.thicknessFactor",
       "not finite"},
      {"distance_string",
       {{"KHR_materials_volume", {{"attenuationDistance", "far"}}}},
       "materials[0].extensions.KHR_materials_volume.attenuationDistance",
       "must be a number, not a string"},
      {"distance_overflow",
       {{"KHR_materials_volume", {{"attenuationDistance", -1e300}}}},
       "materials[0].extensions.KHR_materials_volume.attenuationDistance",
       "not finite"},
      {"attenuation_color_two",
       {{"KHR_materials_volume", {{"attenuationColor", {0.5, 0.5}}}}},
       "materials[0].extensions.KHR_materials_volume.attenuationColor",
       "must be an array of 3 numbers, not an array of 2"},
      {"attenuation_color_overflow",
       {{"KHR_materials_volume", {{"attenuationColor", {0.5, 1e39, 0.5}}}}},
       "materials[0].extensions.KHR_materials_volume.attenuationColor[1]",
       "not finite"},
      {"dispersion_bool",
       {{"KHR_materials_dispersion", {{"dispersion", false}}}},
       "materials[0].extensions.KHR_materials_dispersion.dispersion",
       "must be a number, not a boolean"},
      {"diffuse_color_null",
       {{"KHR_materials_diffuse_transmission", {{"diffuseTransmissionColorFactor", nullptr}}}},
       "materials[0].extensions.KHR_materials_diffuse_transmission.diffuseTransmissionColorFactor",
       "must be an array of 3 numbers, not null"},
      {"transmission_texture_number",
       {{"KHR_materials_transmission", {{"transmissionTexture", 0}}}},
       "materials[0].extensions.KHR_materials_transmission.transmissionTexture",
       "must be a textureInfo object, not a number"},
      {"thickness_texture_no_index",
       {{"KHR_materials_volume", {{"thicknessTexture", {{"texCoord", 1}}}}}},
       "materials[0].extensions.KHR_materials_volume.thicknessTexture.index",
       "missing or not an integer"},
      {"diffuse_texture_missing",
       {{"KHR_materials_diffuse_transmission", {{"diffuseTransmissionTexture", {{"index", 4}}}}}},
       "materials[0].extensions.KHR_materials_diffuse_transmission.diffuseTransmissionTexture."
       "index",
       "texture 4 does not exist"},
      {"color_texture_texcoord_string",
       {{"KHR_materials_diffuse_transmission",
         {{"diffuseTransmissionColorTexture", {{"index", 0}, {"texCoord", "0"}}}}}},
       "materials[0].extensions.KHR_materials_diffuse_transmission."
       "diffuseTransmissionColorTexture.texCoord",
       "must be an integer"},
      {"thickness_transform_not_finite",
       {{"KHR_materials_volume",
         {{"thicknessTexture",
           {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0, 1e39}}}}}}}}}}},
       "materials[0].extensions.KHR_materials_volume.thicknessTexture.extensions."
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

TEST(TransmissionExtensions, NanInTheFileIsAnErrorNamingTheFile) {
  // JSON has no NaN; a file that writes one is not JSON.
  const fs::path path =
      variant("nan", {{"KHR_materials_transmission", {{"transmissionFactor", 7}}}});
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const std::size_t at = text.find("\"transmissionFactor\": 7");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 23, "\"transmissionFactor\": NaN");
  std::ofstream(path) << text;
  try {
    load_scene(path.string());
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("invalid JSON"), std::string::npos) << e.what();
  }
}

struct WarnCase {
  const char* name;
  json extensions;
  const char* warning;  // the start of the one warning ("" for none)
  std::function<void(const Material&)> check;
  bool double_sided = false;
};

TEST(TransmissionExtensions, OutOfRangeValuesAndIneffectiveCombinationsAreWarnings) {
  const json transmission = {{"transmissionFactor", 1}};
  const std::vector<WarnCase> cases = {
      {"transmission_above_1",
       {{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}}},
       "materials[0].extensions.KHR_materials_transmission.transmissionFactor: 1.5 is outside",
       [](const Material& m) { EXPECT_EQ(m.transmission->factor, 1.0f); }},
      {"thickness_negative",
       {{"KHR_materials_transmission", transmission},
        {"KHR_materials_volume", {{"thicknessFactor", -0.5}}}},
       "materials[0].extensions.KHR_materials_volume.thicknessFactor: -0.5 is outside",
       [](const Material& m) { EXPECT_EQ(m.volume->thickness_factor, 0.0f); }},
      {"distance_zero",
       {{"KHR_materials_transmission", transmission},
        {"KHR_materials_volume", {{"thicknessFactor", 1}, {"attenuationDistance", 0}}}},
       "materials[0].extensions.KHR_materials_volume.attenuationDistance: 0 is invalid",
       [](const Material& m) { EXPECT_EQ(m.volume->attenuation_distance, kInf); }},
      {"distance_negative",
       {{"KHR_materials_transmission", transmission},
        {"KHR_materials_volume", {{"thicknessFactor", 1}, {"attenuationDistance", -2}}}},
       "materials[0].extensions.KHR_materials_volume.attenuationDistance: -2 is invalid",
       [](const Material& m) { EXPECT_EQ(m.volume->attenuation_distance, kInf); }},
      {"attenuation_color_out_of_range",
       {{"KHR_materials_transmission", transmission},
        {"KHR_materials_volume", {{"thicknessFactor", 1}, {"attenuationColor", {1.5, 0.5, -0.1}}}}},
       "materials[0].extensions.KHR_materials_volume.attenuationColor: (1.5, 0.5, -0.1) is "
       "outside",
       [](const Material& m) {
         EXPECT_EQ(m.volume->attenuation_color, glm::vec3(1.0f, 0.5f, 0.0f));
       }},
      {"dispersion_negative",
       {{"KHR_materials_transmission", transmission},
        {"KHR_materials_volume", {{"thicknessFactor", 1}}},
        {"KHR_materials_dispersion", {{"dispersion", -0.3}}}},
       "materials[0].extensions.KHR_materials_dispersion.dispersion: -0.3 is outside",
       [](const Material& m) { EXPECT_EQ(m.dispersion->dispersion, 0.0f); }},
      {"diffuse_factor_above_1",
       {{"KHR_materials_diffuse_transmission", {{"diffuseTransmissionFactor", 2}}}},
       "materials[0].extensions.KHR_materials_diffuse_transmission.diffuseTransmissionFactor: 2 "
       "is outside",
       [](const Material& m) { EXPECT_EQ(m.diffuse_transmission->factor, 1.0f); }},
      {"diffuse_color_above_1",
       {{"KHR_materials_diffuse_transmission", {{"diffuseTransmissionColorFactor", {2, 1, 0.5}}}}},
       "materials[0].extensions.KHR_materials_diffuse_transmission.diffuseTransmissionColorFactor"
       ": (2, 1, 0.5) is outside",
       [](const Material& m) {
         EXPECT_EQ(m.diffuse_transmission->color_factor, glm::vec3(1.0f, 1.0f, 0.5f));
       }},
      {"ior_below_1_with_a_volume",
       {{"KHR_materials_ior", {{"ior", 0.7}}},
        {"KHR_materials_transmission", transmission},
        {"KHR_materials_volume", {{"thicknessFactor", 1}}}},
       "materials[0].extensions.KHR_materials_ior.ior: 0.7 is invalid",
       [](const Material& m) { EXPECT_EQ(m.ior, 1.0f); }},
      {"volume_without_transmission",
       {{"KHR_materials_volume", {{"thicknessFactor", 1}}}},
       "materials[0].extensions.KHR_materials_volume: has no effect without "
       "KHR_materials_transmission",
       [](const Material& m) { EXPECT_EQ(m.volume->thickness_factor, 1.0f); }},
      {"dispersion_without_volume",
       {{"KHR_materials_transmission", transmission},
        {"KHR_materials_dispersion", {{"dispersion", 0.5}}}},
       "materials[0].extensions.KHR_materials_dispersion: has no effect without "
       "KHR_materials_volume",
       [](const Material& m) { EXPECT_EQ(m.dispersion->dispersion, 0.5f); }},
      {"dispersion_thin_walled",
       {{"KHR_materials_transmission", transmission},
        {"KHR_materials_volume", json::object()},
        {"KHR_materials_dispersion", {{"dispersion", 0.5}}}},
       "materials[0].extensions.KHR_materials_dispersion: has no effect",
       [](const Material& m) { EXPECT_EQ(m.dispersion->dispersion, 0.5f); }},
      {"double_sided_volume",
       {{"KHR_materials_transmission", transmission},
        {"KHR_materials_volume", {{"thicknessFactor", 1}}}},
       "materials[0].doubleSided: has no effect on a volume boundary",
       [](const Material& m) { EXPECT_TRUE(m.double_sided); },
       true},
      {"unlit_with_transmission",
       {{"KHR_materials_unlit", json::object()}, {"KHR_materials_transmission", transmission}},
       "materials[0].extensions: KHR_materials_unlit must not be combined with "
       "KHR_materials_transmission",
       [](const Material& m) {
         EXPECT_TRUE(m.unlit);
         EXPECT_EQ(m.transmission->factor, 1.0f);
       }},
      // Allowed values that look odd: no warning.
      {"distance_large",
       {{"KHR_materials_transmission", transmission},
        {"KHR_materials_volume", {{"thicknessFactor", 1}, {"attenuationDistance", 1e30}}}},
       "",
       [](const Material& m) { EXPECT_EQ(m.volume->attenuation_distance, 1e30f); }},
      {"attenuation_color_black",
       {{"KHR_materials_transmission", transmission},
        {"KHR_materials_volume",
         {{"thicknessFactor", 1}, {"attenuationDistance", 1}, {"attenuationColor", {0, 0, 0}}}}},
       "",
       [](const Material& m) { EXPECT_EQ(m.volume->attenuation_color, glm::vec3(0.0f)); }},
      {"volume_with_diffuse_transmission_only",
       {{"KHR_materials_diffuse_transmission", {{"diffuseTransmissionFactor", 1}}},
        {"KHR_materials_volume", {{"thicknessFactor", 1}}}},
       "",
       [](const Material& m) { EXPECT_TRUE(m.volume.has_value()); }},
      {"dispersion_zero_without_volume",
       {{"KHR_materials_dispersion", json::object()}},
       "",
       [](const Material& m) { EXPECT_EQ(m.dispersion->dispersion, 0.0f); }},
      {"double_sided_thin_walled",
       {{"KHR_materials_transmission", transmission}, {"KHR_materials_volume", json::object()}},
       "",
       [](const Material& m) { EXPECT_TRUE(m.double_sided); },
       true},
  };
  for (const WarnCase& c : cases) {
    SCOPED_TRACE(c.name);
    CaptureLog log;
    const fs::path path = variant(c.name, c.extensions, 0, [&](json& g) {
      if (c.double_sided) g["materials"][0]["doubleSided"] = true;
    });
    const Scene s = load_scene(path.string());
    const Material& m = material(s, "all_extensions");
    const std::vector<std::string> warnings = extension_warnings(s.warnings);
    const std::vector<std::string> lines = extension_warnings(log.lines);
    if (std::string(c.warning).empty()) {
      EXPECT_TRUE(warnings.empty()) << warnings.front();
    } else {
      ASSERT_EQ(warnings.size(), 1u) << warnings.front();
      EXPECT_EQ(warnings[0].rfind(c.warning, 0), 0u) << warnings[0];
      ASSERT_EQ(lines.size(), 1u);
      EXPECT_EQ(lines[0], path.string() + ": " + warnings[0]);  // names the file
    }
    c.check(m);
  }
}

TEST(TransmissionExtensions, AVolumeOnAnOpenMeshIsAWarningAndRenderedThinWalled) {
  // all_extensions (thicknessFactor 0.5) on the open quad (primitive 2) as well.
  CaptureLog log;
  const fs::path path =
      variant("open", json::parse(std::ifstream(fixture()))["materials"][0]["extensions"], 0,
              [](json& g) { g["meshes"][0]["primitives"][2]["material"] = 0; });
  const Scene s = load_scene(path.string());
  const std::vector<std::string> warnings = extension_warnings(s.warnings);
  const std::vector<std::string> lines = extension_warnings(log.lines);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "meshes[0].primitives[2]: the material (materials[0]) has KHR_materials_volume, but "
            "the primitive is not closed, alone or with the mesh's other primitives of that "
            "material (4 edges not shared by exactly two triangles); it is rendered thin-walled");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].rfind(path.string() + ": meshes[0].primitives[2]", 0), 0u) << lines[0];
  int closed = 0, open = 0;
  for (const Mesh& mesh : s.meshes)
    if (mesh.material == 0) (mesh.closed ? closed : open)++;
  EXPECT_EQ(closed, 1);  // the tetrahedron
  EXPECT_EQ(open, 1);    // the quad
}

// count_edges on meshes whose closure is known by construction.
Mesh triangles(std::vector<glm::vec3> positions, std::vector<std::uint32_t> indices) {
  Mesh m;
  m.positions = std::move(positions);
  m.indices = std::move(indices);
  return m;
}

TEST(MeshClosure, ClosedMeshesHaveNoUnpairedEdges) {
  // A tetrahedron, indexed (4 vertices) and split (12 vertices, welded by position).
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<std::uint32_t> faces = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  const EdgeCount indexed = count_edges(triangles(p, faces));
  EXPECT_EQ(indexed.triangles, 4u);
  EXPECT_EQ(indexed.unpaired, 0u);
  EXPECT_TRUE(indexed.closed());
  std::vector<glm::vec3> split;
  std::vector<std::uint32_t> order;
  for (const std::uint32_t i : faces) {
    order.push_back(std::uint32_t(split.size()));
    split.push_back(p[i]);
  }
  EXPECT_TRUE(count_edges(triangles(split, order)).closed());
  // -0 and +0 are one position.
  split[0] = glm::vec3(-0.0f, 0.0f, -0.0f);
  EXPECT_TRUE(count_edges(triangles(split, order)).closed());
  // The procedural meshes the built-in scenes use for volumes (seams and poles welded).
  EXPECT_TRUE(count_edges(make_uv_sphere(0.4f, 64, 32)).closed());
  EXPECT_TRUE(count_edges(make_uv_sphere(1.0f, 7, 3)).closed());
  EXPECT_TRUE(count_edges(make_box({-0.3f, 0.0f, -0.3f}, {0.3f, 1.2f, 0.3f})).closed());
}

TEST(MeshClosure, OpenMeshesCountTheirUnpairedEdges) {
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  // The tetrahedron without its last face: the 3 edges of the hole.
  EXPECT_EQ(count_edges(triangles(p, {0, 2, 1, 0, 1, 3, 0, 3, 2})).unpaired, 3u);
  // A quad: its 4 boundary edges (the diagonal is shared).
  EXPECT_EQ(count_edges(make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0})).unpaired, 4u);
  // A third triangle on an edge of the closed tetrahedron: that edge has 3 (non-manifold),
  // and the new triangle's two other edges have 1.
  const EdgeCount fin = count_edges(triangles(p, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 1, 2, 4}));
  EXPECT_EQ(fin.unpaired, 3u);
  EXPECT_FALSE(fin.closed());
  // A degenerate triangle (two corners at one position) is skipped, not counted.
  const EdgeCount degenerate =
      count_edges(triangles(p, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 0, 4}));
  EXPECT_EQ(degenerate.triangles, 4u);
  EXPECT_TRUE(degenerate.closed());
  // No triangles at all is not a closed mesh.
  EXPECT_FALSE(count_edges(triangles(p, {0, 0, 1})).closed());
  EXPECT_FALSE(count_edges(Mesh{}).closed());
}

// A scene with the four extensions and textures (texCoord 1, transforms) on a closed
// sphere, plus a thin-walled diffuse-transmission sheet with an infinite distance.
Scene scene_with_transmission() {
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
  Material glass;
  glass.name = "glass";
  glass.metallic_factor = 0.0f;
  glass.roughness_factor = 0.2f;
  glass.ior = 1.6f;
  glass.transmission = TransmissionExtension{0.9f, ref(1, 1, true)};
  glass.volume = VolumeExtension{0.8f, ref(1, 0, true), 0.35f, {0.8f, 0.4f, 0.1f}};
  glass.dispersion = DispersionExtension{0.625f};
  glass.diffuse_transmission =
      DiffuseTransmissionExtension{0.2f, ref(1, 1, false), {0.5f, 0.25f, 0.75f}, ref(0, 0, true)};
  s.materials.push_back(glass);
  Material sheet;
  sheet.name = "sheet";
  sheet.double_sided = true;
  sheet.diffuse_transmission = DiffuseTransmissionExtension{};
  sheet.diffuse_transmission->factor = 0.7f;
  sheet.transmission = TransmissionExtension{1.0f, {}};
  sheet.volume = VolumeExtension{};  // thin-walled; the distance stays +inf
  s.materials.push_back(sheet);
  Mesh sphere = make_uv_sphere(0.5f, 8, 4);
  sphere.texcoords1 = sphere.texcoords0;
  add_mesh_instance(s, sphere, 0);
  add_mesh_instance(s, make_quad({1, 0, 0}, {1, 0, 0}, {0, 1, 0}), 1);
  return s;
}

void expect_same_ref(const Scene& a_scene, const TextureRef& a, const Scene& b_scene,
                     const TextureRef& b, const char* slot) {
  SCOPED_TRACE(slot);
  ASSERT_EQ(a.valid(), b.valid());
  if (!a.valid()) return;
  EXPECT_EQ(a.texcoord, b.texcoord);
  EXPECT_EQ(a_scene.textures[std::size_t(a.texture)].srgb,
            b_scene.textures[std::size_t(b.texture)].srgb);
  ASSERT_EQ(a.transform.has_value(), b.transform.has_value());
  if (a.transform) {
    EXPECT_EQ(a.transform->offset, b.transform->offset);
    EXPECT_EQ(a.transform->rotation, b.transform->rotation);
    EXPECT_EQ(a.transform->scale, b.transform->scale);
  }
}

TEST(TransmissionExtensions, WriteLoadRoundTripKeepsEveryValueAndPassesTheValidator) {
  const Scene original = scene_with_transmission();
  const fs::path path = test::scratch_dir() / "transmission.glb";
  write_glb(original, path);
  // The validator knows transmission, volume and dispersion; diffuse_transmission is newer
  // than it (an UNSUPPORTED_EXTENSION info, which does not fail).
  EXPECT_EQ(test::validate_gltf(path), "");
  CaptureLog log;
  const Scene loaded = load_scene(path.string());
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  std::vector<std::string> used = loaded.extensions_used;
  std::sort(used.begin(), used.end());
  EXPECT_EQ(used, (std::vector<std::string>{"KHR_materials_diffuse_transmission",
                                            "KHR_materials_dispersion", "KHR_materials_ior",
                                            "KHR_materials_transmission", "KHR_materials_volume",
                                            "KHR_texture_transform"}));
  ASSERT_EQ(loaded.materials.size(), 2u);
  const Material& b = loaded.materials[0];
  ASSERT_TRUE(b.transmission && b.volume && b.dispersion && b.diffuse_transmission);
  EXPECT_EQ(b.ior, 1.6f);
  EXPECT_EQ(b.transmission->factor, 0.9f);
  EXPECT_EQ(b.volume->thickness_factor, 0.8f);
  EXPECT_EQ(b.volume->attenuation_distance, 0.35f);
  EXPECT_EQ(b.volume->attenuation_color, glm::vec3(0.8f, 0.4f, 0.1f));
  EXPECT_EQ(b.dispersion->dispersion, 0.625f);
  EXPECT_EQ(b.diffuse_transmission->factor, 0.2f);
  EXPECT_EQ(b.diffuse_transmission->color_factor, glm::vec3(0.5f, 0.25f, 0.75f));
  const auto ta = original.materials[0].textures(), tb = b.textures();
  for (std::size_t i = 0; i < ta.size(); ++i)
    expect_same_ref(original, *ta[i], loaded, *tb[i], texture_slot_name(TextureSlot(i)).c_str());
  // The sphere is closed once loaded (its seam and poles weld).
  EXPECT_TRUE(loaded.meshes[0].closed);

  const Material& sheet = loaded.materials[1];
  ASSERT_TRUE(sheet.volume && sheet.transmission && sheet.diffuse_transmission);
  EXPECT_EQ(sheet.volume->thickness_factor, 0.0f);
  EXPECT_EQ(sheet.volume->attenuation_distance, kInf);  // left out, read back as the default
  EXPECT_EQ(sheet.diffuse_transmission->factor, 0.7f);
  EXPECT_EQ(sheet.diffuse_transmission->color_factor, glm::vec3(1.0f));
  EXPECT_TRUE(sheet.double_sided);
}

}  // namespace
}  // namespace pbrkit
