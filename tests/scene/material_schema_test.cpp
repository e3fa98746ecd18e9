// The material schema (scene/material_schema.h) against the READMEs, and the reader, the
// writer and the loader's checks that iterate it: every factor and texture of every
// extension survives write_glb -> load_scene, defaults are left out of the written JSON,
// out-of-range values are clamped with a warning that names their JSON path, the written
// file passes the Khronos glTF-Validator, and the schema covers every KHR_materials_*
// extension the loader accepts.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "pbrkit/scene/gltf_container.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "scene/gltf_builder.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr float kInf = std::numeric_limits<float>::infinity();

// Silences (and records) loader warnings for the duration of a test.
struct CaptureLog {
  std::vector<std::string> lines;
  LogSink previous;
  CaptureLog() {
    previous = set_log_sink([this](LogLevel, const std::string& m) { lines.push_back(m); });
  }
  ~CaptureLog() { set_log_sink(previous); }
};

// Each factor as its README's "Properties" table and JSON schema give it (KhronosGroup/glTF,
// extensions/2.0/Khronos/<extension>/README.md, schema/*.schema.json): default and valid
// range, typed here from the READMEs, independently of the schema under test. Two ranges
// are the loader's (stricter than the schemas, which bound them below only):
// attenuationColor and diffuseTransmissionColorFactor above 1 would make light.
struct ReadmeFactor {
  const char* extension;
  const char* name;
  int components;
  float fallback;  // the default (each component of a colour)
  float min, max;
};
const ReadmeFactor kReadme[] = {
    {"KHR_materials_emissive_strength", "emissiveStrength", 1, 1.0f, 0.0f, kInf},  // < 0: error
    {"KHR_materials_ior", "ior", 1, 1.5f, 1.0f, kInf},  // and 0, the special case
    {"KHR_materials_specular", "specularFactor", 1, 1.0f, 0.0f, 1.0f},
    {"KHR_materials_specular", "specularColorFactor", 3, 1.0f, 0.0f, kInf},
    {"KHR_materials_clearcoat", "clearcoatFactor", 1, 0.0f, 0.0f, 1.0f},
    {"KHR_materials_clearcoat", "clearcoatRoughnessFactor", 1, 0.0f, 0.0f, 1.0f},
    {"KHR_materials_sheen", "sheenColorFactor", 3, 0.0f, 0.0f, 1.0f},
    {"KHR_materials_sheen", "sheenRoughnessFactor", 1, 0.0f, 0.0f, 1.0f},
    {"KHR_materials_anisotropy", "anisotropyStrength", 1, 0.0f, 0.0f, 1.0f},
    {"KHR_materials_anisotropy", "anisotropyRotation", 1, 0.0f, -kInf, kInf},
    {"KHR_materials_iridescence", "iridescenceFactor", 1, 0.0f, 0.0f, 1.0f},
    {"KHR_materials_iridescence", "iridescenceIor", 1, 1.3f, 1.0f, kInf},
    {"KHR_materials_iridescence", "iridescenceThicknessMinimum", 1, 100.0f, 0.0f, kInf},
    {"KHR_materials_iridescence", "iridescenceThicknessMaximum", 1, 400.0f, 0.0f, kInf},
    {"KHR_materials_transmission", "transmissionFactor", 1, 0.0f, 0.0f, 1.0f},
    {"KHR_materials_volume", "thicknessFactor", 1, 0.0f, 0.0f, kInf},
    {"KHR_materials_volume", "attenuationColor", 3, 1.0f, 0.0f, 1.0f},
    {"KHR_materials_volume", "attenuationDistance", 1, kInf, 0.0f, kInf},  // open at 0
    {"KHR_materials_dispersion", "dispersion", 1, 0.0f, 0.0f, kInf},
    {"KHR_materials_diffuse_transmission", "diffuseTransmissionFactor", 1, 0.0f, 0.0f, 1.0f},
    {"KHR_materials_diffuse_transmission", "diffuseTransmissionColorFactor", 3, 1.0f, 0.0f, 1.0f},
};

