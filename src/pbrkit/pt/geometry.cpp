#include "pbrkit/pt/geometry.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "pbrkit/util/available_memory.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit {

namespace {

// What Embree 3.13 allocates at RTC_BUILD_QUALITY_MEDIUM on an AVX2 machine, rounded up
// (docs/benchmarks_archive.md, "instanced geometry"; bench/instancing_bench.cpp): per triangle, the
// peak of a build as its memory monitor (rtcSetDeviceMemoryMonitorFunction) sees it, the BVH and
// the build's temporary arrays (about 104 bytes; 67 stay); per instance, its share of the top-level
// BVH (about 90 bytes by the monitor) and its geometry object and transform, which Embree allocates
// outside the monitor (about 300 more by the peak RSS of 10^6 instances).
constexpr double kBvhBytesPerTriangle = 128.0;
// The same with RTC_SCENE_FLAG_COMPACT (BvhLayout::kCompact), whose leaves index the mesh's
// vertices instead of copying them. By the monitor, its peak is 70-81 bytes per triangle on
// meshes of 5,696 to 194,432 triangles and 36-47 on meshes of 8 and 24 million, against
// the fast layout's 99-117; 35-47 stay after the build, against 65-71 (docs/benchmarks_archive.md,
// "Embree's compact layout for scenes that do not fit").
constexpr double kCompactBvhBytesPerTriangle = 88.0;
constexpr double kBvhBytesPerInstance = 640.0;
constexpr double kBvhBytesPerScene = 16384.0;  // an Embree scene's fixed cost

void embree_error(void* /*user*/, RTCError code, const char* message) {
  if (code == RTC_ERROR_NONE) return;
  warn("embree: {} (error {})", message ? message : "", int(code));
}

std::string format_bytes(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.2f} GB", bytes * 1e-9);
  if (bytes >= 1e6) return fmt::format("{:.1f} MB", bytes * 1e-6);
  return fmt::format("{:.1f} kB", bytes * 1e-3);
}

// Embree reads a vertex with a 16-byte load, so the buffer must extend 4 bytes past the
// last vec3 (rtcSetSharedGeometryBuffer's documentation).
bool padded(const std::vector<glm::vec3>& v) {
  return v.capacity() > v.size();
}

// The cofactor matrix det(L) L^-T, columns (b x c, c x a, a x b): no division, defined for
// a singular L too, and L a x L b = cofactor(L) (a x b).
glm::mat3 cofactor(const glm::mat3& L) {
  return glm::mat3(glm::cross(L[1], L[2]), glm::cross(L[2], L[0]), glm::cross(L[0], L[1]));
}

// How each instance is built: hidden (a transform of rank 0 or 1, which glTF's zero scales
// give, leaves no area), flattened (a mesh placed once, or a singular transform of rank 2,
// which Embree could not invert to move rays into the mesh: a flat mesh scaled to zero
// across its plane stays visible), or behind an Embree instance of its mesh's scene.
struct Plan {
  enum Kind : std::uint8_t { kHidden, kFlat, kShared };
  std::vector<Kind> kind;           // per instance
  std::vector<std::size_t> flat;    // per mesh: its flattened copies
  std::vector<std::size_t> shared;  // per mesh: its instances behind Embree instances
};

