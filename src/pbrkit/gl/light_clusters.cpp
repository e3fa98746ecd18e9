#include "pbrkit/gl/light_clusters.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pbrkit/gl/surface_bindings.h"
#include "pbrkit/util/error.h"

namespace pbrkit::gl {

std::optional<InfluenceSphere> influence_sphere(const Light& light) {
  // A range beyond 1e18 m windows nothing a float can tell apart from no range (and would
  // overflow the depth bounds): global too, which is exact either way.
  if (light.type == Light::Type::kDirectional || !light.range || !(*light.range > 0.0f) ||
      !(*light.range < 1e18f))
    return std::nullopt;
  return InfluenceSphere{light.position, *light.range};
}

int LightClusters::slice_of(float depth) const {
  if (!(depth > z_lo)) return 0;
  // Olsson et al. eq. 3: k = floor(log(z / near) / log(1 + 2 tan(theta) / S_y)), here with
  // the ratio chosen so that `slices` slices span [z_lo, z_hi] exactly.
  const float k = std::floor(std::log(depth / z_lo) * float(grid.z) / std::log(z_hi / z_lo));
  return int(std::clamp(k, 0.0f, float(grid.z - 1)));
}

float LightClusters::slice_depth(int z) const {
  if (z <= 0) return z_lo;
  if (z >= grid.z) return z_hi;
  return z_lo * std::pow(z_hi / z_lo, float(z) / float(grid.z));
}

namespace {

// Tile edge i of `pixels` pixels in tiles of `tile`, in view space at unit depth (the
// perspective projection of scene/camera.h: x = ndc * d / P00, symmetric, no off-centre
// terms) or at any depth (orthographic: x = ndc / P00); `p` is P00 or P11.
float tile_edge(int i, int tile, int pixels, float p) {
  return (2.0f * std::min(float(i) * float(tile), float(pixels)) / float(pixels) - 1.0f) / p;
}

// The view-space box between tile edges (x0, x1) x (y0, y1) (tile_edge) and view depths d0
// and d1.
void tile_box(bool perspective, float x0, float x1, float y0, float y1, float d0, float d1,
              glm::vec3& lo, glm::vec3& hi) {
  const float s0 = perspective ? d0 : 1.0f, s1 = perspective ? d1 : 1.0f;
  lo = glm::vec3(std::min(x0 * s0, x0 * s1), std::min(y0 * s0, y0 * s1), -d1);
  hi = glm::vec3(std::max(x1 * s0, x1 * s1), std::max(y1 * s0, y1 * s1), -d0);
}

}  // namespace

void cluster_bounds(const LightClusters& clusters, const ClusterView& view, int x, int y, int z,
                    glm::vec3& lo, glm::vec3& hi) {
  const int t = clusters.tile_pixels;
  const float px = view.projection[0][0], py = view.projection[1][1];
  tile_box(clusters.perspective, tile_edge(x, t, view.width, px),
           tile_edge(x + 1, t, view.width, px), tile_edge(y, t, view.height, py),
           tile_edge(y + 1, t, view.height, py), clusters.slice_depth(z),
           clusters.slice_depth(z + 1), lo, hi);
}

namespace {

// Arvo 1990, "A simple method for box-sphere intersection testing": the squared distance
// from the centre to the box against the squared radius.
bool sphere_overlaps_box(const glm::vec3& c, float r, const glm::vec3& lo, const glm::vec3& hi) {
  const glm::vec3 d = glm::max(lo - c, glm::vec3(0.0f)) + glm::max(c - hi, glm::vec3(0.0f));
  return glm::dot(d, d) <= r * r;
}

// The tile range [first, last] of the NDC interval [a, b] over `pixels` pixels (empty when
// first > last).
glm::ivec2 tile_range(float a, float b, int pixels, int tile, int tiles) {
  if (b < -1.0f || a > 1.0f) return {1, 0};
  const float p0 = (std::max(a, -1.0f) + 1.0f) * 0.5f * float(pixels);
  const float p1 = (std::min(b, 1.0f) + 1.0f) * 0.5f * float(pixels);
  return {std::clamp(int(std::floor(p0 / float(tile))), 0, tiles - 1),
          std::clamp(int(std::floor(p1 / float(tile))), 0, tiles - 1)};
}

}  // namespace

LightClusters bin_lights(std::span<const Light* const> lights, const ClusterView& view,
                         const LightClusterGrid& options) {
  if (options.tile_pixels < 1 || options.slices < 1 || options.slices > 1024)
    fail(
        "OpenGL: a light cluster grid of {}-pixel tiles and {} slices (tiles of at least 1 "
        "pixel, 1 to 1024 slices)",
        options.tile_pixels, options.slices);
  const std::int64_t cells =
      std::int64_t((view.width + options.tile_pixels - 1) / options.tile_pixels) *
      ((view.height + options.tile_pixels - 1) / options.tile_pixels) * options.slices;
  if (cells > (std::int64_t(1) << 24))
    fail(
        "OpenGL: a light cluster grid of {} clusters for {}x{} pixels ({}-pixel tiles, {} "
        "slices); at most 2^24",
        cells, view.width, view.height, options.tile_pixels, options.slices);
  LightClusters out;
  out.tile_pixels = options.tile_pixels;
  out.grid = glm::ivec3((view.width + out.tile_pixels - 1) / out.tile_pixels,
                        (view.height + out.tile_pixels - 1) / out.tile_pixels, options.slices);
  out.perspective = view.projection[3][3] == 0.0f;
  const float zfar = view.zfar.value_or(std::numeric_limits<float>::infinity());

  // The view-space spheres, enlarged against the rounding of the fragment's cluster lookup
  // (its view-space coordinates are off by a few ulps of their magnitude); lights that
  // reach no visible depth are dropped, and the slices span the depths the rest reach
  // (a fragment outside that span is outside every sphere: clamping it into the first or
  // last slice shades lights that add exactly 0).
  struct ViewSphere {
    glm::vec3 c;
    float r;
    std::uint32_t index;
  };
  std::vector<ViewSphere> spheres;
  spheres.reserve(lights.size());
  float lo = std::numeric_limits<float>::infinity(), hi = 0.0f;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const auto sphere = influence_sphere(*lights[i]);
    if (!sphere) {
      out.global.push_back(std::uint32_t(i));
      continue;
    }
    const glm::vec3 c = glm::vec3(view.view * glm::vec4(sphere->center, 1.0f));
    const float r = sphere->radius + 1e-4f * (sphere->radius + glm::length(c));
    const float depth = -c.z;
    if (depth + r <= view.znear || depth - r >= zfar) continue;
    lo = std::min(lo, depth - r);
    hi = std::max(hi, depth + r);
    spheres.push_back({c, r, std::uint32_t(i)});
  }
  out.z_lo = std::max(view.znear, lo);
  out.z_hi = std::min(zfar, hi);
  if (spheres.empty() || !(out.z_hi > out.z_lo * 1.001f)) out.z_hi = out.z_lo * 2.0f;
  if (spheres.empty()) out.z_lo = view.znear, out.z_hi = 2.0f * view.znear;

