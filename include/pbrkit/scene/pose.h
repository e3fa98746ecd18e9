#pragma once
// A scene in motion: what a glTF file's node hierarchy, skins, morph targets and
// animations need to pose the flattened Scene at any time, and the posing itself.
// The loader keeps it (Scene::motion) only for files with animations or skins; posing
// rewrites the scene's instance transforms, the vertices of its deforming meshes, and its
// cameras and lights, exactly as the loader placed them at rest, so that both renderers
// draw the same pose from the same Scene.
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "pbrkit/scene/animation.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit {

struct Scene;
struct Bounds;
struct Instance;
struct Light;

/// A node's rest transform (glTF 2.0 section 3.5.2): a matrix, or translation, rotation
/// and scale, which animations replace property by property.
struct NodeRest {
  int parent = -1;
  bool has_matrix = false;  ///< a matrix node (not animatable: section 3.5.2)
  glm::mat4 matrix{1.0f};
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  std::vector<float> weights;  ///< the morph weights at rest (the node's, else its mesh's)
  bool visible = true;         ///< KHR_node_visibility's own `visible` (the ancestors' apply too)
};

/// glTF 2.0 section 3.7.3: joints (node indices) and their inverse bind matrices.
struct Skin {
  std::string name;
  std::vector<int> joints;
  std::vector<glm::mat4> inverse_bind;  ///< one per joint (identity when the file has none)
};

/// One morph target's displacements, per vertex of the mesh (empty when the target does
/// not move that attribute).
struct MorphTarget {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec3> tangents;
};

/// A mesh of the scene whose vertices move with the pose: skinned, or morphed by weights
/// that an animation drives. It is its own geometry, never shared with another instance.
struct DeformingMesh {
  int mesh = -1;      ///< Scene::meshes index
  int instance = -1;  ///< Scene::instances index of its only placement
  int node = -1;      ///< the node that places it (its weights; its skin)
  int skin = -1;      ///< SceneMotion::skins index, -1 when not skinned
  // The vertices before any morph or skin (the attributes the loader read, per vertex of
  // Scene::meshes[mesh]).
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;
  std::vector<MorphTarget> targets;
  /// Normals the loader generated flat (the file has none): recomputed from each pose's
  /// triangles, as glTF 2.0 section 3.7.2.1 asks of a file without normals.
  bool flat_normals = false;
  /// Joint influences per vertex (every JOINTS_n / WEIGHTS_n set): `influences` entries
  /// per vertex of indices into the skin's joints, and their weights, renormalised to sum
  /// to 1 (section 3.7.3.1).
  int influences = 0;
  std::vector<std::uint16_t> joints;
  std::vector<float> weights;
};

/// A property a KHR_animation_pointer channel animates, resolved from its JSON pointer
/// through the glTF 2.0 Asset Object Model: a material factor (the core material's, or any
/// of the material schema's extensions'), a texture's KHR_texture_transform, a punctual
/// light's or a camera's parameter.
struct PointerTarget {
  /// kVisibility: a node's KHR_node_visibility `visible` (index: the node; a value >= 0.5
  /// is true).
  enum class Kind { kMaterial, kTextureTransform, kLight, kCamera, kVisibility };
  std::string pointer;  ///< the JSON pointer, for messages
  Kind kind = Kind::kMaterial;
  int index = -1;  ///< the material, or the file's light or camera
  int components = 1;
  /// kMaterial: the value's components in a material (whose extension the loader added).
  float* (*material_value)(Material& m) = nullptr;
  /// kMaterial: the valid range of each component (the schema's), which poses clamp to.
  float min = -std::numeric_limits<float>::infinity();
  float max = std::numeric_limits<float>::infinity();
  /// kTextureTransform: the texture (its transform added by the loader when absent).
  TextureSlot slot = TextureSlot::kBaseColor;
  /// kTextureTransform: 0 offset, 1 rotation, 2 scale. kLight: 0 color, 1 intensity,
  /// 2 range, 3 spot.innerConeAngle, 4 spot.outerConeAngle. kCamera: 0 yfov, 1 znear,
  /// 2 zfar, 3 aspectRatio, 4 xmag, 5 ymag.
  int field = 0;
  std::vector<float> rest;  ///< the value at rest, restored where a pose does not animate it
};

/// An instance placed by its node's world transform times `offset` (EXT_mesh_gpu_instancing's
/// rows; identity for ordinary nodes).
struct NodePlacement {
  int instance = -1;
  int node = -1;
  glm::mat4 offset{1.0f};
};