Plan plan(const Scene& scene, const GeometryOptions& options) {
  Plan p;
  p.kind.assign(scene.instances.size(), Plan::kHidden);
  p.flat.assign(scene.meshes.size(), 0);
  p.shared.assign(scene.meshes.size(), 0);
  std::vector<std::size_t> uses(scene.meshes.size(), 0);  // invertible placements
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    if (inst.mesh < 0 || inst.mesh >= int(scene.meshes.size()))
      fail("{}: instance {} refers to mesh {} (the scene has {})", scene.source, i, inst.mesh,
           scene.meshes.size());
    const glm::mat4& M = inst.transform;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(M[c][r]))
          fail("{}: instance {} (node {}) has a non-finite transform", scene.source, i, inst.node);
    const glm::mat3 L(M);
    if (cofactor(L) == glm::mat3(0.0f)) continue;  // rank <= 1: no triangle has an area
    if (glm::determinant(L) == 0.0f) {
      p.kind[i] = Plan::kFlat;
      continue;
    }
    p.kind[i] = Plan::kShared;
    ++uses[std::size_t(inst.mesh)];
  }
  const ShutterMotion* motion = options.motion;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const std::size_t m = std::size_t(scene.instances[i].mesh);
    // Motion blur: a rigidly moving instance stays behind an Embree instance (its transform
    // has time steps); one whose vertices move is flattened (its vertices have them).
    const bool rigid = motion && !motion->transforms[i].empty() && motion->positions[i].empty();
    const bool deforms = motion && !motion->positions[i].empty();
    if (p.kind[i] == Plan::kShared && options.flatten_single_use && uses[m] == 1 && !rigid)
      p.kind[i] = Plan::kFlat;
    if (p.kind[i] == Plan::kShared && deforms) p.kind[i] = Plan::kFlat;
    if (p.kind[i] == Plan::kFlat) ++p.flat[m];
    if (p.kind[i] == Plan::kShared) ++p.shared[m];
  }
  return p;
}

}  // namespace

GeometryMemory estimate_geometry_memory(const Scene& scene, const GeometryOptions& options) {
  const Plan p = plan(scene, options);
  const double per_triangle =
      options.layout == BvhLayout::kCompact ? kCompactBvhBytesPerTriangle : kBvhBytesPerTriangle;
  double geometry = double(sizeof(WorldMesh)) * double(scene.instances.size());
  double bvh = kBvhBytesPerScene;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const double triangles = double(mesh.triangle_count());
    const double copy = double(mesh.positions.size() + 1) * sizeof(glm::vec3);
    geometry += copy * double(p.flat[m]);
    bvh += per_triangle * triangles * double(p.flat[m]);
    if (p.shared[m] > 0) {
      if (!padded(mesh.positions)) geometry += copy;
      bvh +=
          kBvhBytesPerScene + per_triangle * triangles + kBvhBytesPerInstance * double(p.shared[m]);
    }
  }
  // Motion blur: a moving mesh's vertices and normals at every step, and a motion BVH
  // over the steps (bounded here as one BVH per step: Embree's motion BVHs are no larger).
  if (options.motion)
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
      const auto& steps = options.motion->positions[i];
      if (steps.empty()) continue;
      const Mesh& mesh = scene.meshes[std::size_t(scene.instances[i].mesh)];
      geometry +=
          2.0 * double(steps.size()) * double(mesh.positions.size() + 1) * sizeof(glm::vec3);
      bvh += per_triangle * double(mesh.triangle_count()) * double(steps.size() - 1);
    }
  return {std::size_t(geometry), std::size_t(bvh), std::size_t(bvh)};
}

// Embree calls the monitor from its build threads before each allocation (bytes > 0) and
// after each release (bytes < 0); returning false makes the allocation fail with
// RTC_ERROR_OUT_OF_MEMORY instead of letting the process be killed.
struct SceneGeometry::Monitor {
  std::atomic<std::int64_t> bytes{0};
  std::atomic<std::int64_t> peak{0};
  std::int64_t limit = std::numeric_limits<std::int64_t>::max();

  static bool callback(void* user, ssize_t bytes, bool /*post*/) {
    Monitor& m = *static_cast<Monitor*>(user);
    const std::int64_t now = m.bytes.fetch_add(bytes, std::memory_order_relaxed) + bytes;
    if (bytes > 0 && now > m.limit) {
      m.bytes.fetch_sub(bytes, std::memory_order_relaxed);
      return false;
    }
    std::int64_t seen = m.peak.load(std::memory_order_relaxed);
    while (now > seen && !m.peak.compare_exchange_weak(seen, now, std::memory_order_relaxed)) {
    }
    return true;
  }
};