// The texture slots whose colour channels the READMEs declare sRGB (every other is linear).
const std::set<TextureSlot> kSrgbSlots = {TextureSlot::kBaseColor, TextureSlot::kEmissive,
                                          TextureSlot::kSpecularColor, TextureSlot::kSheenColor,
                                          TextureSlot::kDiffuseTransmissionColor};

struct Found {
  const MaterialExtension* extension = nullptr;
  const MaterialFactor* factor = nullptr;
};
Found find(const ReadmeFactor& r) {
  Found f;
  f.extension = find_material_extension(r.extension);
  if (f.extension)
    for (const MaterialFactor& factor : f.extension->factors)
      if (std::string(factor.json_name) == r.name) f.factor = &factor;
  return f;
}

TEST(MaterialSchema, DefaultsAndRangesAreTheReadmes) {
  std::size_t factors = 0;
  for (const MaterialExtension& x : material_schema()) factors += x.factors.size();
  EXPECT_EQ(factors, std::size(kReadme));  // no factor of the schema is missing below
  for (const ReadmeFactor& r : kReadme) {
    SCOPED_TRACE(std::string(r.extension) + "." + r.name);
    const Found f = find(r);
    ASSERT_NE(f.factor, nullptr);
    EXPECT_EQ(f.factor->components, r.components);
    EXPECT_EQ(f.factor->min, r.min);
    EXPECT_EQ(f.factor->max, r.max);
    for (int c = 0; c < r.components; ++c)
      EXPECT_EQ(factor_default(*f.extension, *f.factor, c), r.fallback);
  }
}

TEST(MaterialSchema, TextureSlotsAreEachListedOnceWithTheReadmesColourSpace) {
  std::vector<int> seen(std::size_t(kTextureSlotCount), 0);
  for (const MaterialExtension& x : material_schema())
    for (const MaterialTexture& t : x.textures) {
      SCOPED_TRACE(t.json_name);
      ++seen[std::size_t(t.slot)];
      EXPECT_EQ(t.srgb, kSrgbSlots.count(t.slot) == 1);
      // The name Material::textures()' users print is the extension's and the JSON name.
      EXPECT_EQ(texture_slot_name(t.slot), std::string(x.name) + "." + t.json_name);
      // texture_in() is the slot Material::textures() lists.
      Material m;
      x.add(m);
      EXPECT_EQ(&texture_in(m, t.slot), m.textures()[std::size_t(t.slot)]);
      EXPECT_NE(std::string(t.channels), "");
    }
  for (int s = 0; s < kTextureSlotCount; ++s)
    EXPECT_EQ(seen[std::size_t(s)], TextureSlot(s) < kFirstExtensionTextureSlot ? 0 : 1) << s;
  EXPECT_EQ(texture_slot_name(TextureSlot::kBaseColor), "baseColor");
  // A slot of an absent extension cannot be written to.
  Material plain;
  EXPECT_THROW(texture_in(plain, TextureSlot::kSheenColor), Error);
}

