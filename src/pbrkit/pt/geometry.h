#pragma once
// The path tracer's view of a Scene: a two-level Embree 3 acceleration structure and the
// per-mesh data needed to shade a hit.
//
// Memory and build time follow unique triangles, not instanced ones: each mesh that a
// scene places more than once is built once, in its own Embree scene (its own BVH, over
// the Mesh's own vertex and index arrays), and each of its instances is an Embree
// instance (RTC_GEOMETRY_TYPE_INSTANCE) with its world matrix; Embree moves the ray into
// the mesh's space. Shading data (normals, tangents, UVs, colours) stays in object space,
// once per mesh, and resolve() takes a hit to world space with the instance's matrix
// (normals by its inverse transpose).
//
// A mesh placed once is flattened instead: its world-space positions are copied into the
// top level, beside the instances. That keeps one BVH level for such meshes (no ray
// transform, one SAH over all of them) and costs nothing an instance would have saved (the
// copy replaces the padded copy Embree's 16-byte vertex loads need anyway). Measured on the
// built-in `spheres` (49 meshes, each used once), the same rays trace about 18% faster
// flattened than with each mesh behind an instance (bench/instancing_bench.cpp `flatten`;
// docs/benchmarks_archive.md, "instanced geometry").
//
// Before anything is built the memory is estimated against what the system has: a scene
// that fits only with Embree's compact layout (BvhLayout) is built with it, one that fits
// with neither is refused with the figures.
//
// A hit names its instance (`geom`, the index in Scene::instances) and its triangle
// (`prim`, the index in the instance's mesh), whichever level it came from.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "pbrkit/scene/pose.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit {

/// Embree ray masks: opaque geometry answers every ray; geometry with alpha (MASK, or
/// BLEND with alpha < 1) is skipped by the fast any-hit shadow query and handled by a
/// transmittance loop instead.
inline constexpr unsigned kMaskOpaque = 1u;
inline constexpr unsigned kMaskAlpha = 2u;

/// Where emitters on moving geometry are sampled for next-event estimation (motion blur):
/// the shutter's centre. Hits still find such an emitter where it is at the path's time, so
/// a moving emitter's light is approximate; still ones are exact.
inline constexpr float kShutterCentre = 0.5f;

/// One instance: a mesh placed in the world.
struct WorldMesh {
  const Mesh* mesh = nullptr;
  const Material* material = nullptr;
  /// The positions resolve() reads (mesh->positions or a padded copy; world space when
  /// `flattened`, object space otherwise).
  const glm::vec3* positions = nullptr;
  glm::mat3 linear{1.0f};  ///< object to world, without the translation
  glm::vec3 translation{0.0f};
  /// |det| x linear^-T (the cofactor matrix times the sign of the determinant, defined for
  /// a singular transform too): maps an object-space normal to a world-space one of the
  /// same side, and an object-space cross product of two edges to the world one (times the
  /// sign of the determinant), whose length is twice the world-space area.
  glm::mat3 normal_matrix{1.0f};
  /// +1, or -1 for a mirroring transform (negative determinant): glTF's front faces are
  /// counter-clockwise in object space, so clockwise in world space after a mirror.
  float orientation = 1.0f;
  bool flattened = false;  ///< its triangles are in the top level, in world space
  bool has_alpha = false;  ///< needs the alpha test / stochastic transparency
  bool emissive = false;
  bool visible = true;  ///< false for a transform of rank 0 or 1 (no area, nothing to hit)
  /// Motion blur: index of its motion over the shutter (SceneGeometry), -1 when static. The
  /// fields above then hold the shutter's centre (what lights and areas use).
  int motion = -1;
};

/// How Embree lays out the BVHs' triangles.
enum class BvhLayout {
  kAuto,  ///< kFast where the scene fits `GeometryOptions::memory_limit` with it, else kCompact
  kFast,  ///< Embree's default: each leaf holds its triangles' vertices and edges
  /// RTC_SCENE_FLAG_COMPACT: leaves hold indices into the mesh's own vertex array, which
  /// Embree reads at each triangle test: less memory per triangle, slower rays (figures in
  /// geometry.cpp).
  kCompact,
};

