// The viewer's display pass runs display.glsl on the GPU: for every tone mapper and
// several exposures it must give what the C++ display_transform (the PNG outputs) gives,
// to 2e-5 of full scale, well under half an 8-bit step (2e-3), so the window shows the same
// 8-bit values as the PNG but for rare ties. Inputs span black to far above white, with
// saturated colours and exact zeros. And Renderer::display, the pass itself, end to end.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gl/harness/display_eval.h"
#include "gl_test_context.h"
#include "pbrkit/core/color.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"

namespace pbrkit::gl {
namespace {

std::vector<glm::vec3> test_colours() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> ev(-14.0f, 8.0f), u(0.0f, 1.0f);
  std::vector<glm::vec3> colours = {glm::vec3(0.0f), glm::vec3(1.0f), glm::vec3(0.0031308f),
                                    glm::vec3(0.18f), glm::vec3(1e6f, 0.0f, 0.0f)};
  for (int i = 0; i < 4000; ++i) {
    // Log-uniform luminance, random chroma, some channels exactly zero.
    const float scale = std::exp2(ev(rng));
    glm::vec3 c(u(rng), u(rng), u(rng));
    if (i % 7 == 0) c[i % 3] = 0.0f;
    colours.push_back(c * scale);
  }
  return colours;
}

TEST(DisplayGlsl, MatchesTheCppDisplayTransform) {
  testing::context();
  const std::vector<glm::vec3> colours = test_colours();
  for (ToneMapper mapper :
       {ToneMapper::kNone, ToneMapper::kPbrNeutral, ToneMapper::kAces, ToneMapper::kAgx}) {
    for (float exposure : {-2.0f, 0.0f, 1.5f}) {
      const std::vector<glm::vec3> gpu = display_transform_glsl(colours, exposure, mapper);
      ASSERT_EQ(gpu.size(), colours.size());
      double worst = 0.0;
      std::size_t worst_index = 0;
      for (std::size_t i = 0; i < colours.size(); ++i) {
        const glm::vec3 cpu = display_transform(colours[i], exposure, mapper);
        for (int k = 0; k < 3; ++k) {
          const double d = std::abs(double(gpu[i][k]) - double(cpu[k]));
          if (d > worst) worst = d, worst_index = i;
        }
      }
      EXPECT_LT(worst, 2e-5) << tone_mapper_name(mapper) << " at " << exposure
                             << " EV: worst for input (" << colours[worst_index].r << ", "
                             << colours[worst_index].g << ", " << colours[worst_index].b << ")";
    }
  }
}

// The renderer's display pass end to end: a rendered frame drawn by Renderer::display into
// an 8-bit target holds, pixel for pixel and the right way up, the 8-bit values of the CPU
// display transform of the read-back frame (what the PNG writer stores), within one step.
TEST(DisplayGlsl, RendererDisplayPassShowsWhatThePngHolds) {
  testing::context();
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  const Scene scene = builtin_scene("spheres");
  constexpr int kWidth = 96, kHeight = 64;
  const Camera camera = select_camera(scene, std::nullopt, float(kWidth) / float(kHeight));
  Renderer renderer;
  renderer.set_scene(scene);
  renderer.set_environment(&env);
  RenderSettings settings;
  settings.msaa = 1;
  renderer.render(camera, kWidth, kHeight, settings);
  const Image frame = renderer.read_back();  // row 0 at the top

  GLuint target = 0, fbo = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &target);
  glTextureStorage2D(target, 1, GL_RGBA8, kWidth, kHeight);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
  for (ToneMapper mapper : {ToneMapper::kPbrNeutral, ToneMapper::kAgx}) {
    const float exposure = mapper == ToneMapper::kAgx ? 1.0f : 0.0f;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    renderer.display(exposure, mapper);
    std::vector<unsigned char> pixels(std::size_t(kWidth) * kHeight * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    int worst = 0, differing = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        // GL row 0 is the bottom row.
        const unsigned char* p = &pixels[(std::size_t(kHeight - 1 - y) * kWidth + x) * 4];
        const glm::vec3 want = display_transform(frame.rgb(x, y), exposure, mapper);
        for (int k = 0; k < 3; ++k) {
          const int d = std::abs(int(p[k]) - int(std::lround(want[k] * 255.0f)));
          worst = std::max(worst, d);
          differing += d > 0;
        }
      }
    EXPECT_LE(worst, 1) << tone_mapper_name(mapper);
    EXPECT_LT(differing, kWidth * kHeight * 3 / 100) << tone_mapper_name(mapper);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &target);
}

}  // namespace
}  // namespace pbrkit::gl