TEST(MaterialSchema, CoversEveryMaterialExtensionTheLoaderAccepts) {
  for (const std::string& name : supported_gltf_extensions()) {
    // KHR_materials_variants chooses between materials and adds nothing to one.
    if (name.rfind("KHR_materials_", 0) != 0 || name == "KHR_materials_variants") continue;
    EXPECT_NE(find_material_extension(name), nullptr) << name;
  }
  // The renderers' extensions are the schema less the ones that scale a core value.
  const auto schema = material_schema();
  EXPECT_EQ(std::size_t(std::count_if(schema.begin(), schema.end(),
                                      [](const auto& x) { return !x.scales_core; })),
            material_extensions().size());
  for (const MaterialExtension& x : material_extensions()) EXPECT_FALSE(x.scales_core) << x.name;
  EXPECT_TRUE(find_material_extension("KHR_materials_emissive_strength")->scales_core);
  // And each one the schema lists loads when a file requires it, and is present.
  for (const MaterialExtension& x : material_schema()) {
    SCOPED_TRACE(x.name);
    test::GltfBuilder b;
    json ext = json::object();
    // Neither has an optional: 1.5 and 1 are "absent".
    if (std::string(x.name) == "KHR_materials_ior") ext["ior"] = 1.25;
    if (std::string(x.name) == "KHR_materials_emissive_strength") ext["emissiveStrength"] = 2.5;
    b.gltf["materials"] = {{{"extensions", {{x.name, ext}}}}};
    b.gltf["extensionsUsed"] = {x.name};
    b.gltf["extensionsRequired"] = {x.name};
    b.node({{"mesh", b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, 0)})}});
    CaptureLog log;
    const Scene s = load_scene(b.write(std::string(x.name) + ".glb").string());
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_TRUE(x.present(s.materials[0]));
  }
}

// A value of `r`'s range that is not its default: ranges bounded on both sides give a
// point inside, the others the bound plus a small integer and a half (exact in binary).
float non_default(const ReadmeFactor& r, int c) {
  float v = std::isfinite(r.max)   ? r.min + (r.max - r.min) * (0.375f + 0.125f * float(c))
            : std::isfinite(r.min) ? r.min + 1.5f + float(c)
                                   : -0.75f + float(c);
  if (v == r.fallback) v += 0.25f;
  return v;
}

// 2x2 textures, one per slot, whose texels (0.05 * (slot + 1)) say which slot reads them.
float slot_value(int slot) {
  return 0.05f * float(slot + 1);
}

Scene scene_with_every_value() {
  Scene s;
  s.source = "test";
  Material m;
  m.name = "every_value";
  // A strength needs a factor to scale (the validator warns of one without).
  m.emissive_factor = glm::vec3(0.5f, 0.25f, 1.0f);
  Material unlit;
  unlit.name = "unlit";
  unlit.unlit = true;
  for (const MaterialExtension& x : material_schema()) {
    if (&x != find_material_extension("KHR_materials_unlit")) x.add(m);
    // Unlit excludes the others: the writer must leave them out.
    x.add(unlit);
  }
  for (const ReadmeFactor& r : kReadme) {
    const Found f = find(r);
    for (int c = 0; c < r.components; ++c) f.factor->values(m)[c] = non_default(r, c);
  }
  for (int slot = 0; slot < kTextureSlotCount; ++slot) {
    const bool srgb = kSrgbSlots.count(TextureSlot(slot)) == 1;
    Texture t = Texture::from_linear(Image(2, 2, 4, slot_value(slot)), srgb);
    t.name = texture_slot_name(TextureSlot(slot));
    s.textures.push_back(t);
    TextureRef& ref = texture_in(m, TextureSlot(slot));
    ref.texture = slot;
    if (slot % 2 == 1) ref.transform = TextureTransform{{0.125f, 0.75f}, 0.25f, {4.0f, 0.5f}};
  }
  m.clearcoat->normal_scale = 0.8f;
  s.materials = {m, unlit};
  // A sphere with TANGENT (anisotropy and the normal maps need a tangent space).
  add_mesh_instance(s, make_uv_sphere(0.5f, 8, 4), 0);
  add_mesh_instance(s, make_uv_sphere(0.5f, 8, 4), 1);
  return s;
}

// The JSON chunk of a written GLB.
json written_json(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const GlbChunks chunks = parse_glb(bytes.data(), bytes.size(), path.string());
  return json::parse(chunks.json, chunks.json + chunks.json_size);
}