/// What the geometry is built with.
struct GeometryOptions {
  /// Bytes the geometry and its BVH may use; 0: what the process may still allocate
  /// (util/available_memory.h: MemAvailable, and its cgroups' limits). A scene whose estimate
  /// exceeds it with every layout `layout` allows is refused before anything is built.
  std::size_t memory_limit = 0;
  BvhLayout layout = BvhLayout::kAuto;
  /// Meshes placed once go into the top level in world space (see above); false puts every
  /// mesh behind an instance (benchmarks compare both).
  bool flatten_single_use = true;
  /// Motion blur: the instances' motion over the shutter (scene/pose.h shutter_motion);
  /// null or nothing moving: a still scene. A moving instance is built with one Embree time
  /// step per motion step (a moving mesh's world vertices, or a rigid one's transforms),
  /// and rays carry a time in [0, 1] across the shutter.
  const ShutterMotion* motion = nullptr;
};

/// Memory of a SceneGeometry, in bytes.
struct GeometryMemory {
  std::size_t geometry = 0;  ///< vertex copies and per-instance records
  std::size_t bvh = 0;       ///< Embree's allocations (BVHs, its geometry objects)
  std::size_t bvh_peak = 0;  ///< the most Embree held at once (during the build)
  bool compact = false;      ///< built with BvhLayout::kCompact
};

/// The estimate a SceneGeometry is checked against before it is built (an upper bound of
/// what it allocates: `bvh` bounds Embree's peak; see geometry.cpp for the figures), for
/// the kCompact layout when `options.layout` says so and for kFast otherwise.
GeometryMemory estimate_geometry_memory(const Scene& scene, const GeometryOptions& options = {});

/// A ray hit resolved to shading data.
struct SurfaceHit {
  float t = 0.0f;
  glm::vec3 p{0.0f};        ///< from barycentrics (more accurate than o + t d)
  glm::vec3 ng{0.0f};       ///< geometric normal from the winding (CCW = front), unit
  glm::vec3 ns{0.0f};       ///< interpolated shading normal, unit (ng when absent)
  glm::vec4 tangent{0.0f};  ///< interpolated tangent (w: handedness); 0 when absent
  glm::vec2 uv[2]{};        ///< TEXCOORD_0 / TEXCOORD_1
  glm::vec4 color{1.0f};    ///< COLOR_0
  float area = 0.0f;        ///< world-space triangle area
  float uv_area[2]{};       ///< the triangle's area in TEXCOORD_0 / TEXCOORD_1 space
  /// Width of the ray's footprint across the surface, w / |n.d| (ray cones, for texture
  /// level of detail; set by the integrator). 0: textures are read at level 0.
  float footprint = 0.0f;
  float time = 0.0f;       ///< the ray's time across the shutter, [0, 1] (motion blur)
  std::uint32_t geom = 0;  ///< the instance (index in Scene::instances)
  std::uint32_t prim = 0;  ///< the triangle in the instance's mesh
};

/// Sees every ray query a SceneGeometry answers, from the render threads (concurrently).
/// For benchmarks: bench/path_bench.cpp records a render's rays and replays them through
/// Embree alone, which measures Embree's raw rate for exactly the renderer's mix of rays.
class RayObserver {
 public:
  virtual ~RayObserver() = default;
  virtual void packet(const glm::vec3* origins, const glm::vec3* directions) = 0;
  virtual void closest(glm::vec3 o, glm::vec3 d, float tfar, unsigned mask) = 0;
  virtual void occluded(glm::vec3 o, glm::vec3 d, float tfar) = 0;
};

class SceneGeometry {
 public:
  /// Builds the acceleration structure; fails (util/error.h) with the estimate and the
  /// limit when the scene would not fit in `options.memory_limit`.
  explicit SceneGeometry(const Scene& scene, const GeometryOptions& options = {});
  ~SceneGeometry();
  SceneGeometry(const SceneGeometry&) = delete;
  SceneGeometry& operator=(const SceneGeometry&) = delete;