  const int count = out.cluster_count();
  std::vector<float> slice_depths(std::size_t(out.grid.z) + 1);
  for (int z = 0; z <= out.grid.z; ++z) slice_depths[std::size_t(z)] = out.slice_depth(z);
  const float px = view.projection[0][0], py = view.projection[1][1];
  std::vector<float> edge_x(std::size_t(out.grid.x) + 1), edge_y(std::size_t(out.grid.y) + 1);
  for (int x = 0; x <= out.grid.x; ++x)
    edge_x[std::size_t(x)] = tile_edge(x, out.tile_pixels, view.width, px);
  for (int y = 0; y <= out.grid.y; ++y)
    edge_y[std::size_t(y)] = tile_edge(y, out.tile_pixels, view.height, py);

  // (cluster, light) pairs in light order, then a counting sort by cluster (stable: each
  // cluster's lights stay ascending, the order the unclustered loop adds them in).
  std::vector<std::uint32_t> pair_cluster, pair_light;
  std::vector<std::uint32_t> global_too;
  for (const ViewSphere& s : spheres) {
    const float depth = -s.c.z;
    const int z0 = out.slice_of(std::max(depth - s.r, out.z_lo));
    const int z1 = out.slice_of(depth + s.r);
    const std::size_t first = pair_cluster.size();
    for (int z = z0; z <= z1; ++z) {
      // The sphere's part in the slice's depths [za, zb] lies in the box of half width rr
      // about its centre (rr: the radius of its section nearest the centre); its screen
      // bounds are the projections of that box's corners (x / d over a box in front of the
      // eye is extreme at a corner; the slices begin at z_lo >= znear > 0).
      const float za = std::max(slice_depths[std::size_t(z)], depth - s.r);
      const float zb = std::min(slice_depths[std::size_t(z) + 1], depth + s.r);
      const float dz = std::max({za - depth, depth - zb, 0.0f});
      const float rr = std::sqrt(std::max(s.r * s.r - dz * dz, 0.0f));
      glm::vec2 nlo(std::numeric_limits<float>::max()), nhi(-std::numeric_limits<float>::max());
      for (const float d : {za, zb})
        for (const float sx : {-rr, rr})
          for (const float sy : {-rr, rr}) {
            const float w = out.perspective ? std::max(d, 1e-30f) : 1.0f;
            const glm::vec2 n((s.c.x + sx) * px / w, (s.c.y + sy) * py / w);
            nlo = glm::min(nlo, n);
            nhi = glm::max(nhi, n);
          }
      const glm::ivec2 tx = tile_range(nlo.x, nhi.x, view.width, out.tile_pixels, out.grid.x);
      const glm::ivec2 ty = tile_range(nlo.y, nhi.y, view.height, out.tile_pixels, out.grid.y);
      for (int y = ty.x; y <= ty.y; ++y)
        for (int x = tx.x; x <= tx.y; ++x) {
          glm::vec3 lo, hi;
          tile_box(out.perspective, edge_x[std::size_t(x)], edge_x[std::size_t(x) + 1],
                   edge_y[std::size_t(y)], edge_y[std::size_t(y) + 1], slice_depths[std::size_t(z)],
                   slice_depths[std::size_t(z) + 1], lo, hi);
          if (!sphere_overlaps_box(s.c, s.r, lo, hi)) continue;
          const int c = out.cluster_index(x, y, z);
          pair_cluster.push_back(std::uint32_t(c));
          pair_light.push_back(s.index);
        }
    }
    if (pair_cluster.size() - first > std::size_t(count / 2)) {
      pair_cluster.resize(first);
      pair_light.resize(first);
      global_too.push_back(s.index);
    }
  }
  if (!global_too.empty()) {
    out.global.insert(out.global.end(), global_too.begin(), global_too.end());
    std::sort(out.global.begin(), out.global.end());
  }

