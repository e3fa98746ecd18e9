// Khronos' AnimatedMorphCube (the shared assets): its posed bounds at several times against
// an evaluation written here from the file itself (its accessors read from the .bin by
// hand, the LINEAR weights interpolated, the targets added, the node's TRS applied with the
// quaternion's rotation matrix written out), independent of the loader and the pose code.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/util/log.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

using json = nlohmann::json;

struct MorphCube {
  json gltf;
  std::string bin;
  MorphCube() {
    const auto dir = test::shared_asset("models/AnimatedMorphCube");
    std::ifstream(dir / "AnimatedMorphCube.gltf") >> gltf;
    std::ifstream b(dir / "AnimatedMorphCube.bin", std::ios::binary);
    bin.assign(std::istreambuf_iterator<char>(b), {});
  }
  // A tightly packed FLOAT accessor's values.
  std::vector<float> floats(int accessor) const {
    const json& a = gltf["accessors"][std::size_t(accessor)];
    const json& v = gltf["bufferViews"][a["bufferView"].get<std::size_t>()];
    const std::size_t offset = v.value("byteOffset", 0) + a.value("byteOffset", 0);
    const std::size_t per = a["type"] == "SCALAR" ? 1 : a["type"] == "VEC3" ? 3 : 4;
    std::vector<float> out(a["count"].get<std::size_t>() * per);
    std::memcpy(out.data(), bin.data() + offset, out.size() * 4);
    return out;
  }
};

TEST(AnimatedSample, MorphCubeBoundsFollowTheSpecification) {
  const MorphCube cube;
  const json& prim = cube.gltf["meshes"][0]["primitives"][0];
  const std::vector<float> base = cube.floats(prim["attributes"]["POSITION"].get<int>());
  const std::vector<float> d0 = cube.floats(prim["targets"][0]["POSITION"].get<int>());
  const std::vector<float> d1 = cube.floats(prim["targets"][1]["POSITION"].get<int>());
  const json& sampler = cube.gltf["animations"][0]["samplers"][0];
  ASSERT_EQ(sampler["interpolation"], "LINEAR");
  const std::vector<float> times = cube.floats(sampler["input"].get<int>());
  const std::vector<float> weights = cube.floats(sampler["output"].get<int>());
  const json& node = cube.gltf["nodes"][0];
  const double x = node["rotation"][0], y = node["rotation"][1], z = node["rotation"][2],
               w = node["rotation"][3], s = node["scale"][0];
  // Rotation matrix of a unit quaternion (row r, column c).
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  const double qx = x / n, qy = y / n, qz = z / n, qw = w / n;
  const double R[3][3] = {
      {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)},
      {2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)},
      {2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)}};

  LogSink previous = set_log_sink([](LogLevel, const std::string&) {});
  Scene scene =
      load_scene(test::shared_asset("models/AnimatedMorphCube/AnimatedMorphCube.gltf").string());
  set_log_sink(previous);
  ASSERT_TRUE(scene.motion);
  for (const float t : {0.0f, 0.6f, 1.31f, 2.1f, 3.333f, 4.19f, 9.0f}) {
    SCOPED_TRACE(t);
    // The weights at t: the key interval holding t, clamped outside the keys.
    double w0 = 0, w1 = 0;
    if (t <= times.front()) {
      w0 = weights[0];
      w1 = weights[1];
    } else if (t >= times.back()) {
      w0 = weights[weights.size() - 2];
      w1 = weights.back();
    } else {
      std::size_t k = 0;
      while (times[k + 1] <= t) ++k;
      const double u = (t - times[k]) / (times[k + 1] - times[k]);
      w0 = (1 - u) * weights[2 * k] + u * weights[2 * k + 2];
      w1 = (1 - u) * weights[2 * k + 1] + u * weights[2 * k + 3];
    }
    double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
    for (std::size_t v = 0; v < base.size() / 3; ++v) {
      double p[3];
      for (int c = 0; c < 3; ++c)
        p[c] = s * (base[3 * v + c] + w0 * d0[3 * v + c] + w1 * d1[3 * v + c]);
      for (int r = 0; r < 3; ++r) {
        const double q = R[r][0] * p[0] + R[r][1] * p[1] + R[r][2] * p[2];
        lo[r] = std::min(lo[r], q);
        hi[r] = std::max(hi[r], q);
      }
    }
    pose_scene(scene, {0, t});
    const Bounds b = scene.world_bounds();
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(b.min[c], lo[c], 1e-4) << c;
      EXPECT_NEAR(b.max[c], hi[c], 1e-4) << c;
    }
  }
  // The animation moves the cube: somewhere in it the bounds are not the rest pose's.
  pose_scene(scene, {});
  const Bounds rest = scene.world_bounds();
  float moved = 0.0f;
  for (const float t : {1.0f, 2.1f, 3.0f}) {
    pose_scene(scene, {0, t});
    const Bounds b = scene.world_bounds();
    for (int c = 0; c < 3; ++c)
      moved = std::max({moved, std::abs(b.min[c] - rest.min[c]), std::abs(b.max[c] - rest.max[c])});
  }
  EXPECT_GT(moved, 0.1f);
}

}  // namespace
}  // namespace pbrkit