  /// Closest hit along o + t d, t in (0, tfar), of geometry selected by `mask`.
  /// Returns false on a miss; fills geom (the instance), prim, t and barycentrics u, v.
  /// `time`: across the shutter, [0, 1] (motion blur; ignored by a still scene).
  bool intersect(glm::vec3 o, glm::vec3 d, float tfar, unsigned mask, std::uint32_t& geom,
                 std::uint32_t& prim, float& t, float& u, float& v, float time = 0.0f) const;
  /// What intersect() returns, for a ray of a packet: geom = kNoHit on a miss.
  struct PacketHit {
    std::uint32_t geom, prim;
    float t, u, v;
  };
  static constexpr std::uint32_t kNoHit = RTC_INVALID_GEOMETRY_ID;
  static constexpr int kPacketSize = 16;
  /// Closest hits of kPacketSize rays, t in (0, inf), all geometry, through Embree's
  /// packet interface (rtcIntersect16: with AVX-512 kernels about 2.5x the single-ray rate
  /// for coherent rays: 60.8 against 23.5 M camera rays/s, 2 threads, Embree 3.13.5 on a
  /// 2-vCPU AVX-512 Xeon VM; with the AVX2 kernels the device
  /// is limited to, see geometry.cpp, Embree has no 16-wide kernel and passes the packet to
  /// its ray-stream code). A lane's result may depend on the whole packet (the order in
  /// which nodes are visited decides between hits at exactly equal t), so a caller that
  /// needs reproducible results must always trace the same packets.
  void intersect_packet(const glm::vec3* origins, const glm::vec3* directions, PacketHit* hits,
                        const float* times = nullptr) const;
  /// Any opaque hit in (0, tfar)?
  bool occluded(glm::vec3 o, glm::vec3 d, float tfar, float time = 0.0f) const;
  /// Starts loading the vertex data resolve(geom, prim, ...) will read (for a batch of
  /// hits, so that their cache misses overlap).
  void prefetch(std::uint32_t geom, std::uint32_t prim) const {
    const WorldMesh& wm = meshes_[geom];
    const std::uint32_t* idx = wm.mesh->indices.data() + 3 * std::size_t(prim);
    for (int k = 0; k < 3; ++k) {
      __builtin_prefetch(wm.positions + idx[k]);
      if (!wm.mesh->normals.empty()) __builtin_prefetch(wm.mesh->normals.data() + idx[k]);
    }
  }
  /// Shading data of a hit, in world space (at `time` across the shutter: the hit's time).
  SurfaceHit resolve(std::uint32_t geom, std::uint32_t prim, float t, float u, float v,
                     float time = 0.0f) const;
  /// Whether anything moves during the shutter (rays need a time).
  bool moving() const { return !motions_.empty(); }
  /// World-space area of triangle `prim` of instance `geom`.
  float triangle_area(std::uint32_t geom, std::uint32_t prim) const;

  /// Reports every later query to `observer` (nullptr: none).
  void observe(RayObserver* observer) { observer_ = observer; }

  /// Per instance (indexed by `geom`).
  const std::vector<WorldMesh>& meshes() const { return meshes_; }
  /// What was built: the vertex copies and records, and Embree's allocations as measured.
  const GeometryMemory& memory() const { return memory_; }
  /// Meshes built once behind instances, and the instances that use them.
  std::size_t shared_meshes() const { return mesh_scenes_.size(); }
  std::size_t instanced() const { return instanced_; }
  bool has_alpha() const { return has_alpha_; }
  const Bounds& bounds() const { return bounds_; }

 private:
  // A moving instance over the shutter's steps: a rigid one's transforms, or a deforming
  // one's world-space vertices (padded for Embree) and normals.
  struct InstanceMotion {
    std::vector<glm::mat4> transforms;
    std::vector<std::vector<glm::vec3>> positions;
    std::vector<std::vector<glm::vec3>> normals;
  };
  SurfaceHit resolve_moving(std::uint32_t geom, std::uint32_t prim, float t, float u, float v,
                            float time) const;

  RTCDevice device_ = nullptr;
  std::vector<InstanceMotion> motions_;
  RTCScene rtc_scene_ = nullptr;
  std::vector<RTCScene> mesh_scenes_;  ///< one per shared mesh
  std::vector<WorldMesh> meshes_;
  std::vector<std::vector<glm::vec3>> position_copies_;  ///< padded or world-space positions
  GeometryMemory memory_;
  std::size_t instanced_ = 0;
  struct Monitor;  ///< counts Embree's allocations, refuses those past the limit
  std::unique_ptr<Monitor> monitor_;
  RayObserver* observer_ = nullptr;
  bool has_alpha_ = false;
  Bounds bounds_;
};

}  // namespace pbrkit