TEST(MaterialSchema, EveryFactorAndTextureRoundTripsThroughTheWriterAndTheValidator) {
  const Scene original = scene_with_every_value();
  const fs::path path = test::scratch_dir() / "every_value.glb";
  write_glb(original, path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
  CaptureLog log;
  const Scene loaded = load_scene(path.string());
  ASSERT_EQ(loaded.materials.size(), 2u);
  const Material& a = original.materials[0];
  const Material& b = loaded.materials[0];
  for (const MaterialExtension& x : material_schema()) {
    SCOPED_TRACE(x.name);
    EXPECT_EQ(x.present(b), x.present(a));
    EXPECT_EQ(x.present(loaded.materials[1]), std::string(x.name) == "KHR_materials_unlit");
  }
  for (const ReadmeFactor& r : kReadme) {
    SCOPED_TRACE(std::string(r.extension) + "." + r.name);
    const Found f = find(r);
    for (int c = 0; c < r.components; ++c) {
      EXPECT_NE(f.factor->read(b)[c], r.fallback);
      EXPECT_EQ(f.factor->read(b)[c], f.factor->read(a)[c]);
    }
  }
  EXPECT_EQ(b.clearcoat->normal_scale, 0.8f);
  // Each slot reads the texture written for it (its texels say which), in its colour space;
  // 8-bit PNG rounding is well below the 0.05 between two slots' values.
  const auto slots = b.textures();
  for (int slot = 0; slot < kTextureSlotCount; ++slot) {
    SCOPED_TRACE(texture_slot_name(TextureSlot(slot)));
    const TextureRef& ref = *slots[std::size_t(slot)];
    ASSERT_TRUE(ref.valid());
    const Texture& t = loaded.textures[std::size_t(ref.texture)];
    EXPECT_NEAR(t.texel(0, 0, 0).r, slot_value(slot), 0.01f);
    EXPECT_EQ(t.srgb, kSrgbSlots.count(TextureSlot(slot)) == 1);
    EXPECT_EQ(ref.transform.has_value(), slot % 2 == 1);
  }
}

TEST(MaterialSchema, TheWriterLeavesOutEveryDefault) {
  Scene s = scene_with_every_value();
  Material& m = s.materials[0];
  const std::string name = m.name;
  m = Material{};
  m.name = name;
  for (const MaterialExtension& x : material_schema())
    if (std::string(x.name) != "KHR_materials_unlit") x.add(m);
  const fs::path path = test::scratch_dir() / "defaults.glb";
  write_glb(s, path);
  EXPECT_EQ(test::validate_gltf(path), "");
  const json g = written_json(path);
  const json& written = g["materials"][0]["extensions"];
  for (const MaterialExtension& x : material_schema()) {
    SCOPED_TRACE(x.name);
    const std::string n = x.name;
    if (n == "KHR_materials_unlit" || n == "KHR_materials_ior" ||
        n == "KHR_materials_emissive_strength") {
      // Unlit is another material's; an ior of 1.5 and a strength of 1 are the absence of
      // their extensions.
      EXPECT_FALSE(written.contains(n));
      continue;
    }
    ASSERT_TRUE(written.contains(n));
    EXPECT_EQ(written[n], json::object());  // present, every value the default
  }
  // With every value set, every factor and texture is written.
  const fs::path all = test::scratch_dir() / "all.glb";
  write_glb(scene_with_every_value(), all);
  const json every = written_json(all)["materials"][0]["extensions"];
  for (const ReadmeFactor& r : kReadme)
    EXPECT_TRUE(every[r.extension].contains(r.name)) << r.extension << "." << r.name;
  for (const MaterialExtension& x : material_schema())
    for (const MaterialTexture& t : x.textures)
      EXPECT_TRUE(every[x.name].contains(t.json_name)) << x.name << "." << t.json_name;
}

TEST(MaterialSchema, OutOfRangeValuesAreClampedWithAWarningNamingTheJsonPath) {
  for (const ReadmeFactor& r : kReadme) {
    const Found f = find(r);
    const std::string path = std::string("materials[0].extensions.") + r.extension + "." + r.name;
    // Below the minimum and above the maximum, where there is one (a negative strength is
    // refused: the next test).
    for (const float bound : {r.min, r.max}) {
      if (!std::isfinite(bound) || std::string(r.name) == "emissiveStrength") continue;
      const float bad = bound == r.min ? bound - 0.5f : bound + 0.5f;
      SCOPED_TRACE(path + " = " + std::to_string(bad));
      json value = bad;
      if (r.components == 3) value = {r.fallback, bad, r.fallback};
      test::GltfBuilder b;
      b.gltf["materials"] = {{{"extensions", {{r.extension, {{r.name, value}}}}}}};
      b.gltf["extensionsUsed"] = {r.extension};
      b.node({{"mesh", b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, 0)})}});
      CaptureLog log;
      const Scene s = load_scene(b.write("out_of_range.glb").string());
      const auto named = std::find_if(s.warnings.begin(), s.warnings.end(),
                                      [&](const auto& w) { return w.rfind(path + ":", 0) == 0; });
      ASSERT_NE(named, s.warnings.end()) << (s.warnings.empty() ? "" : s.warnings[0]);
      // Clamped to the bound; the two values a range cannot describe fall back instead: an
      // ior below 1 becomes 1, a distance <= 0 means no absorption.
      const float expected = std::string(r.name) == "attenuationDistance" ? kInf : bound;
      EXPECT_EQ(f.factor->read(s.materials[0])[r.components == 3 ? 1 : 0], expected);
    }
    // A value of the wrong type is an error naming the path.
    test::GltfBuilder b;
    b.gltf["materials"] = {{{"extensions", {{r.extension, {{r.name, "x"}}}}}}};
    b.node({{"mesh", b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, 0)})}});
    try {
      CaptureLog log;
      load_scene(b.write("wrong_type.glb").string());
      ADD_FAILURE() << path << ": loaded";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path + ":"), std::string::npos) << e.what();
    }
  }
}

