#pragma once
// Private to the OpenGL renderer (renderer.cpp): the scene's deforming meshes (scene/pose.h's
// DeformingMesh) posed in the vertex shader (shaders/deformation.glsl) rather than on the
// CPU. Each is uploaded once, at rest: its rest positions, normals and tangents, its joint
// influences, its flat triangles' corners and its morph targets' displacements, in one
// storage buffer read by gl_VertexID. A pose then uploads only every skin's joint matrices
// and every mesh's morph weights (and the renderer the instance transforms:
// GpuScene::update_instances), a few kilobytes where posing on the CPU re-uploads every
// deforming vertex.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "pbrkit/gl/program.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit::gl {

/// One deforming mesh on the GPU: its buffer and the uniforms deformation.glsl reads it by.
struct GpuDeformingMesh {
  int mesh = -1;  ///< Scene::meshes index
  GLuint buffer = 0;
  GLint vertex_count = 0;
  GLint influences = 0;   ///< per vertex, 0 when not skinned
  GLint targets = 0;      ///< morph targets
  GLint joint_base = -1;  ///< its skin's first joint matrix, -1 when not skinned
  GLint weight_base = 0;  ///< its first morph weight
  // Where the influences, the triangles' corners and the targets start (in 16-byte words).
  GLint influence_offset = 0, corner_offset = 0, target_offset = 0;
  GLint attributes = 0;  ///< bit 0: normals, bit 1: tangents
  bool flat_normals = false;
  /// The surface program's DEFORM (shader_permutations.h).
  int deform() const { return flat_normals ? 2 : 1; }
};

/// The bytes GpuDeformation::upload allocates for `scene`'s deforming meshes.
std::size_t gl_deformation_bytes(const Scene& scene);

/// The deforming meshes of a scene on the GPU and the pose they are drawn at. Needs the
/// current GL context for its whole life.
class GpuDeformation {
 public:
  GpuDeformation() = default;
  ~GpuDeformation() { release(); }
  GpuDeformation(const GpuDeformation&) = delete;
  GpuDeformation& operator=(const GpuDeformation&) = delete;

  /// Takes `scene`'s deforming meshes (none without Scene::motion), replacing what was
  /// there; they are drawn as uploaded until the first pose(), which uploads their rest data
  /// (so that a caller that poses on the CPU and sets every posed scene pays nothing here).
  void set_scene(const Scene& scene);
  /// Uploads the joint matrices and morph weights at the nodes' world transforms `world`
  /// and morph weights `weights` (posed_node_transforms, posed_morph_weights), and the
  /// first time the rest data: from now on the deforming meshes are drawn deformed.
  void pose(const std::vector<glm::mat4>& world, const std::vector<std::vector<float>>& weights);
  /// Deletes the buffers and forgets the motion: no mesh deforms.
  void release();
  /// Mesh `mesh`'s deformation when it is drawn deformed, else nullptr.
  const GpuDeformingMesh* of_mesh(int mesh) const;
  /// Binds the pose's buffers, which every deforming draw of a frame reads.
  void bind_pose() const;
  /// Binds `d`'s rest data and sets its uniforms on `p` (a program compiled with DEFORM
  /// d.deform()).
  static void bind(const Program& p, const GpuDeformingMesh& d);

 private:
  void upload_rest();

  std::shared_ptr<const SceneMotion> motion_;
  std::size_t mesh_count_ = 0;
  // The flat-normal meshes' triangles (their corners), by DeformingMesh; empty for the others.
  std::vector<std::vector<std::uint32_t>> flat_indices_;
  std::vector<GpuDeformingMesh> meshes_;
  std::vector<int> by_mesh_;      // Scene::meshes index -> meshes_ index, or -1
  std::vector<GLint> skin_base_;  // per skin, its first joint matrix
  GLuint joint_buffer_ = 0, weight_buffer_ = 0;
  std::size_t joint_count_ = 0, weight_count_ = 0;
  bool posed_ = false;
};

}  // namespace pbrkit::gl
