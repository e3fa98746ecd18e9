// What the default bounce count (PathTracerSettings::max_bounces, the CLI's --max-bounces
// default) costs against a converged render: light that needs more interactions than the
// limit allows (through a glass object's two interfaces and its internal reflections, a
// liquid inside a tumbler) is dropped, so a truncated render is darker (measured as
// support/bounce_deficit.h says; every built-in scene's table: bench/bounces_bench.cpp).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/load.h"
#include "support/bounce_deficit.h"

namespace pbrkit::test {
namespace {

// The built-in transmissive scenes at the default bounce count are within 1% of converged:
// `glass` (two interfaces per object, total internal reflection in the prism and the thick
// sphere) and `liquid` (a liquid inside a tumbler: four interfaces before the backdrop; at
// 8 bounces it is 6% dark).
void expect_default_within_one_percent(const std::string& name) {
  const int bounces = PathTracerSettings{}.max_bounces;
  const Scene scene = builtin_scene(name);
  const Deficit d = deficit(render_luminance(scene, 64, 16, bounces),
                            render_luminance(scene, 64, 16, kConverged));
  std::printf("%s: %d bounces %.4f +- %.4f below %d (worst 16x16 block %.4f)\n", name.c_str(),
              bounces, d.deficit, d.std_error, kConverged, d.worst_block);
  EXPECT_LT(d.deficit, 0.01) << name << ": +- " << d.std_error;
}

TEST(DefaultBounces, GlassSceneWithinOnePercentOfConverged) {
  expect_default_within_one_percent("glass");
}

TEST(DefaultBounces, LiquidSceneWithinOnePercentOfConverged) {
  expect_default_within_one_percent("liquid");
}

}  // namespace
}  // namespace pbrkit::test
