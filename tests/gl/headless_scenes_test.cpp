// Headless rendering (EGL, no display) of every built-in scene and of the shared glTF
// models, as CI runs it: each image must be finite and must show the scene, i.e. differ
// from the same camera's empty-scene (background only) image on a good share of pixels.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "support/test_paths.h"

namespace pbrkit::gl {
namespace {

const IblMaps& small_ibl(const Environment& env) {
  static const IblMaps maps = testing::small_ibl_maps(env);
  return maps;
}

// Fraction of pixels where the scene changed the image.
double coverage(const std::string& scene_name, float min_fraction) {
  testing::context();
  static const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  const Scene scene = load_scene(scene_name);
  constexpr int kSize = 64;
  const Camera camera = select_camera(scene, std::nullopt, 1.0f);
  RenderSettings settings;
  settings.msaa = 2;
  Renderer renderer;
  renderer.set_environment(&env);
  renderer.set_ibl(&small_ibl(env));
  renderer.set_scene(scene);
  renderer.render(camera, kSize, kSize, settings);
  const Image image = renderer.read_back();
  renderer.set_scene(Scene{});
  renderer.render(camera, kSize, kSize, settings);
  const Image empty = renderer.read_back();
  int changed = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec3 a = image.rgb(x, y), b = empty.rgb(x, y);
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(a[k])) << scene_name;
      if (glm::length(a - b) > 1e-3f * (1.0f + glm::length(b))) ++changed;
    }
  const double fraction = double(changed) / double(kSize * kSize);
  EXPECT_GT(fraction, min_fraction) << scene_name;
  return fraction;
}

TEST(GlHeadless, BuiltinScenes) {
  for (const std::string& name : builtin_scene_names()) coverage(name, 0.2f);
}

TEST(GlHeadless, SharedModels) {
  for (const char* model :
       {"models/bunny_uncompressed.glb", "models/suzi_uncompressed.glb",
        "models/BoxTextured/BoxTextured.gltf", "models/BoxTextured/BoxTextured.glb",
        "models/Cameras/Cameras.gltf", "models/AnimatedMorphCube/AnimatedMorphCube.gltf",
        "models/2CylinderEngine/2CylinderEngine.glb"})
    coverage(pbrkit::test::shared_asset(model).string(), 0.02f);
}

}  // namespace
}  // namespace pbrkit::gl
