// The OpenGL renderer captures the frame again before glass that covers glass drawn since
// the last capture, up to a fixed number of captures (gl/renderer.cpp); a frame that needs
// more gets a warning naming the limit, once per renderer, rather than a silently wrong
// image. Sheets of clear glass stacked in front of an emissive backdrop: each sheet covers
// the one behind it, so n sheets need n captures (the opaque frame's, then one before each
// sheet after the first).
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/util/log.h"

namespace pbrkit::gl {
namespace {

Scene stacked_sheets(int n) {
  Scene scene;
  Material backdrop;
  backdrop.base_color_factor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  backdrop.emissive_factor = glm::vec3(0.2f, 0.5f, 1.0f);
  scene.materials.push_back(backdrop);
  add_mesh_instance(scene,
                    make_quad(glm::vec3(-5, -5, -2), glm::vec3(10, 0, 0), glm::vec3(0, 10, 0)), 0);
  Material glass;
  glass.base_color_factor = glm::vec4(1.0f);
  glass.metallic_factor = 0.0f;
  glass.roughness_factor = 0.0f;
  glass.transmission = TransmissionExtension{1.0f, {}};
  scene.materials.push_back(glass);
  for (int k = 0; k < n; ++k)
    add_mesh_instance(scene,
                      make_quad(glm::vec3(-1, -1, -1.0f + 0.3f * float(k)), glm::vec3(2, 0, 0),
                                glm::vec3(0, 2, 0)),
                      1);
  return scene;
}

// The warnings logged while rendering `scene` `frames` times with one renderer.
std::vector<std::string> warnings_rendering(const Scene& scene, int frames) {
  testing::context();
  std::vector<std::string> lines;
  const LogSink previous = set_log_sink([&](LogLevel level, const std::string& m) {
    if (level == LogLevel::kWarning) lines.push_back(m);
  });
  Camera camera;
  camera.yfov = 0.6f;
  camera.camera_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 3.0f));
  RenderSettings settings;
  settings.msaa = 1;
  settings.background.mode = Background::Mode::kColor;
  Renderer renderer;
  renderer.set_scene(scene);
  for (int f = 0; f < frames; ++f) renderer.render(camera, 32, 32, settings);
  set_log_sink(previous);
  return lines;
}

TEST(GlTransmissionCaptures, MoreGlassLayersThanCapturesWarnOnceNamingTheLimit) {
  // Four sheets need four captures (the limit): no warning.
  EXPECT_TRUE(warnings_rendering(stacked_sheets(4), 1).empty());
  // Five need five: one warning naming the limit, however many frames are drawn.
  const std::vector<std::string> lines = warnings_rendering(stacked_sheets(5), 3);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("more than 4 captures"), std::string::npos) << lines[0];
}

}  // namespace
}  // namespace pbrkit::gl
