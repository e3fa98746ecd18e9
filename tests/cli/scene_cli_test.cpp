// `pbrkit scene write`: every built-in scene, written as glTF, passes the Khronos
// glTF-Validator with no error and no warning (a file another tool rejects, or reads
// differently, breaks the promise that it renders the same scene).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

TEST(SceneCli, EveryBuiltinSceneWritesAValidGltf) {
  const fs::path dir = test::scratch_dir();
  std::string list;
  ASSERT_EQ(test::run_command(test::cli_path().string() + " scene list", &list), 0) << list;
  std::istringstream names(list);
  int count = 0;
  for (std::string name; std::getline(names, name);) {
    if (name.empty()) continue;
    const fs::path glb = dir / (name + ".glb");
    std::string log;
    ASSERT_EQ(test::run_command(
                  test::cli_path().string() + " scene write " + name + " " + glb.string(), &log),
              0)
        << log;
    EXPECT_EQ(test::validate_gltf(glb), "") << name;
    ++count;
  }
  EXPECT_GE(count, 10) << list;  // spheres, furnace, cornell and the 7 KHR_materials scenes
}

// --flatten-instances: the same field with no EXT_mesh_gpu_instancing anywhere in the file
// (Blender 3.4 refuses a file that requires it) and still valid.
TEST(SceneCli, FlattenInstancesWritesNoInstancingExtension) {
  const fs::path dir = test::scratch_dir();
  const fs::path instanced = dir / "instances_cli.glb", flat = dir / "instances_cli_flat.glb";
  std::string log;
  ASSERT_EQ(test::run_command(
                test::cli_path().string() + " scene write instances " + instanced.string(), &log),
            0)
      << log;
  ASSERT_EQ(test::run_command(test::cli_path().string() + " scene write instances " +
                                  flat.string() + " --flatten-instances",
                              &log),
            0)
      << log;
  EXPECT_EQ(test::validate_gltf(flat), "");
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_NE(bytes(instanced).find("EXT_mesh_gpu_instancing"), std::string::npos);
  EXPECT_EQ(bytes(flat).find("EXT_mesh_gpu_instancing"), std::string::npos);
  // The same triangles in both (the command reports the count).
  EXPECT_NE(log.find("(1200002 triangles)"), std::string::npos) << log;
}

// The validator itself catches the defect this test exists for: a camera with zfar 0.
TEST(SceneCli, ValidatorRejectsAnInvalidFile) {
  const fs::path file = test::scratch_dir() / "bad.gltf";
  std::ofstream(file) << R"({"asset": {"version": "2.0"},
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 0.0}}]})";
  const std::string report = test::validate_gltf(file);
  EXPECT_NE(report.find("/cameras/0/perspective/zfar"), std::string::npos) << report;
}

}  // namespace
}  // namespace pbrkit
