// scene.h's has_alpha: which primitives the renderers may treat as opaque. A BLEND
// material whose alpha is 1 everywhere is opaque; any alpha below 1 (factor, baseColor
// texture, COLOR_0) or MASK is not.
#include <gtest/gtest.h>

#include "pbrkit/scene/primitives.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit {
namespace {

Scene quad_scene(AlphaMode mode) {
  Scene scene;
  Material m;
  m.alpha_mode = mode;
  scene.materials.push_back(m);
  add_mesh_instance(scene, make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 0);
  return scene;
}

// A 2x2 RGBA texture whose last texel has alpha `a`.
Texture rgba_texture(float a) {
  Image image(2, 2, 4);
  for (float& v : image.data) v = 1.0f;
  image.data.back() = a;
  return Texture::from_linear(image, false);
}

TEST(HasAlpha, OpaqueAndMaskFollowTheMode) {
  EXPECT_FALSE(has_alpha(quad_scene(AlphaMode::kOpaque), quad_scene(AlphaMode::kOpaque).meshes[0]));
  Scene opaque = quad_scene(AlphaMode::kOpaque);
  opaque.materials[0].base_color_factor.a = 0.5f;  // ignored: OPAQUE
  EXPECT_FALSE(has_alpha(opaque, opaque.meshes[0]));
  const Scene mask = quad_scene(AlphaMode::kMask);
  EXPECT_TRUE(has_alpha(mask, mask.meshes[0]));
}

TEST(HasAlpha, BlendNeedsAnAlphaBelowOneSomewhere) {
  Scene scene = quad_scene(AlphaMode::kBlend);
  EXPECT_FALSE(has_alpha(scene, scene.meshes[0]));  // alpha 1 everywhere: opaque

  scene.materials[0].base_color_factor.a = 0.999f;
  EXPECT_TRUE(has_alpha(scene, scene.meshes[0]));
  scene.materials[0].base_color_factor.a = 1.0f;

  Mesh& mesh = scene.meshes[0];
  mesh.colors0.assign(mesh.positions.size(), glm::vec4(1.0f));
  EXPECT_FALSE(has_alpha(scene, mesh));
  mesh.colors0[2].a = 0.0f;
  EXPECT_TRUE(has_alpha(scene, mesh));
  mesh.colors0.clear();

  scene.textures.push_back(rgba_texture(1.0f));
  scene.materials[0].base_color_texture.texture = 0;
  EXPECT_FALSE(has_alpha(scene, mesh));
  scene.textures[0] = rgba_texture(0.25f);
  EXPECT_TRUE(has_alpha(scene, mesh));
}

}  // namespace
}  // namespace pbrkit
