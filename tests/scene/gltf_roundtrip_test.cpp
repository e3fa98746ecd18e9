// write_glb -> load_scene must reproduce every attribute and material value of the
// built-in scenes (and of a scene exercising the optional features).
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

// Element-wise equality with a short message (gtest would print whole vectors).
template <typename T>
void expect_same(const std::vector<T>& a, const std::vector<T>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i])) {
      ADD_FAILURE() << what << " differs first at element " << i;
      return;
    }
}

void expect_same_material(const Material& a, const Material& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.base_color_factor, b.base_color_factor);
  EXPECT_EQ(a.metallic_factor, b.metallic_factor);
  EXPECT_EQ(a.roughness_factor, b.roughness_factor);
  // glTF keeps emissiveFactor in [0, 1]: a brighter factor comes back as a [0, 1] colour
  // and a larger strength, with the same emitted radiance.
  const glm::vec3 ea = a.emissive_factor * a.emissive_strength;
  const glm::vec3 eb = b.emissive_factor * b.emissive_strength;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(ea[c], eb[c], 1e-6f * std::max(1.0f, ea[c]));
  EXPECT_LE(std::max({b.emissive_factor.r, b.emissive_factor.g, b.emissive_factor.b}), 1.0f);
  EXPECT_EQ(a.normal_scale, b.normal_scale);
  EXPECT_EQ(a.occlusion_strength, b.occlusion_strength);
  EXPECT_EQ(a.alpha_mode, b.alpha_mode);
  EXPECT_EQ(a.alpha_cutoff, b.alpha_cutoff);
  EXPECT_EQ(a.double_sided, b.double_sided);
  // The KHR_materials surface extensions (material_extensions_test.cpp covers their
  // textures); an unlit material is written with KHR_materials_unlit only.
  EXPECT_EQ(a.unlit, b.unlit);
  if (!a.unlit) {
    EXPECT_EQ(a.ior, b.ior);
    ASSERT_EQ(a.specular.has_value(), b.specular.has_value());
    if (a.specular) {
      EXPECT_EQ(a.specular->factor, b.specular->factor);
      EXPECT_EQ(a.specular->color_factor, b.specular->color_factor);
    }
    ASSERT_EQ(a.clearcoat.has_value(), b.clearcoat.has_value());
    if (a.clearcoat) {
      EXPECT_EQ(a.clearcoat->factor, b.clearcoat->factor);
      EXPECT_EQ(a.clearcoat->roughness_factor, b.clearcoat->roughness_factor);
    }
    ASSERT_EQ(a.sheen.has_value(), b.sheen.has_value());
    if (a.sheen) {
      EXPECT_EQ(a.sheen->color_factor, b.sheen->color_factor);
      EXPECT_EQ(a.sheen->roughness_factor, b.sheen->roughness_factor);
    }
    ASSERT_EQ(a.anisotropy.has_value(), b.anisotropy.has_value());
    if (a.anisotropy) {
      EXPECT_EQ(a.anisotropy->strength, b.anisotropy->strength);
      EXPECT_EQ(a.anisotropy->rotation, b.anisotropy->rotation);
    }
    ASSERT_EQ(a.iridescence.has_value(), b.iridescence.has_value());
    if (a.iridescence) {
      EXPECT_EQ(a.iridescence->factor, b.iridescence->factor);
      EXPECT_EQ(a.iridescence->ior, b.iridescence->ior);
      EXPECT_EQ(a.iridescence->thickness_min, b.iridescence->thickness_min);
      EXPECT_EQ(a.iridescence->thickness_max, b.iridescence->thickness_max);
    }
  }
  for (auto [ra, rb] : {std::pair{&a.base_color_texture, &b.base_color_texture},
                        std::pair{&a.metallic_roughness_texture, &b.metallic_roughness_texture},
                        std::pair{&a.normal_texture, &b.normal_texture},
                        std::pair{&a.occlusion_texture, &b.occlusion_texture},
                        std::pair{&a.emissive_texture, &b.emissive_texture}}) {
    EXPECT_EQ(ra->valid(), rb->valid());
    EXPECT_EQ(ra->texcoord, rb->texcoord);
    EXPECT_EQ(ra->transform.has_value(), rb->transform.has_value());
    if (ra->transform && rb->transform) {
      EXPECT_EQ(ra->transform->offset, rb->transform->offset);
      EXPECT_EQ(ra->transform->scale, rb->transform->scale);
      EXPECT_EQ(ra->transform->rotation, rb->transform->rotation);
    }
  }
}

