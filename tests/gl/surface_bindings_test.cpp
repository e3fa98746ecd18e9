// The surface program's names for its texture slots, texture units and buffer binding
// points (surface_bindings.h): every slot and unit is named once, with its own number, the
// surface shaders type none of the numbers, and each material texture slot reads its own
// texture through its own unit and channels (a slot wired to another unit or channel
// renders otherwise than its texel folded into the factors).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/gl/shader_permutations.h"
#include "pbrkit/gl/shaders.h"
#include "pbrkit/gl/surface_bindings.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::gl {
namespace {

// The value of `macro` as the prelude defines it (-1 when it is not defined). (Scanned by
// hand: GCC 12's <regex> trips -Wmaybe-uninitialized in the sanitizer builds.)
int defined_value(const std::string& prelude, const std::string& macro) {
  const std::string key = "#define " + macro + " ";
  for (std::size_t at = prelude.find(key); at != std::string::npos;
       at = prelude.find(key, at + 1)) {
    if (at > 0 && prelude[at - 1] != '\n') continue;
    const std::size_t begin = at + key.size(), end = prelude.find('\n', begin);
    const std::string value = prelude.substr(begin, end - begin);
    if (value.empty() || value.find_first_not_of("-0123456789") != std::string::npos) return -1;
    return std::stoi(value);
  }
  return -1;
}

// Whether `text` has `prefix` followed by a digit (after spaces; with separator '=', after
// spaces, '=' and spaces; with another separator, after the first one): a number typed where
// a name belongs.
bool number_follows(const std::string& text, const std::string& prefix, char separator) {
  for (std::size_t at = text.find(prefix); at != std::string::npos;
       at = text.find(prefix, at + 1)) {
    std::size_t i = at + prefix.size();
    if (separator == '=') {  // `binding = N`: only spaces around the '='
      while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
      if (i == text.size() || text[i] != '=') continue;
      ++i;
    } else if (separator != 0) {  // `map_normal(tex, N`: the argument after the first comma
      i = text.find(separator, i);
      if (i == std::string::npos) return false;
      ++i;
    }
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
    if (i < text.size() && text[i] >= '0' && text[i] <= '9') return true;
  }
  return false;
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
  std::set<GLuint> units, buffers, blocks;
  const std::string& prelude = surface_prelude();
  for (const SurfaceBinding& b : surface_bindings()) {
    EXPECT_TRUE(names.insert(b.name).second) << b.name;
    using Kind = SurfaceBinding::Kind;
    std::set<GLuint>& taken = b.kind == Kind::kStorageBuffer   ? buffers
                              : b.kind == Kind::kUniformBuffer ? blocks
                                                               : units;
    EXPECT_TRUE(taken.insert(b.point).second)
        << b.name << " shares "
        << (b.kind == Kind::kSampler ? "texture unit " : "buffer binding point ") << b.point;
    if (b.kind == Kind::kSampler) {
      EXPECT_LE(b.point, kLastSurfaceUnit) << b.name;
    }
    EXPECT_EQ(defined_value(prelude, "BINDING_" + b.name), int(b.point)) << b.name;
  }
}

// Every shader a renderer program compiles (all but the *_test.glsl compute harnesses,
// whose buffers the tests bind themselves) reads its units and binding points by name.
TEST(GlSurfaceBindings, TheRenderersShadersTypeNoSlotOrBindingNumber) {
  int scanned = 0;
  for (const std::string& file : shader_names()) {
    const std::string suffix = "_test.glsl";
    if (file.size() > suffix.size() &&
        file.compare(file.size() - suffix.size(), suffix.size(), suffix) == 0)
      continue;
    ++scanned;
    const std::string text = expand_shader(file);
    EXPECT_FALSE(number_follows(text, "binding", '=')) << file;
    EXPECT_FALSE(number_follows(text, "texcoord(", 0)) << file;
    EXPECT_FALSE(number_follows(text, "map_normal(", ',')) << file;
    EXPECT_EQ(text.find("HAS_TEXTURE_"), std::string::npos) << file;
  }
  EXPECT_GE(scanned, 8);  // at least the surface, back-face, background and display shaders
  // The scan sees a typed number where there is one.
  EXPECT_TRUE(number_follows("layout(binding = 1) uniform sampler2D u;", "binding", '='));
  EXPECT_FALSE(
      number_follows("layout(binding = BINDING_FRAME) uniform sampler2D u;", "binding", '='));
}

// The background and display programs' preludes name each of their units with its number,
// and no two of a program's units share one.
TEST(GlSurfaceBindings, TheBackgroundAndDisplayPreludesNameTheirUnits) {
  for (const auto& [bindings, prelude] : {std::pair{background_bindings(), background_prelude()},
                                          std::pair{display_bindings(), display_prelude()}}) {
    std::set<GLuint> units;
    for (const SurfaceBinding& b : bindings) {
      EXPECT_TRUE(units.insert(b.point).second) << b.name;
      EXPECT_EQ(defined_value(prelude, "BINDING_" + b.name), int(b.point)) << b.name;
    }
  }
  EXPECT_EQ(defined_value(background_prelude(), "BINDING_ENVIRONMENT"),
            int(kBackgroundEnvironmentUnit));
  EXPECT_EQ(defined_value(background_prelude(), "BINDING_SPECULAR_CUBE"),
            int(kBackgroundSpecularCubeUnit));
  EXPECT_EQ(defined_value(display_prelude(), "BINDING_FRAME"), int(kDisplayFrameUnit));
}

// The renderer sets each extension's factors by the schema (factor_uniform()'s names): the
// surface program with every extension on has each as an active uniform of the factor's
// type, so that none is set on a name the shader does not read.
TEST(GlSurfaceBindings, EverySchemaFactorIsAUniformOfItsType) {
  testing::context();
  ShaderPermutations permutations;
  SurfaceFeatures f;
  f.specular = f.anisotropy = f.iridescence = f.clearcoat = f.sheen = true;
  f.transmission = f.volume = f.dispersion = f.diffuse_transmission = true;
  f.ibl = true;
  f.textures = (1u << kTextureSlotCount) - 1u;  // a factor may be read only with its texture
  const GLuint program = permutations.surface(f).id();
  std::map<std::string, GLenum> active;
  GLint count = 0;
  glGetProgramiv(program, GL_ACTIVE_UNIFORMS, &count);
  for (GLint i = 0; i < count; ++i) {
    char name[256];
    GLsizei length = 0;
    GLint size = 0;
    GLenum type = 0;
    glGetActiveUniform(program, GLuint(i), sizeof name, &length, &size, &type, name);
    active[std::string(name, std::size_t(length))] = type;
  }
  int factors = 0;
  for (const MaterialExtension& e : material_extensions())
    for (const MaterialFactor& factor : e.factors) {
      const std::string name = factor_uniform(factor);
      const auto it = active.find(name);
      ASSERT_NE(it, active.end()) << e.name << "." << factor.json_name << ": no " << name;
      EXPECT_EQ(it->second, GLenum(factor.components == 3 ? GL_FLOAT_VEC3 : GL_FLOAT)) << name;
      ++factors;
    }
  EXPECT_GE(factors, 20);  // ior 1, specular 2, clearcoat 2, sheen 2, anisotropy 2,
                           // iridescence 4, transmission 1, volume 3, dispersion 1, DT 2
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

// The texel's values, i / 255 of its 8-bit samples.
constexpr glm::vec4 kTexel(204.0f / 255.0f, 77.0f / 255.0f, 153.0f / 255.0f, 102.0f / 255.0f);

// Folds a constant texture of kTexel in `slot` into the factors it scales (the channels
// material_schema.cpp lists for it), so that the material without the texture is
// the one the shader should see with it; false where no factor is equivalent (a normal,
// an anisotropy direction, the occlusion, which has no factor).
bool fold_texel(Material& m, TextureSlot slot) {
  switch (slot) {
    case TextureSlot::kBaseColor:
      m.base_color_factor *= kTexel;
      return true;
    case TextureSlot::kMetallicRoughness:
      m.roughness_factor *= kTexel.g;
      m.metallic_factor *= kTexel.b;
      return true;
    case TextureSlot::kEmissive:
      m.emissive_factor *= glm::vec3(kTexel);
      return true;
    case TextureSlot::kSpecular:
      m.specular->factor *= kTexel.a;
      return true;
    case TextureSlot::kSpecularColor:
      m.specular->color_factor *= glm::vec3(kTexel);
      return true;
    case TextureSlot::kClearcoat:
      m.clearcoat->factor *= kTexel.r;
      return true;
    case TextureSlot::kClearcoatRoughness:
      m.clearcoat->roughness_factor *= kTexel.g;
      return true;
    case TextureSlot::kSheenColor:
      m.sheen->color_factor *= glm::vec3(kTexel);
      return true;
    case TextureSlot::kSheenRoughness:
      m.sheen->roughness_factor *= kTexel.a;
      return true;
    case TextureSlot::kIridescence:
      m.iridescence->factor *= kTexel.r;
      return true;
    case TextureSlot::kIridescenceThickness:
      // The README: thickness = mix(minimum, maximum, G); the maximum without the texture.
      m.iridescence->thickness_max =
          glm::mix(m.iridescence->thickness_min, m.iridescence->thickness_max, kTexel.g);
      return true;
    case TextureSlot::kTransmission:
      m.transmission->factor *= kTexel.r;
      return true;
    case TextureSlot::kThickness:
      m.volume->thickness_factor *= kTexel.g;
      return true;
    case TextureSlot::kDiffuseTransmission:
      m.diffuse_transmission->factor *= kTexel.a;
      return true;
    case TextureSlot::kDiffuseTransmissionColor:
      m.diffuse_transmission->color_factor *= glm::vec3(kTexel);
      return true;
    default:
      return false;
  }
}

// The mean over the pixels of |a - b|, averaged over R, G, B.
double mean_difference(const Image& a, const Image& b) {
  double sum = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const glm::vec3 d = glm::abs(a.rgb(x, y) - b.rgb(x, y));
      sum += (d.r + d.g + d.b) / 3.0;
    }
  return sum / (double(a.width) * a.height);
}

// A slot reads its own texture through its own unit and channels: the image with a
// constant texture in the slot is the image with the texel folded into the factors, and
// differs from the one without it. A slot wired to another unit reads that unit's texture
// (the white one, an unbound unit's black, or a stale one), which matches neither.
TEST(GlSurfaceBindings, EachSlotReadsItsTextureThroughItsOwnUnit) {
  testing::context();
  // One texel, every channel away from 1 and from the others (a factor times it differs
  // from the factor alone; as a normal or anisotropy direction it tilts, (0.6, -0.4)).
  const Texture texel = Texture::from_unorm8(1, 1, 4, {204, 77, 153, 102}, false);  // kTexel
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

    const double difference = mean_difference(textured, plain);
    Material folded = without;
    const bool foldable = fold_texel(folded, slot);
    double folded_difference = 0.0;
    if (foldable) {
      renderer.set_materials({folded});
      renderer.render(camera, kSize, kSize, settings);
      folded_difference = mean_difference(textured, renderer.read_back());
    }
    std::printf("%-54s mean |textured - plain| %.4f, |textured - folded| %.1e\n",
                texture_slot_name(slot).c_str(), difference, folded_difference);
    // 1e-3: the smallest change measured above is 3e-3 (the specular colour's); llvmpipe
    // renders a material the same way each time, so an unused texture changes nothing.
    EXPECT_GT(difference, 1e-3) << texture_slot_name(slot) << ": its texture changes nothing";
    // A 1x1 unorm texel is fetched exactly (any filter), so only float rounding of the
    // factor times it remains (measured: below 1e-8); 1e-4 is 30 times below the smallest
    // change a texture makes, and a sampler on another unit or channel measured >= 1e-2.
    EXPECT_LT(folded_difference, 1e-4) << texture_slot_name(slot) << ": not its texel's value";
  }
}

}  // namespace
}  // namespace pbrkit::gl
