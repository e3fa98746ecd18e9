#pragma once
// Private to the OpenGL renderer (renderer.cpp): clustered shading of the punctual lights
// (Olsson, Billeter & Assarsson 2012, "Clustered Deferred and Forward Shading"; Filament's
// froxels). The view frustum is cut into a grid of clusters: x/y tiles of the viewport in
// pixels, z slices exponential in view depth (Olsson et al. section 4.2: each slice as deep
// as it is wide, so the clusters stay near cubes). Each frame every light of limited range
// (KHR_lights_punctual `range`: its sphere of influence, beyond which it adds exactly 0) is
// binned into the clusters its sphere overlaps; a fragment shades its cluster's lights.
//
// Lights without a range and directional lights reach everything: they are not clipped at a
// threshold (that would change the image) but kept in a global list that every fragment
// shades. The clustered image is therefore the unclustered one up to the order of the sum.
// The binning is on the CPU: per light only the clusters within its sphere's screen and
// depth bounds are tested, each by sphere against the cluster's view-space box (Arvo 1990).
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "pbrkit/gl/render_settings.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit::gl {

/// A light's sphere of influence in world space; none for a light that reaches everything
/// (directional, or no `range`).
struct InfluenceSphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};
std::optional<InfluenceSphere> influence_sphere(const Light& light);

/// The view the clusters are cut from: the frame's matrices (scene/camera.h) and viewport.
struct ClusterView {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  int width = 1;
  int height = 1;
  float znear = 0.01f;
  std::optional<float> zfar;
};

/// The binned lights of one frame. Cluster (x, y, z) is number x + tiles.x * (y + tiles.y *
/// z); tile (x, y) covers pixels [x, x+1) * tile_pixels by [y, y+1) * tile_pixels with y up
/// from the bottom (gl_FragCoord's convention); slice z covers view depths
/// [z_lo * (z_hi / z_lo)^(z / slices), z_lo * (z_hi / z_lo)^((z + 1) / slices)).
struct LightClusters {
  glm::ivec3 grid{0};  ///< tiles x, tiles y, slices
  int tile_pixels = 32;
  bool perspective = true;
  float z_lo = 1.0f, z_hi = 2.0f;  ///< the view depths the slices span
  /// The lights every fragment shades (indices into the frame's lights, ascending).
  std::vector<std::uint32_t> global;
  /// Per cluster, (offset into `indices`, count); each cluster's indices ascending.
  std::vector<glm::uvec2> ranges;
  std::vector<std::uint32_t> indices;

  int cluster_count() const { return grid.x * grid.y * grid.z; }
  int cluster_index(int x, int y, int z) const { return x + grid.x * (y + grid.y * z); }
  /// The slice of view depth `depth` (clamped to the grid).
  int slice_of(float depth) const;
  /// The view-space depth where slice `z` begins (z = slices: where the last one ends).
  float slice_depth(int z) const;
  /// The lights of cluster `c` (indices into the frame's lights).
  std::span<const std::uint32_t> lights_of(int c) const {
    const glm::uvec2 r = ranges[std::size_t(c)];
    if (r.y == 0) return {};
    return {indices.data() + r.x, r.y};
  }
};

/// The view-space bounding box of cluster (x, y, z) of `clusters` cut from `view`
/// (view space looks down -Z: depth d is z = -d).
void cluster_bounds(const LightClusters& clusters, const ClusterView& view, int x, int y, int z,
                    glm::vec3& lo, glm::vec3& hi);

/// Bins `lights` (the frame's, in the order the shader reads them) into the clusters of
/// `view`. The spheres are enlarged by a relative 1e-4 so that a fragment whose cluster is
/// found from rounded coordinates (gl_FragCoord, its interpolated depth) still finds every
/// light that reaches it; a light that would overlap more than half the clusters goes to
/// the global list instead (the same work for the fragments, a shorter index list).
LightClusters bin_lights(std::span<const Light* const> lights, const ClusterView& view,
                         const LightClusterGrid& options = {});

/// A punctual light as pbr_fragment.glsl's PunctualLight reads it (std430).
struct GpuLight {
  glm::vec3 position{0.0f};
  float range = 0.0f;  ///< <= 0: infinite
  glm::vec3 direction{0.0f, 0.0f, -1.0f};
  std::int32_t type = 0;  ///< 0 point, 1 spot, 2 directional
  glm::vec3 radiance{0.0f};
  float unused0 = 0.0f;
  glm::vec2 cone{0.0f};  ///< spot: (scale, offset) of the glTF cone falloff
  glm::vec2 unused1{0.0f};
};
static_assert(sizeof(GpuLight) == 64);
GpuLight gpu_light(const Light& light);

/// An entry of the frame's listed lights (pbr_fragment.glsl's ListedLights, std430): what
/// the clustered loop reads of a light, its sphere of influence and all a point or
/// directional light needs besides; a spot light's direction and cone are read from its
/// GpuLight at `light`.
struct GpuListedLight {
  glm::vec3 position{0.0f};  ///< a directional light's direction
  float range = 0.0f;        ///< <= 0: reaches everything
  glm::vec3 radiance{0.0f};
  std::uint32_t light = 0;  ///< type << 30 | the light's index (GpuLight::type, below 2^30)
};
static_assert(sizeof(GpuListedLight) == 32);
GpuListedLight gpu_listed_light(const GpuLight& light, std::uint32_t index);

/// The frame's light buffers on the GPU: the lights, the cluster ranges, and the listed
/// lights, one GpuListedLight per entry of the global list and then of each cluster's list
/// (the ranges' offsets are past the global ones). Needs the current GL context for its
/// whole life.
class GpuLightBuffers {
 public:
  GpuLightBuffers();
  ~GpuLightBuffers();
  GpuLightBuffers(const GpuLightBuffers&) = delete;
  GpuLightBuffers& operator=(const GpuLightBuffers&) = delete;

  /// Uploads `lights` and, when given, their clusters; binds the buffers.
  void upload(std::span<const Light* const> lights, const LightClusters* clusters);

 private:
  GLuint lights_ = 0, ranges_ = 0, listed_ = 0;
};

}  // namespace pbrkit::gl
