#pragma once
// One glTF file's load: the state its steps share. load() (loader.cpp) runs the steps in
// order; each step is defined in the file of this folder named beside its declaration.
// Private to src/pbrkit/scene/gltf/.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>  // every step formats its messages
#include <tiny_gltf.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/pose.h"

namespace pbrkit::gltf {

using nlohmann::json;

// Image files (external or data: URIs) larger than this are refused before they are read.
inline constexpr std::size_t kMaxImageFileBytes = std::size_t(1) << 30;

class Loader {
 public:
  Loader(std::filesystem::path path, const LoadOptions& options)
      : path_(std::move(path)), file_(path_.string()), options_(options) {}
  /// Loads from bytes already in memory; `path` names them and its folder resolves URIs.
  Loader(std::string bytes, std::filesystem::path path, const LoadOptions& options)
      : path_(std::move(path)),
        file_(path_.string()),
        options_(options),
        bytes_(std::move(bytes)),
        preloaded_(true) {}

  Scene load();

 private:
  // validation.cpp: messages name the file and the JSON path of the bad element.
  [[noreturn]] void error(const std::string& where, const std::string& what) const;
  void warning(const std::string& message);
  // LoadOptions::progress, when given.
  // False once LoadOptions::progress asked to stop (util/progress.h).
  bool report_progress(double fraction, const std::string& detail) const {
    return !options_.progress || options_.progress(fraction, detail);
  }

  // file_access.cpp: the file's bytes, the GLB container, tinygltf behind our callbacks.
  void read_container();
  void rebuild_glb();
  void parse_model();
  void read_image_buffer_views();

  // validation.cpp: the JSON and the sizes in it, checked before anything trusts them.
  json parse_json() const;
  void check_json(const json& root);
  void check_uris(const json& root);
  void check_buffers() const;
  void check_buffer_views();

  // meshopt.cpp: EXT_meshopt_compression.
  bool prepare_meshopt_fallbacks(json& root);
  void size_meshopt_fallbacks();
  void decode_meshopt_views();

  // draco.cpp: KHR_draco_mesh_compression.
  bool drop_draco_indices(json& root) const;
  void decode_draco_primitives();

  // accessors.cpp: a view of an accessor's bytes after validation.
  struct AccessorView {
    const tinygltf::Accessor* accessor = nullptr;
    const unsigned char* data = nullptr;  // null: all zeros (sparse only)
    std::size_t stride = 0;
    int components = 0;
  };
  AccessorView accessor_view(int index, const std::string& where);
  std::vector<float> read_floats(int index, const std::string& where, int expected_components,
                                 bool allow_normalized_int);
  std::vector<std::uint32_t> read_indices(int index, const std::string& where);

  // meshes.cpp: one Mesh per primitive.
  std::vector<int> build_mesh(int mesh_index, const std::vector<double>& weights);
  // With `deform`, the primitive is a deforming mesh's: built at rest (no morph applied),
  // its morph targets and joint influences read into `deform` (skins.cpp).
  void build_primitive(int mesh_index, int prim_index, const std::vector<double>& weights,
                       std::vector<int>& out, DeformingMesh* deform = nullptr, int skin = -1);
  // A skinned or morph-animated node's own meshes, one DeformingMesh each.
  std::vector<int> build_deforming_mesh(int mesh_index, int node, int skin);
  // Mesh::closed for the primitives (scene meshes) built from one glTF mesh;
  // gltf_primitive[i] is the index in the glTF mesh of primitives[i]; `when` ends the
  // warning of an open volume (the variant active, for variants.cpp).
  void decide_closure(int mesh_index, const std::vector<int>& primitives,
                      const std::vector<int>& gltf_primitive, const std::string& when = "");
  // variants.cpp: KHR_materials_variants, the root's variants and every primitive's
  // mappings checked; then Mesh::variant_materials for the primitives of one glTF mesh.
  void read_variants(const json& root);
  void add_variant_materials(int mesh_index, const std::vector<int>& primitives,
                             const std::vector<int>& gltf_primitive);