SceneGeometry::SceneGeometry(const Scene& scene, const GeometryOptions& options)
    : monitor_(std::make_unique<Monitor>()) {
  // Refuse what cannot fit before anything is allocated; a scene that fits only with the
  // compact layout is built with it.
  const std::size_t limit = options.memory_limit > 0 ? options.memory_limit : available_memory();
  GeometryOptions chosen = options;
  if (chosen.layout == BvhLayout::kAuto) chosen.layout = BvhLayout::kFast;
  GeometryMemory estimate = estimate_geometry_memory(scene, chosen);
  const GeometryMemory fast = estimate;
  if (options.layout == BvhLayout::kAuto && estimate.geometry + estimate.bvh > limit) {
    chosen.layout = BvhLayout::kCompact;
    estimate = estimate_geometry_memory(scene, chosen);
  }
  std::size_t unique_triangles = 0;
  for (const Mesh& m : scene.meshes) unique_triangles += m.triangle_count();
  if (estimate.geometry + estimate.bvh > limit)
    fail(
        "{}: the path tracer's geometry needs an estimated {} (geometry {}, BVH {}{}; {} unique "
        "triangles in {} meshes, {} instances) but {} is available",
        scene.source, format_bytes(double(estimate.geometry + estimate.bvh)),
        format_bytes(double(estimate.geometry)), format_bytes(double(estimate.bvh)),
        chosen.layout == BvhLayout::kCompact ? " in Embree's compact layout" : "", unique_triangles,
        scene.meshes.size(), scene.instances.size(), format_bytes(double(limit)));
  memory_.compact = chosen.layout == BvhLayout::kCompact;
  if (memory_.compact && options.layout == BvhLayout::kAuto)
    note(
        "{}: the geometry would need an estimated {} with the fast BVH layout but {} is "
        "available; building Embree's compact layout ({}), whose rays are 10-17% slower",
        scene.source, format_bytes(double(fast.geometry + fast.bvh)), format_bytes(double(limit)),
        format_bytes(double(estimate.geometry + estimate.bvh)));
  const RTCSceneFlags scene_flags = memory_.compact ? RTC_SCENE_FLAG_COMPACT : RTC_SCENE_FLAG_NONE;
  monitor_->limit =
      std::int64_t(std::min<std::size_t>(limit - std::min(limit, estimate.geometry),
                                         std::size_t(std::numeric_limits<std::int64_t>::max())));

  // At most AVX2 kernels: on AVX-512 machines Embree 3 otherwise picks its AVX-512 ones,
  // which traced this path tracer's rays (single rays, incoherent after the first bounce)
  // more slowly on the development VM: 5-11% more samples per CPU second on the built-in
  // `spheres` with AVX2 (docs/benchmarks_archive.md, "spheres throughput"), although Embree then
  // has no 16-wide packet kernel and passes the camera packets to its ray-stream code. Machines
  // without AVX2 keep their best kernels (a maximum, not a choice).
  device_ = rtcNewDevice("max_isa=avx2");
  if (!device_)
    fail("{}: cannot create an Embree device (error {})", scene.source,
         int(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
  rtcSetDeviceMemoryMonitorFunction(device_, &Monitor::callback, monitor_.get());
  rtc_scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(rtc_scene_, scene_flags);
  // MEDIUM: about half the build time of HIGH for a few percent of trace speed (`spheres`:
  // HIGH traced at most 2% faster and doubled the build, 0.25 -> 0.52 CPU s;
  // docs/benchmarks_archive.md, "The remaining levers"); renders here are short enough for
  // build time to matter.
  rtcSetSceneBuildQuality(rtc_scene_, RTC_BUILD_QUALITY_MEDIUM);

  const Plan p = plan(scene, options);
  // Per mesh, once however many instances it has: the index check, has_alpha (which may
  // scan a texture), and, for a shared mesh, its Embree scene.
  std::vector<bool> mesh_alpha(scene.meshes.size());
  std::vector<int> mesh_scene(scene.meshes.size(), -1);
  std::vector<const glm::vec3*> mesh_positions(scene.meshes.size(), nullptr);
  std::vector<Bounds> mesh_bounds(scene.meshes.size());
  auto triangle_geometry = [&](const Mesh& mesh, const glm::vec3* positions, unsigned mask) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions, 0,
                               sizeof(glm::vec3), mesh.positions.size());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(),
                               0, 3 * sizeof(std::uint32_t), mesh.triangle_count());
    rtcSetGeometryMask(g, mask);
    rtcCommitGeometry(g);
    return g;
  };
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    if (p.flat[m] + p.shared[m] == 0) continue;
    const Mesh& mesh = scene.meshes[m];
    for (std::uint32_t idx : mesh.indices)
      if (idx >= mesh.positions.size())
        fail("{}: mesh '{}' has an index {} past its {} vertices", scene.source, mesh.name, idx,
             mesh.positions.size());
    // resolve() reads every attribute a mesh has at the triangle's indices.
    const std::size_t n = mesh.positions.size();
    for (std::size_t size : {mesh.normals.size(), mesh.tangents.size(), mesh.texcoords0.size(),
                             mesh.texcoords1.size(), mesh.colors0.size()})
      if (size != 0 && size != n)
        fail("{}: mesh '{}' has an attribute of {} elements for {} vertices", scene.source,
             mesh.name, size, n);
    mesh_alpha[m] = pbrkit::has_alpha(scene, mesh);
    if (p.shared[m] == 0) continue;
    const glm::vec3* positions = mesh.positions.data();
    if (!padded(mesh.positions)) {
      std::vector<glm::vec3>& copy = position_copies_.emplace_back();
      copy.reserve(mesh.positions.size() + 1);
      copy.assign(mesh.positions.begin(), mesh.positions.end());
      copy.push_back(glm::vec3(0.0f));
      positions = copy.data();
    }
    mesh_positions[m] = positions;
    for (const glm::vec3& q : mesh.positions) mesh_bounds[m].extend(q);
    RTCScene s = rtcNewScene(device_);
    rtcSetSceneFlags(s, scene_flags);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry g = triangle_geometry(mesh, positions, mesh_alpha[m] ? kMaskAlpha : kMaskOpaque);
    rtcAttachGeometryByID(s, g, 0);
    rtcReleaseGeometry(g);
    rtcCommitScene(s);
    mesh_scene[m] = int(mesh_scenes_.size());
    mesh_scenes_.push_back(s);
  }

  meshes_.resize(scene.instances.size());
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    const std::size_t m = std::size_t(inst.mesh);
    const Mesh& mesh = scene.meshes[m];
    WorldMesh& wm = meshes_[i];
    wm.mesh = &mesh;
    wm.material = &scene.material_of(mesh);
    wm.has_alpha = mesh_alpha[m];
    const glm::vec3 e = wm.material->emissive_factor * wm.material->emissive_strength;
    wm.emissive = e.x > 0.0f || e.y > 0.0f || e.z > 0.0f;
    wm.visible = p.kind[i] != Plan::kHidden;
    wm.positions = mesh.positions.data();
    if (!wm.visible) continue;
    has_alpha_ = has_alpha_ || wm.has_alpha;

    const glm::mat4& M = inst.transform;
    wm.linear = glm::mat3(M);
    wm.translation = glm::vec3(M[3]);
    wm.orientation = glm::determinant(wm.linear) < 0.0f ? -1.0f : 1.0f;
    wm.normal_matrix = wm.orientation * cofactor(wm.linear);
    const unsigned mask = wm.has_alpha ? kMaskAlpha : kMaskOpaque;
    const ShutterMotion* motion = options.motion;
    if (p.kind[i] == Plan::kFlat && motion && !motion->positions[i].empty()) {
      // A mesh whose vertices move: its world vertices and normals at every step.
      wm.flattened = true;
      wm.motion = int(motions_.size());
      InstanceMotion& mo = motions_.emplace_back();
      const auto& steps = motion->positions[i];
      const std::size_t count = steps.size();
      RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      rtcSetGeometryTimeStepCount(g, unsigned(count));
      mo.positions.resize(count);
      mo.normals.resize(count);
      for (std::size_t k = 0; k < count; ++k) {
        const glm::mat4 T = motion->transforms[i].empty() ? M : motion->transforms[i][k];
        const glm::mat3 L(T);
        const glm::mat3 N = (glm::determinant(L) < 0.0f ? -1.0f : 1.0f) * cofactor(L);
        std::vector<glm::vec3>& world = mo.positions[k];
        world.reserve(steps[k].size() + 1);
        for (const glm::vec3& q : steps[k]) {
          world.push_back(L * q + glm::vec3(T[3]));
          bounds_.extend(world.back());
        }
        world.push_back(glm::vec3(0.0f));  // Embree's 16-byte loads read past the last
        for (const glm::vec3& n : motion->normals[i][k]) {
          const glm::vec3 wn = N * n;
          const float len = glm::length(wn);
          mo.normals[k].push_back(len > 0.0f ? wn / len : glm::vec3(0, 0, 1));
        }
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, unsigned(k), RTC_FORMAT_FLOAT3,
                                   world.data(), 0, sizeof(glm::vec3), steps[k].size());
      }
      // The shutter's centre stands for the mesh where one position is needed (the light
      // samplers' triangles and areas).
      wm.positions = mo.positions[count / 2].data();
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(),
                                 0, 3 * sizeof(std::uint32_t), mesh.triangle_count());
      rtcSetGeometryMask(g, mask);
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(rtc_scene_, g, unsigned(i));
      rtcReleaseGeometry(g);
    } else if (p.kind[i] == Plan::kFlat) {
      wm.flattened = true;
      std::vector<glm::vec3>& world = position_copies_.emplace_back();
      world.reserve(mesh.positions.size() + 1);
      for (const glm::vec3& q : mesh.positions) {
        world.push_back(wm.linear * q + wm.translation);
        bounds_.extend(world.back());
      }
      world.push_back(glm::vec3(0.0f));
      wm.positions = world.data();
      RTCGeometry g = triangle_geometry(mesh, wm.positions, mask);
      rtcAttachGeometryByID(rtc_scene_, g, unsigned(i));
      rtcReleaseGeometry(g);
    } else {
      wm.positions = mesh_positions[m];
      // The world bounds of the mesh's object-space bounds' corners.
      const Bounds& object = mesh_bounds[m];
      if (!object.empty())
        for (int k = 0; k < 8; ++k)
          bounds_.extend(wm.linear * glm::vec3(k & 1 ? object.max.x : object.min.x,
                                               k & 2 ? object.max.y : object.min.y,
                                               k & 4 ? object.max.z : object.min.z) +
                         wm.translation);
      RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(g, mesh_scenes_[std::size_t(mesh_scene[m])]);
      if (motion && !motion->transforms[i].empty()) {
        // A rigid motion: one transform per step, which Embree interpolates linearly (as
        // resolve_moving does).
        wm.motion = int(motions_.size());
        InstanceMotion& mo = motions_.emplace_back();
        mo.transforms = motion->transforms[i];
        rtcSetGeometryTimeStepCount(g, unsigned(mo.transforms.size()));
        for (std::size_t k = 0; k < mo.transforms.size(); ++k) {
          rtcSetGeometryTransform(g, unsigned(k), RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                                  glm::value_ptr(mo.transforms[k]));
          if (!object.empty())
            for (int c = 0; c < 8; ++c)
              bounds_.extend(glm::vec3(mo.transforms[k] *
                                       glm::vec4(c & 1 ? object.max.x : object.min.x,
                                                 c & 2 ? object.max.y : object.min.y,
                                                 c & 4 ? object.max.z : object.min.z, 1.0f)));
        }
      } else {
        rtcSetGeometryTimeStepCount(g, 1);
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, glm::value_ptr(M));
      }
      rtcSetGeometryMask(g, mask);
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(rtc_scene_, g, unsigned(i));
      rtcReleaseGeometry(g);
      ++instanced_;
    }
  }
  rtcCommitScene(rtc_scene_);
  if (const RTCError error = rtcGetDeviceError(device_); error != RTC_ERROR_NONE)
    fail("{}: building the path tracer's BVH failed (Embree error {}{})", scene.source, int(error),
         error == RTC_ERROR_OUT_OF_MEMORY
             ? fmt::format(": out of memory, {} available", format_bytes(double(limit)))
             : "");
  memory_.bvh = std::size_t(std::max<std::int64_t>(monitor_->bytes.load(), 0));
  memory_.bvh_peak = std::size_t(std::max<std::int64_t>(monitor_->peak.load(), 0));
  memory_.geometry = sizeof(WorldMesh) * meshes_.capacity();
  for (const auto& copy : position_copies_) memory_.geometry += copy.capacity() * sizeof(glm::vec3);
}

