#pragma once
// The glTF 2.0 loader behind load_scene (internal to the scene module).
#include <filesystem>

#include "pbrkit/scene/load.h"

namespace pbrkit {

/// Loads a .gltf or .glb file (see load_scene for the contract).
Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options);

}  // namespace pbrkit
