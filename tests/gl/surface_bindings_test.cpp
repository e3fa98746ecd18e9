// The surface program's names for its texture slots, texture units and buffer binding
// points (surface_bindings.h): every slot and unit is named once, with its own number, the
// surface shaders type none of the numbers, and each material texture slot reaches the
// sampler its slot's code reads (a slot wired to another unit samples the white texture
// bound there and renders as if it had no texture).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/gl/shaders.h"
#include "pbrkit/gl/surface_bindings.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::gl {
namespace {

// The value of `macro` as the prelude defines it (-1 when it is not defined).
int defined_value(const std::string& prelude, const std::string& macro) {
  const std::regex line("#define " + macro + " (-?[0-9]+)\n");
  std::smatch m;
  return std::regex_search(prelude, m, line) ? std::stoi(m[1].str()) : -1;
}

TEST(GlSurfaceBindings, ThePreludeNamesEverySlotOnceWithItsIndex) {
  const std::string& prelude = surface_prelude();
  std::set<std::string> names;
  for (int t = 0; t < kTextureSlotCount; ++t) {
    const std::string name = texture_slot_macro(TextureSlot(t));
    EXPECT_TRUE(names.insert(name).second) << name << " names two slots";
    EXPECT_EQ(defined_value(prelude, "SLOT_" + name), t) << name;
    EXPECT_GE(defined_value(prelude, "BINDING_" + name), 0) << name;
  }
  EXPECT_EQ(texture_slot_macro(TextureSlot::kBaseColor), "BASE_COLOR_TEXTURE");
  EXPECT_EQ(texture_slot_macro(TextureSlot::kSheenColor), "SHEEN_COLOR_TEXTURE");
  EXPECT_EQ(texture_slot_macro(TextureSlot::kDiffuseTransmissionColor),
            "DIFFUSE_TRANSMISSION_COLOR_TEXTURE");
}

TEST(GlSurfaceBindings, NoTwoBindingsShareANameOrANumber) {
  std::set<std::string> names;
  std::set<GLuint> units, buffers;
  const std::string& prelude = surface_prelude();
  for (const SurfaceBinding& b : surface_bindings()) {
    EXPECT_TRUE(names.insert(b.name).second) << b.name;
    EXPECT_TRUE((b.buffer ? buffers : units).insert(b.point).second)
        << b.name << " shares " << (b.buffer ? "buffer binding point " : "texture unit ")
        << b.point;
    if (!b.buffer) {
      EXPECT_LE(b.point, kLastSurfaceUnit) << b.name;
    }
    EXPECT_EQ(defined_value(prelude, "BINDING_" + b.name), int(b.point)) << b.name;
  }
}

TEST(GlSurfaceBindings, TheSurfaceShadersTypeNoSlotOrBindingNumber) {
  const std::regex literal_binding(R"(binding\s*=\s*[0-9])");
  const std::regex literal_slot(R"(texcoord\(\s*[0-9]|map_normal\([^,]*,\s*[0-9]|HAS_TEXTURE_)");
  for (const char* file : {"pbr_vertex.glsl", "pbr_fragment.glsl", "back_face_fragment.glsl"}) {
    const std::string text = expand_shader(file);
    EXPECT_FALSE(std::regex_search(text, literal_binding)) << file;
    EXPECT_FALSE(std::regex_search(text, literal_slot)) << file;
  }
}

// Makes `slot`'s extension present in `m` with factors under which the slot's texture
// changes the image (an extension whose defaults switch it off is switched on); false for
// a slot this test does not know, so that a new slot fails until it is added here.
bool use_slot(Material& m, TextureSlot slot) {
  switch (slot) {
    case TextureSlot::kBaseColor:
    case TextureSlot::kMetallicRoughness:
    case TextureSlot::kNormal:
    case TextureSlot::kOcclusion:
      return true;
    case TextureSlot::kEmissive:
      m.emissive_factor = glm::vec3(0.5f);
      return true;
    case TextureSlot::kSpecular:
    case TextureSlot::kSpecularColor:
      m.specular.emplace();
      return true;
    case TextureSlot::kClearcoat:
    case TextureSlot::kClearcoatRoughness:
    case TextureSlot::kClearcoatNormal:
      m.clearcoat.emplace();
      m.clearcoat->factor = 1.0f;
      m.clearcoat->roughness_factor = 0.6f;
      return true;
    case TextureSlot::kSheenColor:
    case TextureSlot::kSheenRoughness:
      m.sheen.emplace();
      m.sheen->color_factor = glm::vec3(1.0f);
      m.sheen->roughness_factor = 0.6f;
      return true;
    case TextureSlot::kAnisotropy:
      m.anisotropy.emplace();
      m.anisotropy->strength = 1.0f;
      return true;
    case TextureSlot::kIridescence:
    case TextureSlot::kIridescenceThickness:
      m.iridescence.emplace();
      m.iridescence->factor = 1.0f;
      return true;
    case TextureSlot::kTransmission:
      m.transmission.emplace();
      m.transmission->factor = 1.0f;
      return true;
    case TextureSlot::kThickness:
      // The refraction measures its own path through the closed mesh; the diffuse
      // transmission's light crosses the thickness (pbr_fragment.glsl), so it shows there.
      m.transmission.emplace();
      m.transmission->factor = 0.5f;
      m.diffuse_transmission.emplace();
      m.diffuse_transmission->factor = 1.0f;
      m.volume.emplace();
      m.volume->thickness_factor = 1.0f;
      m.volume->attenuation_distance = 0.2f;
      m.volume->attenuation_color = glm::vec3(0.1f, 0.5f, 0.9f);
      return true;
    case TextureSlot::kDiffuseTransmission:
    case TextureSlot::kDiffuseTransmissionColor:
      m.diffuse_transmission.emplace();
      m.diffuse_transmission->factor = 1.0f;
      return true;
  }
  return false;
}

TEST(GlSurfaceBindings, EachSlotsTextureChangesTheImage) {
  testing::context();
  // One texel, every channel away from 1 and from the others (a factor times it differs
  // from the factor alone; as a normal or anisotropy direction it tilts, (0.6, -0.4)).
  const Texture texel = Texture::from_unorm8(1, 1, 4, {204, 77, 153, 102}, false);
  const Environment env = Environment::constant(glm::vec3(0.5f));
  const IblMaps maps = testing::small_ibl_maps(env);
  Camera camera;
  camera.type = Camera::Type::kOrthographic;
  camera.xmag = camera.ymag = 1.1f;
  camera.camera_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 5.0f));
  RenderSettings settings;
  settings.msaa = 1;
  constexpr int kSize = 32;
  Light sun;
  sun.type = Light::Type::kDirectional;
  sun.intensity = 3.0f;
  sun.direction = glm::normalize(glm::vec3(0.5f, -0.4f, -1.0f));

  Renderer renderer;
  renderer.set_environment(&env);
  renderer.set_ibl(&maps);
  for (int t = 0; t < kTextureSlotCount; ++t) {
    const TextureSlot slot = TextureSlot(t);
    Material without;
    // A coloured, half-metallic base under both lights, so that every lobe shows.
    without.base_color_factor = glm::vec4(0.9f, 0.5f, 0.2f, 1.0f);
    without.metallic_factor = 0.5f;
    without.roughness_factor = 0.5f;
    ASSERT_TRUE(use_slot(without, slot)) << texture_slot_name(slot) << ": not in this test";
    Material with = without;
    texture_in(with, slot).texture = 0;

    Scene scene;
    scene.source = "test:surface_bindings";
    scene.textures.push_back(texel);
    scene.materials.push_back(with);
    scene.lights.push_back(sun);
    add_mesh_instance(scene, make_uv_sphere(1.0f, 32, 16), 0);
    renderer.set_scene(scene);
    renderer.render(camera, kSize, kSize, settings);
    const Image textured = renderer.read_back();
    renderer.set_materials({without});
    renderer.render(camera, kSize, kSize, settings);
    const Image plain = renderer.read_back();

    // The mean |difference| over the image, which the sphere covers 65% of.
    double difference = 0.0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const glm::vec3 d = glm::abs(textured.rgb(x, y) - plain.rgb(x, y));
        difference += (d.r + d.g + d.b) / 3.0;
      }
    difference /= kSize * kSize;
    std::printf("%-50s mean |textured - plain| %.4f\n", texture_slot_name(slot).c_str(),
                difference);
    EXPECT_TRUE(std::isfinite(difference)) << texture_slot_name(slot);
    EXPECT_GT(difference, 1e-3) << texture_slot_name(slot) << ": its texture does not reach it";
  }
}

}  // namespace
}  // namespace pbrkit::gl
