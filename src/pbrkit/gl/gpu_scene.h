#pragma once
// Private to the OpenGL renderer (renderer.cpp): the scene on the GPU. Meshes become vertex
// arrays over one buffer per attribute plus an index buffer, glTF textures become float
// textures with the glTF sampler's filters and wraps, and the environment becomes its
// equirect texture and the IBL cubes; materials, instances and lights stay on the CPU,
// where the frame reads them to set uniforms.
#include <array>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "pbrkit/gl/ibl_maps.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit::gl {

struct GpuMesh {
  GLuint vao = 0;
  std::array<GLuint, 7> buffers{};  // 6 attributes + indices
  GLsizei index_count = 0;
  bool has_colors = false;
  bool closed = true;  ///< Mesh::closed: a volume needs a closed mesh, else it is thin walled
  int material = -1;
  /// The material's alphaMode as drawn: 0 opaque, 1 mask, 2 blend; BLEND without any
  /// alpha below 1 is drawn opaque (scene.h has_alpha).
  int alpha_mode = 0;
  glm::vec3 center{0.0f};
  glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};  ///< object-space bounding box
  /// The radius of the sphere the mesh's vertices lie on about `center` (within 3%), or 0
  /// when they do not (occluders.h: the proxy that stands in for it).
  float sphere_radius = 0.0f;
  /// The triangles' total area, object space (occluders.h: whether the bounding box can
  /// stand in for the mesh).
  float surface_area = 0.0f;
};

/// Instances that one glDrawElementsInstanced can draw: one mesh, one winding (mirrored
/// or not), their transforms at consecutive slots of GpuScene::instance_buffer.
struct InstanceRun {
  std::size_t first_slot = 0;
  std::size_t count = 0;
};

/// The bytes GpuScene::upload allocates for `scene`: its meshes' vertex and index buffers,
/// its textures' mip chains in the formats they are uploaded in, and the instance buffer.
/// With the deforming meshes' rest data (gpu_deformation.h), which the renderer uploads
/// beside.
struct GlSceneBytes {
  std::size_t vertices = 0, indices = 0, textures = 0, instances = 0, deforming = 0;
  std::size_t total() const { return vertices + indices + textures + instances + deforming; }
};
GlSceneBytes gl_scene_bytes(const Scene& scene);

/// A Scene's meshes and textures on the GPU, with the materials, instances and lights
/// that index them. Needs the current GL context for its whole life.
struct GpuScene {
  std::vector<GpuMesh> meshes;
  std::vector<GLuint> textures;
  /// Each texture's mean linear RGB (white for an empty one): the albedo of an opaque
  /// object's proxy (occluders.h's opaque_albedo).
  std::vector<glm::vec3> texture_means;
  std::vector<Material> materials;
  std::vector<Instance> instances;
  std::vector<Light> lights;
  /// Each instance's model matrix and normal matrix (the inverse transpose of its 3x3, in a
  /// mat4's columns), at its slot: instances of a run sit side by side, so the vertex
  /// shader finds an instance's matrices at uInstanceBase + gl_InstanceID.
  GLuint instance_buffer = 0;
  std::vector<std::size_t> slot_of;  ///< instance index -> slot
  std::vector<std::size_t> at_slot;  ///< slot -> instance index
  std::vector<InstanceRun> runs;     ///< the instances with a valid mesh, in slot order

  GpuScene() = default;
  ~GpuScene() { release(); }
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  /// Uploads `scene`, replacing what was there. Refuses (util/error.h), before anything is
  /// allocated or released (the scene uploaded before stays), a scene whose buffers and
  /// textures (gl_scene_bytes) exceed `memory_limit` bytes; 0: on a software rasteriser,
  /// whose buffers are this process's memory, what the process may still allocate
  /// (util/available_memory.h) less what its frame needs, and no limit on a GPU. A GPU that
  /// runs out (GL_OUT_OF_MEMORY) is reported with the figures after the upload, which is
  /// then released (the GpuScene left empty).
  void upload(const Scene& scene, std::size_t memory_limit = 0);
  /// Deletes the GL objects and forgets the scene (materials, instances, runs): empty.
  void release();
  /// The instance buffer, slots and runs of `instances` (upload() calls it).
  void upload_instances();
  /// The instances' transforms of a pose (`posed`: the scene's instances, moved): rewrites
  /// the instance buffer in place, or lays out the slots and runs again when an instance's
  /// winding flipped (a mirroring transform cannot share a run with the others).
  void update_instances(const std::vector<Instance>& posed);
  /// The mesh's material, or the glTF default material when it has none.
  const Material& material_of(const GpuMesh& mesh) const;
};

/// The environment's textures: the sharp equirect map (the background) and the IBL cubes
/// (1x1 black ones until maps are set), with the rotation and intensity each was made with.
struct GpuEnvironment {
  GLuint env_texture = 0;
  float env_rotation = 0.0f, env_intensity = 1.0f;
  bool has_env = false;
  GLuint specular_cube = 0, irradiance_cube = 0;
  GLuint sheen_cube = 0;  ///< the Charlie-prefiltered chain (IblMaps::sheen)
  int specular_levels = 1;
  int sheen_levels = 1;
  bool has_ibl = false;
  IblMaps ibl_params;  // rotation, intensity and SH (cubes are on the GPU)

  GpuEnvironment();
  ~GpuEnvironment();
  GpuEnvironment(const GpuEnvironment&) = delete;
  GpuEnvironment& operator=(const GpuEnvironment&) = delete;

  /// The equirect map of `env` (nullptr: none).
  void set_environment(const Environment* env);
  /// The cubes and SH of `maps` (nullptr: none).
  void set_ibl(const IblMaps* maps);
};

}  // namespace pbrkit::gl