  // materials.cpp: materials and their texture references.
  void build_materials();
  TextureRef texture_ref(int texture_index, int texcoord, const tinygltf::ExtensionMap& ext,
                         bool srgb, const std::string& where);
  // material_extensions.cpp: the KHR_materials_* extensions of one material, as the
  // material schema (material_schema.h) lists them, read from the JSON check_json kept
  // (tinygltf drops extension values that are not objects, and empty objects inside them,
  // so it cannot tell a wrong type from an absent value); then the warnings for
  // combinations the READMEs give no effect.
  void read_material_extensions(const json& extensions, const std::string& where, Material& m);
  void warn_ineffective_combinations(const json& extensions, const std::string& where,
                                     const Material& m);
  // The extension object `name` of a material's extensions, or null when absent (an error
  // when it is not an object).
  const json* extension_object(const json& extensions, const char* name,
                               const std::string& where) const;
  float finite_float(const json& v, const std::string& path) const;
  // One factor of the schema into `values` (left as they are when the JSON has none).
  void extension_values(const json& ext, const MaterialFactor& factor, const std::string& where,
                        float* values);
  float extension_factor(const json& ext, const char* name, float fallback, float lo, float hi,
                         const std::string& where);
  glm::vec3 extension_color(const json& ext, const char* name, glm::vec3 fallback, float lo,
                            float hi, const std::string& where);
  TextureRef extension_texture(const json& ext, const char* name, bool srgb,
                               const std::string& where, float* scale = nullptr);
  // textures.cpp: images decoded once per colour space, with their samplers.
  int texture_for(int texture_index, bool srgb, const std::string& where);

  // animations.cpp: every animation's samplers and channels, checked, into motion_.
  void read_animations();
  // animation_pointer.cpp: KHR_animation_pointer's pointers taken out of the JSON (tinygltf
  // requires a node in every channel target), then each resolved into the channel (a node's
  // property, or a PointerTarget; `width` its floats per key); false: not played (warned).
  bool prepare_animation_pointers(json& root);
  bool resolve_pointer(const std::string& pointer, const std::string& where, AnimationChannel& ch,
                       int& width);
  // skins.cpp: skins (joints, inverse bind matrices) into motion_; a deforming primitive's
  // morph targets and joint influences (`vertices` as the file has them).
  void read_skins();
  void read_deformation(const tinygltf::Primitive& prim,
                        const std::map<std::string, int>& attributes, const std::string& where,
                        std::size_t vertices, int skin, DeformingMesh& d);

  // nodes.cpp: the hierarchy, its transforms and mesh instances.
  void build_nodes();
  // The nodes' rest transforms and an order with parents first, into motion_.
  void keep_rest_pose(const std::vector<int>& parent);
  // visibility.cpp: KHR_node_visibility's `visible: false` into node_hidden_.
  void read_node_visibility(const json& root);
  glm::mat4 local_transform(int node) const;
  // instancing.cpp: EXT_mesh_gpu_instancing, one Instance per mesh primitive and per row
  // of the node's instance attributes.
  void add_gpu_instances(int node, const json& extension, const glm::mat4& world,
                         const std::vector<int>& meshes);
  // cameras.cpp, lights.cpp: what a node carries besides a mesh.
  void add_camera(int camera, const glm::mat4& world, const std::string& where);
  void add_light(const tinygltf::Value& extension, const glm::mat4& world,
                 const std::string& where);

  std::filesystem::path path_;
  std::string file_;
  LoadOptions options_;
  std::string bytes_;
  bool preloaded_ = false;
  bool is_glb_ = false;
  std::string json_text_;
  tinygltf::Model model_;
  Scene scene_;
  std::vector<json> material_extensions_;  // materials[i].extensions (or {}), from check_json
  std::map<int, json> node_instancing_;    // node -> its EXT_mesh_gpu_instancing, from check_json
  // KHR_materials_variants: (mesh, primitive) -> its mappings, by variant (closed unset).
  std::map<std::pair<int, int>, std::vector<VariantMaterial>> variant_mappings_;
  // KHR_node_visibility: nodes not drawn (their own `visible: false`; build_nodes hands it
  // down to the children as it walks).
  std::vector<char> node_hidden_;
  // What poses the scene (scene/pose.h), kept when the file has animations or skins.
  bool keep_motion_ = false;
  SceneMotion motion_;
  std::vector<char> weights_animated_;  // per node: an animation drives its morph weights
  std::map<std::pair<int, int>, std::string> animation_pointers_;  // (animation, channel)
  bool visibility_animated_ = false;  // a pointer animates a node's KHR_node_visibility
  std::map<std::pair<int, bool>, int> texture_cache_;
  std::size_t texture_bytes_ = 0;
  std::size_t triangles_ = 0;
  std::map<std::size_t, std::size_t> meshopt_fallbacks_;  // buffer -> real byteLength
  // Decoded Draco primitives: (mesh, primitive) -> attribute name -> accessor index of a
  // synthetic accessor appended to the model.
  std::map<std::pair<int, int>, std::pair<std::map<std::string, int>, int>> draco_;
};

}  // namespace pbrkit::gltf
