// util/progress.h's rule for the bake: a progress callback that returns false stops it,
// and the bake returns what it has (BakeResult::interrupted): the stages finished before
// the stop, of the specular and sheen chains the levels finished, each equal to a
// complete bake's, and the stages not reached left empty.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pbrkit/ibl/bake.h"

namespace pbrkit {
namespace {

// A map whose levels differ from one another (a smooth pattern over the sphere).
Environment patterned() {
  Environment env;
  env.map = Image(64, 32, 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      env.map.set_rgb(x, y,
                      glm::vec3(1.0f + std::sin(0.3f * float(x)), 1.0f + std::cos(0.4f * float(y)),
                                0.5f + 0.01f * float(x + y)));
  env.source = "patterned";
  return env;
}

BakeOptions small_bake() {
  BakeOptions o;
  o.face_size = 32;
  o.samples = 64;
  o.irradiance_size = 8;
  o.lut_size = 16;
  return o;
}

// The levels of `part` are the first levels of `full`, texel for texel.
void expect_prefix(const Cubemap& part, const Cubemap& full) {
  ASSERT_LE(part.mips.size(), full.mips.size());
  for (std::size_t m = 0; m < part.mips.size(); ++m)
    for (std::size_t f = 0; f < 6; ++f) EXPECT_EQ(part.mips[m][f].data, full.mips[m][f].data) << m;
}

TEST(BakeInterruption, AStoppedBakeReturnsTheStagesAndLevelsItFinished) {
  const Environment env = patterned();
  const BakeOptions o = small_bake();
  const BakeResult full = bake_environment(env, o);
  EXPECT_FALSE(full.interrupted);
  ASSERT_GT(full.specular.mips.size(), 2u);

  // Stopped at the first report (after the cube): the cube, nothing else.
  const BakeResult cube_only =
      bake_environment(env, o, [](double, const std::string&) { return false; });
  EXPECT_TRUE(cube_only.interrupted);
  expect_prefix(cube_only.environment, full.environment);
  EXPECT_EQ(cube_only.environment.mips.size(), full.environment.mips.size());
  EXPECT_TRUE(cube_only.specular.mips.empty());
  EXPECT_TRUE(cube_only.irradiance.mips.empty());
  EXPECT_TRUE(cube_only.sheen.mips.empty());
  EXPECT_TRUE(cube_only.lut.data.empty());

  // Stopped inside the specular stage: the levels it finished (level 0, the mirror, at
  // least), not all of them, and no later stage.
  const BakeResult in_specular = bake_environment(
      env, o, [](double, const std::string& stage) { return stage != "specular"; });
  EXPECT_TRUE(in_specular.interrupted);
  EXPECT_GE(in_specular.specular.mips.size(), 1u);
  EXPECT_LT(in_specular.specular.mips.size(), full.specular.mips.size());
  expect_prefix(in_specular.specular, full.specular);
  EXPECT_TRUE(in_specular.irradiance.mips.empty());
  EXPECT_TRUE(in_specular.sheen.mips.empty());

  // Stopped inside the sheen stage: every earlier stage complete, the sheen levels done.
  const BakeResult in_sheen =
      bake_environment(env, o, [](double, const std::string& stage) { return stage != "sheen"; });
  EXPECT_TRUE(in_sheen.interrupted);
  EXPECT_EQ(in_sheen.specular.mips.size(), full.specular.mips.size());
  expect_prefix(in_sheen.specular, full.specular);
  expect_prefix(in_sheen.irradiance, full.irradiance);
  EXPECT_EQ(in_sheen.lut.data, full.lut.data);
  EXPECT_LT(in_sheen.sheen.mips.size(), full.sheen.mips.size());
  expect_prefix(in_sheen.sheen, full.sheen);
  EXPECT_TRUE(in_sheen.sheen_lut.data.empty());
}

}  // namespace
}  // namespace pbrkit
