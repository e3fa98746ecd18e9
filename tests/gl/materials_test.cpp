// glTF material features of the GL renderer with closed-form expectations (no lights, no
// environment, so only the feature under test contributes): emission is added as is,
// alpha MASK discards below the cutoff, alpha BLEND composites "over" the background.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::gl {
namespace {

constexpr int kSize = 32;
const glm::vec3 kBackground(0.1f, 0.2f, 0.3f);

// The furnace sphere with `material`, rendered against a solid background; the centre.
glm::vec3 centre_pixel(const Material& material) {
  testing::context();
  Scene scene = builtin_scene("furnace");
  scene.materials.at(0) = material;
  RenderSettings settings;
  settings.msaa = 1;
  settings.background.mode = Background::Mode::kColor;
  settings.background.color = kBackground;
  const Camera camera = select_camera(scene, std::nullopt, 1.0f);
  const Image image = render_headless(scene, camera, kSize, kSize, nullptr, nullptr, settings);
  return image.rgb(kSize / 2, kSize / 2);
}

Material emissive_material() {
  Material m;
  m.base_color_factor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  m.metallic_factor = 0.0f;
  m.emissive_factor = glm::vec3(0.2f, 0.5f, 1.0f);
  m.emissive_strength = 2.0f;  // KHR_materials_emissive_strength
  return m;
}

TEST(GlMaterials, EmissionIsAdded) {
  const glm::vec3 c = centre_pixel(emissive_material());
  EXPECT_NEAR(c.r, 0.4f, 1e-5f);
  EXPECT_NEAR(c.g, 1.0f, 1e-5f);
  EXPECT_NEAR(c.b, 2.0f, 1e-5f);
}

TEST(GlMaterials, AlphaMaskDiscardsBelowTheCutoff) {
  Material m = emissive_material();
  m.alpha_mode = AlphaMode::kMask;
  m.alpha_cutoff = 0.5f;
  m.base_color_factor.a = 0.3f;
  const glm::vec3 hidden = centre_pixel(m);
  EXPECT_NEAR(hidden.r, kBackground.r, 1e-6f);
  EXPECT_NEAR(hidden.b, kBackground.b, 1e-6f);
  m.base_color_factor.a = 0.7f;
  EXPECT_NEAR(centre_pixel(m).b, 2.0f, 1e-5f);
}

TEST(GlMaterials, AlphaBlendCompositesOver) {
  Material m = emissive_material();
  m.alpha_mode = AlphaMode::kBlend;
  m.base_color_factor.a = 0.25f;
  m.double_sided = true;  // the far side of the sphere is blended first, then the near one
  const glm::vec3 c = centre_pixel(m);
  // Two layers (back then front), each out = 0.25 emission + 0.75 below.
  const glm::vec3 e(0.4f, 1.0f, 2.0f);
  const glm::vec3 back = 0.25f * e + 0.75f * kBackground;
  const glm::vec3 expected = 0.25f * e + 0.75f * back;
  EXPECT_NEAR(c.r, expected.r, 1e-4f);
  EXPECT_NEAR(c.g, expected.g, 1e-4f);
  EXPECT_NEAR(c.b, expected.b, 1e-4f);
}

// A double-sided blended sphere whose far half is red and near half green (COLOR_0), lit
// from the camera: at the centre the green near layer must be composited over the red far
// one whatever the order of the triangles (the renderer draws back faces, then front).
TEST(GlMaterials, BlendedDoubleSidedDrawsTheFarSideFirst) {
  testing::context();
  for (bool reversed : {false, true}) {
    Scene scene = builtin_scene("furnace");
    Material& m = scene.materials.at(0);
    m.alpha_mode = AlphaMode::kBlend;
    m.base_color_factor = glm::vec4(1.0f, 1.0f, 1.0f, 0.5f);
    m.metallic_factor = 0.0f;
    m.double_sided = true;
    Mesh& mesh = scene.meshes.at(0);
    mesh.colors0.clear();
    for (const glm::vec3& p : mesh.positions)
      mesh.colors0.push_back(p.z < 0.0f ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 1, 0, 1));
    if (reversed) {
      std::vector<std::uint32_t> rev;
      for (std::size_t t = mesh.indices.size() / 3; t-- > 0;)
        rev.insert(rev.end(), mesh.indices.begin() + 3 * t, mesh.indices.begin() + 3 * t + 3);
      mesh.indices = rev;
    }
    const Camera camera = select_camera(scene, std::nullopt, 1.0f);
    Light light;
    light.type = Light::Type::kDirectional;
    light.direction = camera.forward();
    light.intensity = 3.0f;
    scene.lights.push_back(light);
    RenderSettings settings;
    settings.msaa = 1;
    settings.background.mode = Background::Mode::kColor;
    const glm::vec3 c = render_headless(scene, camera, kSize, kSize, nullptr, nullptr, settings)
                            .rgb(kSize / 2, kSize / 2);
    // Over black: green 0.5 g + red 0.25 r, with g and r the lit layers (equal).
    EXPECT_NEAR(c.g / c.r, 2.0f, 0.1f) << "reversed " << reversed;
  }
}

