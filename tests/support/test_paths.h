#pragma once
// Where tests find their data, the shared assets, the pbrkit binary and scratch space.
#include <filesystem>
#include <string>

namespace pbrkit::test {

/// tests/data/<name>
std::filesystem::path test_data(const std::string& name);
/// tests/data/assets/<name>: the project's copy of its shared third-party assets (HDRIs
/// and glTF models, with their licences in tests/data/assets/LICENSES.md)
std::filesystem::path shared_asset(const std::string& name);
/// The built pbrkit executable.
std::filesystem::path cli_path();
/// A fresh, empty directory unique to the calling test (removed at process exit is not
/// guaranteed; it lives under the system temp dir).
std::filesystem::path scratch_dir();

/// Runs a shell command; returns its exit status and puts stdout+stderr into `output`.
int run_command(const std::string& command, std::string* output = nullptr);

/// Runs the Khronos glTF-Validator (tools/gltf-validator, installed by scripts/setup) over
/// a .glb/.gltf file. Returns "" when it reports no error and no warning, otherwise its
/// report (or why it could not run), so a test writes EXPECT_EQ(validate_gltf(p), "").
std::string validate_gltf(const std::filesystem::path& path);

}  // namespace pbrkit::test
