// Headless contexts (gl/context.h) share their process's EGL display: destroying one must
// leave the others working. Before the display was reference-counted, every
// ~HeadlessContext terminated it, so a second context (gl_tests' shared one after
// render_headless, or the survivor of two) could no longer be made current or draw, and
// gl_tests crashed when run in one process.
#include <memory>

#include <gtest/gtest.h>

#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"

namespace pbrkit::gl {
namespace {

constexpr glm::vec3 kColor(0.25f, 0.5f, 0.75f);

RenderSettings solid_background() {
  RenderSettings settings;
  settings.msaa = 1;
  settings.background.mode = Background::Mode::kColor;
  settings.background.color = kColor;
  return settings;
}

// Draws an empty scene on the solid background with whatever context is current and
// counts the pixels that are not the background colour (exactly: no tone mapping, and the
// colour is representable in the float target).
int wrong_pixels() {
  constexpr int kSize = 8;
  Renderer renderer;
  renderer.set_scene(Scene{});
  renderer.render(Camera{}, kSize, kSize, solid_background());
  const Image image = renderer.read_back();
  if (image.width != kSize || image.height != kSize) return kSize * kSize;
  int wrong = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) wrong += image.rgb(x, y) != kColor;
  return wrong;
}

TEST(GlContext, OneContextSurvivesAnothersDestruction) {
  // Both orders: the destroyed context is the current one (b, the newer) or not (a).
  for (bool destroy_current : {false, true}) {
    auto a = std::make_unique<HeadlessContext>();
    auto b = std::make_unique<HeadlessContext>();
    ASSERT_EQ(a->platform(), b->platform());
    EXPECT_EQ(wrong_pixels(), 0) << "with both alive";
    std::unique_ptr<HeadlessContext>& survivor = destroy_current ? a : b;
    (destroy_current ? b : a).reset();
    ASSERT_NO_THROW(survivor->make_current()) << "destroy_current " << destroy_current;
    EXPECT_EQ(wrong_pixels(), 0) << "destroy_current " << destroy_current;
  }
}

TEST(GlContext, RenderHeadlessLeavesTheCallersContextUsable) {
  // render_headless makes and destroys a context of its own, as `pbrkit render --renderer
  // gl` does; a context the caller holds must still draw afterwards.
  HeadlessContext mine;
  const Image other =
      render_headless(Scene{}, Camera{}, 4, 4, nullptr, nullptr, solid_background());
  EXPECT_EQ(other.rgb(1, 1), kColor);
  ASSERT_NO_THROW(mine.make_current());
  EXPECT_EQ(wrong_pixels(), 0);
}

}  // namespace
}  // namespace pbrkit::gl