void expect_same_scene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (std::size_t i = 0; i < a.meshes.size(); ++i) {
    const Mesh &ma = a.meshes[i], &mb = b.meshes[i];
    EXPECT_EQ(ma.name, mb.name);
    expect_same(ma.positions, mb.positions, "positions");
    expect_same(ma.normals, mb.normals, "normals");
    expect_same(ma.tangents, mb.tangents, "tangents");
    expect_same(ma.texcoords0, mb.texcoords0, "texcoords0");
    expect_same(ma.texcoords1, mb.texcoords1, "texcoords1");
    expect_same(ma.colors0, mb.colors0, "colors0");
    expect_same(ma.indices, mb.indices, "indices");
    EXPECT_EQ(ma.material, mb.material);
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i)
    expect_same_material(a.materials[i], b.materials[i]);
  ASSERT_EQ(a.instances.size(), b.instances.size());
  for (std::size_t i = 0; i < a.instances.size(); ++i) {
    EXPECT_EQ(a.instances[i].mesh, b.instances[i].mesh);
    // A mesh drawn more than once is written with EXT_mesh_gpu_instancing, as translation,
    // rotation (a quaternion) and scale: rebuilt, the matrix may differ by float rounding.
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        EXPECT_NEAR(a.instances[i].transform[c][r], b.instances[i].transform[c][r],
                    4e-7f * (1.0f + std::fabs(a.instances[i].transform[c][r])))
            << "instance " << i << " [" << c << "][" << r << "]";
  }
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (std::size_t i = 0; i < a.cameras.size(); ++i) {
    const Camera &ca = a.cameras[i], &cb = b.cameras[i];
    EXPECT_EQ(ca.type, cb.type);
    EXPECT_EQ(ca.yfov, cb.yfov);
    EXPECT_EQ(ca.aspect_ratio, cb.aspect_ratio);
    EXPECT_EQ(ca.znear, cb.znear);
    EXPECT_EQ(ca.zfar, cb.zfar);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        EXPECT_NEAR(ca.camera_to_world[c][r], cb.camera_to_world[c][r], 1e-6f);
  }
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    const Light &la = a.lights[i], &lb = b.lights[i];
    EXPECT_EQ(la.type, lb.type);
    EXPECT_EQ(la.color, lb.color);
    EXPECT_EQ(la.intensity, lb.intensity);
    EXPECT_EQ(la.range, lb.range);
    EXPECT_EQ(la.inner_cone_angle, lb.inner_cone_angle);
    EXPECT_EQ(la.outer_cone_angle, lb.outer_cone_angle);
    EXPECT_NEAR(glm::distance(la.position, lb.position), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(la.direction, lb.direction), 0.0f, 1e-6f);
  }
}

TEST(GltfRoundTrip, BuiltinScenes) {
  const auto dir = test::scratch_dir();
  for (const std::string& name : builtin_scene_names()) {
    SCOPED_TRACE(name);
    const Scene original = builtin_scene(name);
    const auto path = dir / (name + ".glb");
    write_glb(original, path);
    EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
    const Scene loaded = load_scene(path.string());
    EXPECT_TRUE(loaded.warnings.empty());
    expect_same_scene(original, loaded);
  }
}

TEST(GltfRoundTrip, OptionalFeatures) {
  Scene s;
  s.source = "test";
  Image img(2, 2, 4, 1.0f);
  img.pixel(1, 0)[0] = 0.0f;
  Texture tex = Texture::from_linear(img, true);
  tex.name = "tex";
  tex.sampler.wrap_s = WrapMode::kMirroredRepeat;
  s.textures.push_back(tex);
  Material m;
  m.name = "everything";
  m.base_color_factor = {0.1f, 0.2f, 0.3f, 0.4f};
  m.alpha_mode = AlphaMode::kMask;
  m.alpha_cutoff = 0.25f;
  m.double_sided = true;
  m.normal_scale = 0.7f;
  m.occlusion_strength = 0.3f;
  m.emissive_factor = {1, 2, 3};
  m.emissive_strength = 4.0f;
  m.base_color_texture.texture = 0;
  m.base_color_texture.texcoord = 1;
  m.base_color_texture.transform = TextureTransform{{0.5f, 0.25f}, 0.3f, {2.0f, 3.0f}};
  m.emissive_texture.texture = 0;  // same source, also sRGB: shared on load
  // Normal scale and occlusion strength only exist in glTF together with their textures;
  // used as data, the same image loads as a second (linear) texture.
  m.normal_texture.texture = 0;
  m.occlusion_texture.texture = 0;
  s.materials.push_back(m);
  Mesh mesh = make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  mesh.texcoords1 = mesh.texcoords0;
  mesh.colors0.assign(4, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
  // A transform glTF can store (the writer flattens nodes to world matrices, which must
  // decompose into translation, rotation and scale).
  add_mesh_instance(s, mesh, 0,
                    glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {1.0f, 2.0f, 3.0f}),
                                           0.5f, glm::vec3(0.0f, 1.0f, 0.0f)),
                               glm::vec3(2.0f)));
  Light spot;
  spot.name = "spot";
  spot.type = Light::Type::kSpot;
  spot.color = {1, 0.5f, 0.25f};
  spot.intensity = 12.0f;
  spot.range = 7.0f;
  spot.inner_cone_angle = 0.1f;
  spot.outer_cone_angle = 0.5f;
  spot.position = {1, 2, 3};
  spot.direction = glm::normalize(glm::vec3(1, -1, 0));
  s.lights.push_back(spot);
  const auto path = test::scratch_dir() / "features.glb";
  write_glb(s, path);
  EXPECT_EQ(test::validate_gltf(path), "");  // the Khronos glTF-Validator
  const Scene loaded = load_scene(path.string());
  expect_same_scene(s, loaded);
  ASSERT_EQ(loaded.textures.size(), 2u);
  EXPECT_TRUE(loaded.textures[0].srgb);
  EXPECT_FALSE(loaded.textures[1].srgb);
  EXPECT_EQ(loaded.textures[0].sampler.wrap_s, WrapMode::kMirroredRepeat);
  // 8-bit sRGB storage: 1 and 0 are exact.
  EXPECT_EQ(loaded.textures[0].format, TexelFormat::kUnorm8);
  EXPECT_EQ(loaded.textures[0].texel(0, 1, 0).r, 0.0f);
  EXPECT_EQ(loaded.textures[0].texel(0, 0, 0).r, 1.0f);
}

}  // namespace
}  // namespace pbrkit