SceneGeometry::~SceneGeometry() {
  if (rtc_scene_) rtcReleaseScene(rtc_scene_);
  for (RTCScene s : mesh_scenes_) rtcReleaseScene(s);
  if (device_) rtcReleaseDevice(device_);
}

bool SceneGeometry::intersect(glm::vec3 o, glm::vec3 d, float tfar, unsigned mask,
                              std::uint32_t& geom, std::uint32_t& prim, float& t, float& u,
                              float& v, float time) const {
  if (observer_) observer_->closest(o, d, tfar, mask);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = o.x;
  rh.ray.org_y = o.y;
  rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x;
  rh.ray.dir_y = d.y;
  rh.ray.dir_z = d.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = tfar;
  rh.ray.mask = mask;
  rh.ray.time = time;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(rtc_scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  // An instanced mesh's hit names the instance in instID (its geomID is the mesh's, 0).
  geom = rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? rh.hit.instID[0] : rh.hit.geomID;
  prim = rh.hit.primID;
  t = rh.ray.tfar;
  u = rh.hit.u;
  v = rh.hit.v;
  return true;
}

void SceneGeometry::intersect_packet(const glm::vec3* origins, const glm::vec3* directions,
                                     PacketHit* hits, const float* times) const {
  static_assert(kPacketSize == 16);
  if (observer_) observer_->packet(origins, directions);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  RTCRayHit16 rh;
  alignas(64) int valid[16];
  for (int k = 0; k < 16; ++k) {
    valid[k] = -1;
    rh.ray.org_x[k] = origins[k].x;
    rh.ray.org_y[k] = origins[k].y;
    rh.ray.org_z[k] = origins[k].z;
    rh.ray.dir_x[k] = directions[k].x;
    rh.ray.dir_y[k] = directions[k].y;
    rh.ray.dir_z[k] = directions[k].z;
    rh.ray.tnear[k] = 0.0f;
    rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
    rh.ray.mask[k] = 0xffffffffu;
    rh.ray.time[k] = times ? times[k] : 0.0f;
    rh.ray.flags[k] = 0;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, rtc_scene_, &context, &rh);
  for (int k = 0; k < 16; ++k) {
    const std::uint32_t inst = rh.hit.instID[0][k];
    const std::uint32_t geom = rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? kNoHit
                               : inst != RTC_INVALID_GEOMETRY_ID           ? inst
                                                                           : rh.hit.geomID[k];
    hits[k] = {geom, rh.hit.primID[k], rh.ray.tfar[k], rh.hit.u[k], rh.hit.v[k]};
  }
}

bool SceneGeometry::occluded(glm::vec3 o, glm::vec3 d, float tfar, float time) const {
  if (observer_) observer_->occluded(o, d, tfar);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  ray.org_x = o.x;
  ray.org_y = o.y;
  ray.org_z = o.z;
  ray.dir_x = d.x;
  ray.dir_y = d.y;
  ray.dir_z = d.z;
  ray.tnear = 0.0f;
  ray.tfar = tfar;
  ray.mask = kMaskOpaque;
  ray.time = time;
  ray.flags = 0;
  rtcOccluded1(rtc_scene_, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

namespace {

// What a hit interpolates besides its position and normals: the tangent (taken to world
// space by `linear`, its handedness flipped by a mirroring `orientation`), the UVs and
// their triangle's area, the vertex colour.
void interpolate_attributes(const Mesh& mesh, std::uint32_t i0, std::uint32_t i1, std::uint32_t i2,
                            float u, float v, const glm::mat3& linear, float orientation,
                            SurfaceHit& hit) {
  const float w = 1.0f - u - v;
  if (!mesh.tangents.empty()) {
    const glm::vec4 tg = w * mesh.tangents[i0] + u * mesh.tangents[i1] + v * mesh.tangents[i2];
    // A mirroring transform flips the bitangent's handedness.
    hit.tangent = glm::vec4(linear * glm::vec3(tg), tg.w * orientation);
  }
  const auto uv_area = [&](const std::vector<glm::vec2>& t) {
    const glm::vec2 a = t[i1] - t[i0], b = t[i2] - t[i0];
    return 0.5f * std::abs(a.x * b.y - a.y * b.x);
  };
  if (!mesh.texcoords0.empty()) {
    hit.uv[0] = w * mesh.texcoords0[i0] + u * mesh.texcoords0[i1] + v * mesh.texcoords0[i2];
    hit.uv_area[0] = uv_area(mesh.texcoords0);
  }
  if (!mesh.texcoords1.empty()) {
    hit.uv[1] = w * mesh.texcoords1[i0] + u * mesh.texcoords1[i1] + v * mesh.texcoords1[i2];
    hit.uv_area[1] = uv_area(mesh.texcoords1);
  }
  if (!mesh.colors0.empty())
    hit.color = w * mesh.colors0[i0] + u * mesh.colors0[i1] + v * mesh.colors0[i2];
}

// The geometric normal and area from a world-space cross product of two edges.
void set_geometric_normal(glm::vec3 c, SurfaceHit& hit) {
  const float len = glm::length(c);
  hit.area = 0.5f * len;
  hit.ng = len > 0.0f ? c / len : glm::vec3(0.0f, 0.0f, 1.0f);
  hit.ns = hit.ng;
}

}  // namespace

SurfaceHit SceneGeometry::resolve(std::uint32_t geom, std::uint32_t prim, float t, float u, float v,
                                  float time) const {
  const WorldMesh& wm = meshes_[geom];
  if (wm.motion >= 0) return resolve_moving(geom, prim, t, u, v, time);
  const Mesh& mesh = *wm.mesh;
  const std::uint32_t i0 = mesh.indices[3 * prim], i1 = mesh.indices[3 * prim + 1],
                      i2 = mesh.indices[3 * prim + 2];
  const float w = 1.0f - u - v;
  SurfaceHit hit;
  hit.t = t;
  hit.time = time;
  hit.geom = geom;
  hit.prim = prim;
  const glm::vec3 p0 = wm.positions[i0], p1 = wm.positions[i1], p2 = wm.positions[i2];
  hit.p = w * p0 + u * p1 + v * p2;
  glm::vec3 c = glm::cross(p1 - p0, p2 - p0);
  if (wm.flattened) {
    // World-space winding: clockwise is the front after a mirroring transform (glTF).
    c *= wm.orientation;
  } else {
    hit.p = wm.linear * hit.p + wm.translation;
    c = wm.normal_matrix * c;
  }
  set_geometric_normal(c, hit);
  if (!mesh.normals.empty()) {
    const glm::vec3 n =
        wm.normal_matrix * (w * mesh.normals[i0] + u * mesh.normals[i1] + v * mesh.normals[i2]);
    const float nl = glm::length(n);
    if (nl > 0.0f) hit.ns = n / nl;
  }
  interpolate_attributes(mesh, i0, i1, i2, u, v, wm.linear, wm.orientation, hit);
  return hit;
}

// A hit on a moving instance at `time`: between the two motion steps around it, linearly,
// as Embree interpolates the vertices and the instance transforms it intersected.
SurfaceHit SceneGeometry::resolve_moving(std::uint32_t geom, std::uint32_t prim, float t, float u,
                                         float v, float time) const {
  const WorldMesh& wm = meshes_[geom];
  const InstanceMotion& mo = motions_[std::size_t(wm.motion)];
  const Mesh& mesh = *wm.mesh;
  const std::uint32_t i0 = mesh.indices[3 * prim], i1 = mesh.indices[3 * prim + 1],
                      i2 = mesh.indices[3 * prim + 2];
  const std::size_t steps = mo.positions.empty() ? mo.transforms.size() : mo.positions.size();
  const float f = std::clamp(time, 0.0f, 1.0f) * float(steps - 1);
  const std::size_t k = std::min(std::size_t(f), steps - 2);
  const float a = f - float(k);
  const float w = 1.0f - u - v;
  SurfaceHit hit;
  hit.t = t;
  hit.time = time;
  hit.geom = geom;
  hit.prim = prim;
  if (!mo.positions.empty()) {
    // World-space vertices and normals per step.
    const auto at = [&](const std::vector<std::vector<glm::vec3>>& steps_of, std::uint32_t i) {
      return (1.0f - a) * steps_of[k][i] + a * steps_of[k + 1][i];
    };
    const glm::vec3 p0 = at(mo.positions, i0), p1 = at(mo.positions, i1), p2 = at(mo.positions, i2);
    hit.p = w * p0 + u * p1 + v * p2;
    set_geometric_normal(glm::cross(p1 - p0, p2 - p0) * wm.orientation, hit);
    const glm::vec3 n = w * at(mo.normals, i0) + u * at(mo.normals, i1) + v * at(mo.normals, i2);
    const float nl = glm::length(n);
    if (nl > 0.0f) hit.ns = n / nl;
    // (The tangents are the shutter centre's: a normal map's frame turns with the mesh
    // only as far as the centre pose does.)
    interpolate_attributes(mesh, i0, i1, i2, u, v, wm.linear, wm.orientation, hit);
    return hit;
  }
  const glm::mat4 M = (1.0f - a) * mo.transforms[k] + a * mo.transforms[k + 1];
  const glm::mat3 linear(M);
  const float orientation = glm::determinant(linear) < 0.0f ? -1.0f : 1.0f;
  const glm::mat3 normal_matrix = orientation * cofactor(linear);
  const glm::vec3 p0 = wm.positions[i0], p1 = wm.positions[i1], p2 = wm.positions[i2];
  hit.p = linear * (w * p0 + u * p1 + v * p2) + glm::vec3(M[3]);
  set_geometric_normal(normal_matrix * glm::cross(p1 - p0, p2 - p0), hit);
  if (!mesh.normals.empty()) {
    const glm::vec3 n =
        normal_matrix * (w * mesh.normals[i0] + u * mesh.normals[i1] + v * mesh.normals[i2]);
    const float nl = glm::length(n);
    if (nl > 0.0f) hit.ns = n / nl;
  }
  interpolate_attributes(mesh, i0, i1, i2, u, v, linear, orientation, hit);
  return hit;
}

float SceneGeometry::triangle_area(std::uint32_t geom, std::uint32_t prim) const {
  const WorldMesh& wm = meshes_[geom];
  const std::uint32_t* idx = wm.mesh->indices.data() + 3 * std::size_t(prim);
  const glm::vec3 p0 = wm.positions[idx[0]];
  glm::vec3 c = glm::cross(wm.positions[idx[1]] - p0, wm.positions[idx[2]] - p0);
  if (!wm.flattened) c = wm.normal_matrix * c;
  return 0.5f * glm::length(c);
}

}  // namespace pbrkit