  out.ranges.assign(std::size_t(count), glm::uvec2(0u));
  for (const std::uint32_t c : pair_cluster) ++out.ranges[c].y;
  std::uint32_t offset = 0;
  for (glm::uvec2& r : out.ranges) {
    r.x = offset;
    offset += r.y;
    r.y = 0;
  }
  out.indices.resize(pair_cluster.size());
  for (std::size_t k = 0; k < pair_cluster.size(); ++k) {
    glm::uvec2& r = out.ranges[pair_cluster[k]];
    out.indices[r.x + r.y++] = pair_light[k];
  }
  return out;
}

GpuLight gpu_light(const Light& l) {
  GpuLight g;
  g.position = l.position;
  // A directional light has no range (KHR_lights_punctual defines it for point and spot
  // lights only): 0, which the shader's range test passes wherever the light's position.
  g.range = l.type == Light::Type::kDirectional ? 0.0f : l.range.value_or(0.0f);
  g.direction = glm::normalize(l.direction);
  g.type = l.type == Light::Type::kPoint ? 0 : l.type == Light::Type::kSpot ? 1 : 2;
  g.radiance = l.color * l.intensity;
  // KHR_lights_punctual's spot falloff: scale = 1 / max(0.001, cos(inner) - cos(outer)).
  const float scale =
      1.0f / std::max(0.001f, std::cos(l.inner_cone_angle) - std::cos(l.outer_cone_angle));
  g.cone = glm::vec2(scale, -std::cos(l.outer_cone_angle) * scale);
  return g;
}

GpuListedLight gpu_listed_light(const GpuLight& light, std::uint32_t index) {
  // A directional light's direction where a point light's position is (its range, 0,
  // passes every range test).
  return GpuListedLight{light.type == 2 ? light.direction : light.position, light.range,
                        light.radiance, std::uint32_t(light.type) << 30 | index};
}

GpuLightBuffers::GpuLightBuffers() {
  glCreateBuffers(1, &lights_);
  glCreateBuffers(1, &ranges_);
  glCreateBuffers(1, &listed_);
}

GpuLightBuffers::~GpuLightBuffers() {
  glDeleteBuffers(1, &lights_);
  glDeleteBuffers(1, &ranges_);
  glDeleteBuffers(1, &listed_);
}

void GpuLightBuffers::upload(std::span<const Light* const> lights, const LightClusters* clusters) {
  if (lights.size() >= (std::size_t(1) << 30))
    fail("OpenGL: {} punctual lights; at most 2^30 - 1", lights.size());
  // Each buffer holds at least one element: a buffer of size 0 cannot be bound.
  std::vector<GpuLight> gpu(std::max<std::size_t>(1, lights.size()));
  for (std::size_t i = 0; i < lights.size(); ++i) gpu[i] = gpu_light(*lights[i]);
  std::vector<glm::uvec2> ranges(1, glm::uvec2(0u));
  std::vector<GpuListedLight> listed;
  if (clusters) {
    const auto global = std::uint32_t(clusters->global.size());
    listed.reserve(global + clusters->indices.size());
    for (const std::uint32_t i : clusters->global) listed.push_back(gpu_listed_light(gpu[i], i));
    for (const std::uint32_t i : clusters->indices) listed.push_back(gpu_listed_light(gpu[i], i));
    if (!clusters->ranges.empty()) ranges = clusters->ranges;
    for (glm::uvec2& r : ranges) r.x += global;
  }
  if (listed.empty()) listed.emplace_back();
  glNamedBufferData(lights_, GLsizeiptr(gpu.size() * sizeof(GpuLight)), gpu.data(), GL_STREAM_DRAW);
  glNamedBufferData(ranges_, GLsizeiptr(ranges.size() * sizeof(glm::uvec2)), ranges.data(),
                    GL_STREAM_DRAW);
  glNamedBufferData(listed_, GLsizeiptr(listed.size() * sizeof(GpuListedLight)), listed.data(),
                    GL_STREAM_DRAW);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightBufferBinding, lights_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kClusterRangeBufferBinding, ranges_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kListedLightBufferBinding, listed_);
}

}  // namespace pbrkit::gl
