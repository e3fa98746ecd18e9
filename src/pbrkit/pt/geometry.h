#pragma once
// The path tracer's view of a Scene: Embree 3 geometry plus the world-space vertex data
// needed to shade a hit.
//
// Instances are flattened: every instance becomes its own world-space triangle geometry
// (geomID = instance index) rather than an Embree instance of a shared mesh. The scenes
// this toolkit renders are small (at most a few million triangles) and rarely instance a
// mesh many times, so flattening costs little memory and buys a single BVH level (no
// per-ray instance transform, better SAH over the whole scene), and shading data is
// already in world space.
#include <cstdint>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

/// Embree ray masks: opaque geometry answers every ray; geometry with alpha (MASK, or
/// BLEND with alpha < 1) is skipped by the fast any-hit shadow query and handled by a
/// transmittance loop instead.
inline constexpr unsigned kMaskOpaque = 1u;
inline constexpr unsigned kMaskAlpha = 2u;

/// One instance in world space.
struct WorldMesh {
  const Mesh* mesh = nullptr;
  const Material* material = nullptr;
  std::vector<glm::vec3> positions;  ///< world space (+1 padding element for Embree)
  std::vector<glm::vec3> normals;    ///< world space, unit (may be empty)
  std::vector<glm::vec4> tangents;   ///< world space xyz + handedness (may be empty)
  bool has_alpha = false;            ///< needs the alpha test / stochastic transparency
  bool emissive = false;
};

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
  std::uint32_t geom = 0, prim = 0;
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
  explicit SceneGeometry(const Scene& scene);
  ~SceneGeometry();
  SceneGeometry(const SceneGeometry&) = delete;
  SceneGeometry& operator=(const SceneGeometry&) = delete;

  /// Closest hit along o + t d, t in (0, tfar), of geometry selected by `mask`.
  /// Returns false on a miss; fills geom/prim/t and barycentrics u, v.
  bool intersect(glm::vec3 o, glm::vec3 d, float tfar, unsigned mask, std::uint32_t& geom,
                 std::uint32_t& prim, float& t, float& u, float& v) const;
  /// What intersect() returns, for a ray of a packet: geom = kNoHit on a miss.
  struct PacketHit {
    std::uint32_t geom, prim;
    float t, u, v;
  };
  static constexpr std::uint32_t kNoHit = RTC_INVALID_GEOMETRY_ID;
  static constexpr int kPacketSize = 16;
  /// Closest hits of kPacketSize rays, t in (0, inf), all geometry, through Embree's
  /// packet traversal (rtcIntersect16: about 2.5x the single-ray rate for coherent rays,
  /// ../shared/PLATFORM.md section 4). A lane's result may depend on the whole packet
  /// (the order in which nodes are visited decides between hits at exactly equal t), so
  /// a caller that needs reproducible results must always trace the same packets.
  void intersect_packet(const glm::vec3* origins, const glm::vec3* directions,
                        PacketHit* hits) const;
  /// Any opaque hit in (0, tfar)?
  bool occluded(glm::vec3 o, glm::vec3 d, float tfar) const;
  /// Starts loading the vertex data resolve(geom, prim, ...) will read (for a batch of
  /// hits, so that their cache misses overlap).
  void prefetch(std::uint32_t geom, std::uint32_t prim) const {
    const WorldMesh& wm = meshes_[geom];
    const std::uint32_t* idx = wm.mesh->indices.data() + 3 * std::size_t(prim);
    for (int k = 0; k < 3; ++k) {
      __builtin_prefetch(wm.positions.data() + idx[k]);
      if (!wm.normals.empty()) __builtin_prefetch(wm.normals.data() + idx[k]);
    }
  }
  /// Shading data of a hit.
  SurfaceHit resolve(std::uint32_t geom, std::uint32_t prim, float t, float u, float v) const;

  /// Reports every later query to `observer` (nullptr: none).
  void observe(RayObserver* observer) { observer_ = observer; }

  const std::vector<WorldMesh>& meshes() const { return meshes_; }
  bool has_alpha() const { return has_alpha_; }
  const Bounds& bounds() const { return bounds_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene rtc_scene_ = nullptr;
  std::vector<WorldMesh> meshes_;
  RayObserver* observer_ = nullptr;
  bool has_alpha_ = false;
  Bounds bounds_;
};

}  // namespace pbrkit
