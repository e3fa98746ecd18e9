// glTF 2.0 loading through Debian's tinygltf, hardened for hostile files: the container
// (GLB header, JSON, URIs) is checked before tinygltf sees it, every file access goes
// through our own callbacks, and every index, offset and size in the parsed model is
// checked before it is used. Errors name the file and the JSON path of the bad element.
// This file is the order of the work; each step lives in the file named beside it.
#include "pbrkit/scene/gltf/load_gltf.h"

#include <memory>

#include "pbrkit/scene/gltf/loader.h"
#include "pbrkit/util/log.h"

namespace pbrkit {

namespace gltf {

Scene Loader::load() {
  scene_.source = file_;
  // The bytes and, for a .glb, its chunks: checked before any parser runs.
  read_container();  // file_access.cpp

  // The JSON, checked with nlohmann: types, version, extensions, URIs and their sizes.
  json root = parse_json();  // validation.cpp
  check_json(root);
  read_variants(root);                                      // variants.cpp
  read_node_visibility(root);                               // visibility.cpp
  bool modified = prepare_meshopt_fallbacks(root);          // meshopt.cpp
  modified = prepare_animation_pointers(root) || modified;  // animation_pointer.cpp
  check_uris(root);
  modified = drop_draco_indices(root) || modified;  // draco.cpp
  if (modified) {
    json_text_ = root.dump();
    if (is_glb_) rebuild_glb();  // file_access.cpp
  }

  // tinygltf parses the model; every file it reads goes through our callbacks.
  parse_model();              // file_access.cpp
  check_buffers();            // validation.cpp
  size_meshopt_fallbacks();   // meshopt.cpp
  check_buffer_views();       // validation.cpp
  read_image_buffer_views();  // file_access.cpp

  // Compressed data decoded into ordinary buffers and accessors.
  decode_meshopt_views();     // meshopt.cpp
  decode_draco_primitives();  // draco.cpp

  // Whether the scene can move (animations or skins): the loader then keeps what poses it.
  keep_motion_ = !model_.animations.empty() || !model_.skins.empty();
  weights_animated_.assign(model_.nodes.size(), 0);

  // The scene: materials (with their textures) first, since meshes generate tangents
  // for normal-mapped materials; then the nodes, which build meshes, cameras and lights.
  build_materials();  // materials.cpp, textures.cpp
  // Skins and animations, checked before the nodes use them (after the materials, which
  // KHR_animation_pointer channels may animate).
  if (keep_motion_) {
    read_skins();       // skins.cpp
    read_animations();  // animations.cpp, animation_pointer.cpp
  }
  build_nodes();  // nodes.cpp, instancing.cpp, meshes.cpp, accessors.cpp, cameras.cpp, lights.cpp
  scene_.node_count = model_.nodes.size();
  if (keep_motion_) {
    motion_.visibility_animated = visibility_animated_;
    const bool deforms = !motion_.deforming.empty() || visibility_animated_;
    scene_.motion = std::make_shared<const SceneMotion>(std::move(motion_));
    // The rest pose skins the skinned meshes, morphs the morphing ones by their default
    // weights and hides the invisible nodes of an animated visibility (pose.cpp); the other
    // nodes are where the walk put them.
    if (deforms) pose_scene(scene_, PoseTime{});
  }
  report_progress(
      1.0, fmt::format("{} nodes, {} instances", model_.nodes.size(), scene_.instances.size()));
  return std::move(scene_);
}

}  // namespace gltf

Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options) {
  return gltf::Loader(path, options).load();
}

Scene load_gltf_from_memory(std::string bytes, const std::filesystem::path& name,
                            const LoadOptions& options) {
  return gltf::Loader(std::move(bytes), name, options).load();
}

}  // namespace pbrkit
