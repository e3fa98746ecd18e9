#pragma once
// The glTF 2.0 loader behind load_scene (internal to the scene module). The work is in
// this folder: loader.cpp runs the steps in order, one file per concept.
#include <filesystem>

#include "pbrkit/scene/load.h"

namespace pbrkit {

/// Loads a .gltf or .glb file (see load_scene for the contract).
Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options);

/// The same for a file's bytes already in memory (used by the fuzz target): `name` is
/// used in messages and its folder resolves relative URIs.
Scene load_gltf_from_memory(std::string bytes, const std::filesystem::path& name,
                            const LoadOptions& options);

}  // namespace pbrkit