// A BLEND material whose alpha is 1 everywhere (as exporters often write) is drawn as
// OPAQUE, with depth: one mesh of two quads facing the camera, the near one red and listed
// first, the far one green. Blended without depth writes, the far quad would be drawn over
// the near one (the patchy Stanford bunny of the shared models).
TEST(GlMaterials, BlendWithoutAlphaIsDrawnOpaque) {
  testing::context();
  Mesh mesh = make_quad({-1, -1, 0.5f}, {2, 0, 0}, {0, 2, 0});
  const Mesh far = make_quad({-1, -1, -0.5f}, {2, 0, 0}, {0, 2, 0});
  mesh.colors0.assign(mesh.positions.size(), glm::vec4(1, 0, 0, 1));
  const auto base = std::uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), far.positions.begin(), far.positions.end());
  mesh.normals.insert(mesh.normals.end(), far.normals.begin(), far.normals.end());
  mesh.texcoords0.insert(mesh.texcoords0.end(), far.texcoords0.begin(), far.texcoords0.end());
  mesh.tangents.insert(mesh.tangents.end(), far.tangents.begin(), far.tangents.end());
  mesh.colors0.resize(mesh.positions.size(), glm::vec4(0, 1, 0, 1));
  for (std::uint32_t i : far.indices) mesh.indices.push_back(base + i);
  Scene scene;
  Material m;
  m.alpha_mode = AlphaMode::kBlend;
  m.metallic_factor = 0.0f;
  scene.materials.push_back(m);
  add_mesh_instance(scene, mesh, 0);
  Light sun;
  sun.type = Light::Type::kDirectional;
  sun.direction = glm::vec3(0, 0, -1);
  sun.intensity = 3.0f;
  scene.lights.push_back(sun);
  RenderSettings settings;
  settings.msaa = 1;
  settings.background.mode = Background::Mode::kColor;
  const Camera camera = select_camera(scene, std::nullopt, 1.0f);
  const glm::vec3 c = render_headless(scene, camera, kSize, kSize, nullptr, nullptr, settings)
                          .rgb(kSize / 2, kSize / 2);
  // Red diffuse of the near quad; green only from the white specular (F0 = 0.04).
  EXPECT_GT(c.r, 0.5f);
  EXPECT_LT(c.g, 0.05f * c.r);
}

// Vertex normals that point against the winding are turned to the viewer's side (the rule
// the path tracer uses): a lit sphere whose normals all point inwards renders as the same
// sphere with outward normals. Single-sided (front faces only) and double-sided.
TEST(GlMaterials, NormalsAgainstWindingShadeLikeConsistentOnes) {
  testing::context();
  for (bool double_sided : {false, true}) {
    auto render = [&](bool flip) {
      Scene scene = builtin_scene("furnace");
      scene.materials.at(0).base_color_factor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
      scene.materials.at(0).metallic_factor = 0.0f;
      scene.materials.at(0).roughness_factor = 0.5f;
      scene.materials.at(0).double_sided = double_sided;
      if (flip)
        for (Mesh& mesh : scene.meshes)
          for (glm::vec3& n : mesh.normals) n = -n;
      Light light;
      light.type = Light::Type::kPoint;
      light.intensity = 20.0f;
      light.position = glm::vec3(1.5f, 2.0f, 4.0f);
      scene.lights.push_back(light);
      RenderSettings settings;
      settings.msaa = 1;
      settings.background.mode = Background::Mode::kColor;
      settings.background.color = glm::vec3(0.0f);
      const Camera camera = select_camera(scene, std::nullopt, 1.0f);
      return render_headless(scene, camera, kSize, kSize, nullptr, nullptr, settings);
    };
    const Image consistent = render(false);
    const Image flipped = render(true);
    ASSERT_GT(consistent.rgb(kSize / 2, kSize / 2).r, 0.05f);
    double max_diff = 0.0;
    for (std::size_t i = 0; i < consistent.data.size(); ++i)
      max_diff = std::max(max_diff, double(std::fabs(consistent.data[i] - flipped.data[i])));
    EXPECT_LT(max_diff, 1e-5) << "double_sided " << double_sided;
  }
}

}  // namespace
}  // namespace pbrkit::gl