TEST(MaterialSchema, ANegativeEmissiveStrengthIsAnErrorNamingTheJsonPath) {
  test::GltfBuilder b;
  b.gltf["materials"] = {
      {{"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", -2.0}}}}}}};
  b.node({{"mesh", b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, 0)})}});
  try {
    CaptureLog log;
    load_scene(b.write("negative_strength.glb").string());
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength: "
                  "must not be negative"),
              std::string::npos)
        << e.what();
  }
}

// KHR_materials_unlit excludes KHR_materials_emissive_strength as it does the others (the
// validator reports the two together): an unlit material is written without its strength,
// and a file that has both is read with a warning that says so.
TEST(MaterialSchema, UnlitExcludesTheEmissionStrengthToo) {
  Scene s;
  s.source = "test";
  Material m;
  m.name = "glow";
  m.unlit = true;
  m.emissive_factor = glm::vec3(0.5f, 0.25f, 1.0f);
  m.emissive_strength = 6.0f;
  s.materials = {m};
  add_mesh_instance(s, make_uv_sphere(0.5f, 8, 4), 0);
  const fs::path path = test::scratch_dir() / "unlit_glow.glb";
  write_glb(s, path);
  EXPECT_EQ(test::validate_gltf(path), "");
  EXPECT_EQ(written_json(path)["materials"][0]["extensions"],
            json({{"KHR_materials_unlit", json::object()}}));

  test::GltfBuilder b;
  b.gltf["materials"] = {{{"extensions",
                           {{"KHR_materials_unlit", json::object()},
                            {"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}}};
  b.node({{"mesh", b.mesh({b.primitive({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, 0)})}});
  CaptureLog log;
  const Scene both = load_scene(b.write("unlit_and_strength.glb").string());
  ASSERT_EQ(both.materials.size(), 1u);
  EXPECT_EQ(both.materials[0].emissive_strength, 4.0f);  // kept, as the file has it
  ASSERT_EQ(both.warnings.size(), 1u);
  EXPECT_NE(both.warnings[0].find("KHR_materials_unlit must not be combined with "
                                  "KHR_materials_emissive_strength"),
            std::string::npos)
      << both.warnings[0];
}

}  // namespace
}  // namespace pbrkit