struct SceneMotion {
  std::vector<NodeRest> nodes;
  std::vector<int> order;  ///< every posed node, parents before children
  std::vector<Animation> animations;
  std::vector<Skin> skins;
  std::vector<DeformingMesh> deforming;
  std::vector<NodePlacement> placements;  ///< instances that are not deforming meshes
  std::vector<int> camera_nodes;          ///< per Scene::cameras entry, its node
  std::vector<int> light_nodes;           ///< per Scene::lights entry, its node
  std::vector<int> camera_sources;        ///< per Scene::cameras entry, the file's camera
  std::vector<int> light_sources;         ///< per Scene::lights entry, the file's light
  std::vector<PointerTarget> pointers;    ///< KHR_animation_pointer targets
  /// An animation drives a node's visibility: the loader then kept every node's meshes and
  /// lights, and a pose hides those of invisible nodes (an instance by a zero transform, which
  /// no renderer draws or hits; a light by a zero intensity, restored from
  /// `light_rest_intensity` when visible).
  bool visibility_animated = false;
  std::vector<float> light_rest_intensity;  ///< per Scene::lights entry
};

/// Which animation at which time; `animation` -1 is the rest pose.
struct PoseTime {
  int animation = -1;
  float time = 0.0f;
};

/// The index of the animation named `name_or_index` (its name, or its index as a number):
/// Error listing the scene's animations when there is none such.
int find_animation(const Scene& scene, std::string_view name_or_index);

/// The nodes' world transforms at `pose` (SceneMotion::nodes' order).
std::vector<glm::mat4> posed_node_transforms(const SceneMotion& motion, const PoseTime& pose);

/// posed_node_transforms, checked as pose_scene checks a pose: throws pbrkit::Error (naming
/// `source`, the scene's file) for an animation out of range, a time that is not finite, or
/// a node transform that is not finite.
std::vector<glm::mat4> checked_node_transforms(const SceneMotion& motion, std::string_view source,
                                               const PoseTime& pose);

/// The nodes' morph weights at `pose` (per node: its rest weights unless a channel of the
/// animation drives them; glTF 2.0 section 3.7.2.2).
std::vector<std::vector<float>> posed_morph_weights(const SceneMotion& motion,
                                                    const PoseTime& pose);

/// A skin's joint matrices at the nodes' world transforms `world`: each joint's world
/// transform times its inverse bind matrix (glTF 2.0 section 3.7.3.1), the matrices that
/// linear blend skinning blends per vertex.
std::vector<glm::mat4> joint_matrices(const Skin& skin, const std::vector<glm::mat4>& world);

/// What a pose changes besides the deforming meshes' vertices and the cameras, at the
/// nodes' world transforms `world`: the instances' transforms (a skinned mesh's identity,
/// its vertices being in world space; another deforming mesh's its node's) and the lights'
/// positions and directions. pose_scene calls it; so does a renderer that deforms the
/// meshes itself (gl::Renderer::set_pose).
void place_instances_and_lights(const SceneMotion& motion, const std::vector<glm::mat4>& world,
                                std::vector<Instance>& instances, std::vector<Light>& lights);

/// A scene's motion over a camera shutter, for motion blur: the instances' transforms and
/// the deforming meshes' vertices at `steps` equally spaced times from the shutter's
/// opening to its closing (renderers interpolate linearly between steps, as Embree does).
struct ShutterMotion {
  int steps = 0;
  /// Per instance: `steps` transforms when it moves (empty when it does not).
  std::vector<std::vector<glm::mat4>> transforms;
  /// Per instance of a deforming mesh whose vertices move: `steps` arrays of its mesh's
  /// object-space positions and normals (empty otherwise).
  std::vector<std::vector<std::vector<glm::vec3>>> positions;
  std::vector<std::vector<std::vector<glm::vec3>>> normals;
  /// Whether anything moves.
  bool moving() const;
  /// Whether instance `i` moves (rigidly or by its vertices).
  bool moving(std::size_t i) const { return !transforms[i].empty() || !positions[i].empty(); }
};

/// The scene's motion at `steps` (>= 2) times over [open, close] of `animation` (seconds).
/// The scene itself is not changed. Throws pbrkit::Error for a scene without animations,
/// an animation out of range or a shutter that is not open < close.
ShutterMotion shutter_motion(const Scene& scene, int animation, float open, float close, int steps);

/// Poses `scene` (a no-op for a scene without motion). Throws pbrkit::Error for an
/// animation index out of range, or a pose that is not finite (naming the node).
void pose_scene(Scene& scene, const PoseTime& pose);

}  // namespace pbrkit
