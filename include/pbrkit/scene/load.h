#pragma once
// Loading scenes: glTF 2.0 (.gltf / .glb) files and the built-in generated scenes.
#include <filesystem>
#include <string>
#include <vector>

#include "pbrkit/scene/scene.h"
#include "pbrkit/util/progress.h"

namespace pbrkit {

/// Limits applied while loading hostile files (each violation is an Error saying the limit).
struct SceneLimits {
  std::size_t max_image_pixels = std::size_t(1) << 26;         ///< 64 M pixels per image
  std::size_t max_total_texture_bytes = std::size_t(4) << 30;  ///< 4 GiB of decoded texels
  std::size_t max_buffer_bytes = std::size_t(2) << 30;         ///< 2 GiB per buffer
  std::size_t max_triangles = std::size_t(200) << 20;          ///< 200 M unique triangles
};

struct LoadOptions {
  SceneLimits limits;
  /// Called as a glTF file's nodes and instances are set up (a file of 10^5 nodes or 10^6
  /// instances takes seconds). When it returns false the load stops early and returns the
  /// nodes set up so far (Scene::interrupted, and a warning). None: no reports.
  ProgressCallback progress;
};

/// Loads a .gltf or .glb file, or a built-in scene when `path_or_name` is one of
/// builtin_scene_names() (or "builtin:<name>"). Throws pbrkit::Error naming the file and,
/// where possible, the JSON path of the bad element (e.g. "accessors[3].count").
Scene load_scene(const std::string& path_or_name, const LoadOptions& options = {});

/// The glTF extensions load_scene implements (any other one in extensionsRequired is an
/// Error; in extensionsUsed only, a warning).
std::vector<std::string> supported_gltf_extensions();

/// Names of the built-in scenes: "spheres" (7 x 7 metallic x roughness), "furnace" (a white
/// diffuse sphere), "cornell" (the Cornell box), and one comparison scene per
/// KHR_materials_* extension, "clearcoat", "sheen", "anisotropy", "iridescence", "specular",
/// "ior" and "unlit" (3 rows of 6 spheres: a control sphere without the extension, then a
/// sweep of one parameter; builtin/extension_rows.cpp says which), and the transmission scenes
/// "glass" (smooth, rough, tinted, thin-walled and dispersive glass before a checker
/// backdrop) and "liquid" (a tumbler with a liquid beside an empty one), and "instances" (a
/// 100 x 100 field of one rock mesh, some mirrored, some squashed, one glowing), and
/// "lights" (a closed room lit by emissive ceiling and wall panels and 82 point and spot
/// lights with a range; no environment: render it with none).
std::vector<std::string> builtin_scene_names();
bool is_builtin_scene(const std::string& name);
/// Generates a built-in scene (Error for an unknown name, listing the known ones).
Scene builtin_scene(const std::string& name);

/// How write_glb lays out the scene's nodes.
struct GltfWriteOptions {
  /// Every instance its own node (the nodes of one mesh share it by index: standard glTF
  /// 2.0, which every importer reads) instead of one node per repeated mesh with
  /// EXT_mesh_gpu_instancing, which some importers refuse when it is in
  /// extensionsRequired (Blender 3.4). The file grows by a node per instance.
  bool flatten_instances = false;
};

/// Writes a scene as a binary glTF (.glb), atomically, so other tools can render exactly
/// the same scene. A mesh placed more than once is written as one node with
/// EXT_mesh_gpu_instancing (required), unless `options.flatten_instances`.
void write_glb(const Scene& scene, const std::filesystem::path& path,
               const GltfWriteOptions& options = {});

}  // namespace pbrkit
