#include "pbrkit/pt/geometry.h"

#include <cmath>
#include <limits>

#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit {

namespace {

void embree_error(void* /*user*/, RTCError code, const char* message) {
  if (code == RTC_ERROR_NONE) return;
  warn("embree: {} (error {})", message ? message : "", int(code));
}

}  // namespace

SceneGeometry::SceneGeometry(const Scene& scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_)
    fail("{}: cannot create an Embree device (error {})", scene.source,
         int(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
  rtc_scene_ = rtcNewScene(device_);
  // MEDIUM: about half the build time of HIGH (../shared/PLATFORM.md section 4) for
  // a few percent of trace speed; renders here are short enough for build time to matter.
  rtcSetSceneBuildQuality(rtc_scene_, RTC_BUILD_QUALITY_MEDIUM);

  meshes_.resize(scene.instances.size());
  // has_alpha may scan a texture: once per mesh, however many instances it has.
  std::vector<bool> mesh_alpha(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    mesh_alpha[m] = pbrkit::has_alpha(scene, scene.meshes[m]);
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    WorldMesh& wm = meshes_[i];
    if (inst.mesh < 0 || inst.mesh >= int(scene.meshes.size()))
      fail("{}: instance {} refers to mesh {} (the scene has {})", scene.source, i, inst.mesh,
           scene.meshes.size());
    const Mesh& mesh = scene.meshes[std::size_t(inst.mesh)];
    wm.mesh = &mesh;
    wm.material = &scene.material_of(mesh);
    wm.has_alpha = mesh_alpha[std::size_t(inst.mesh)];
    const glm::vec3 e = wm.material->emissive_factor * wm.material->emissive_strength;
    wm.emissive = e.x > 0.0f || e.y > 0.0f || e.z > 0.0f;
    has_alpha_ = has_alpha_ || wm.has_alpha;

    const glm::mat4& M = inst.transform;
    const glm::mat3 N = glm::transpose(glm::inverse(glm::mat3(M)));
    const float det = glm::determinant(glm::mat3(M));
    wm.positions.resize(mesh.positions.size() + 1, glm::vec3(0.0f));  // Embree reads 16 B
    for (std::size_t k = 0; k < mesh.positions.size(); ++k) {
      wm.positions[k] = glm::vec3(M * glm::vec4(mesh.positions[k], 1.0f));
      bounds_.extend(wm.positions[k]);
    }
    if (mesh.normals.size() == mesh.positions.size()) {
      wm.normals.resize(mesh.normals.size());
      for (std::size_t k = 0; k < mesh.normals.size(); ++k) {
        const glm::vec3 n = N * mesh.normals[k];
        const float len = glm::length(n);
        wm.normals[k] = len > 0.0f ? n / len : glm::vec3(0.0f);
      }
    }
    if (mesh.tangents.size() == mesh.positions.size()) {
      wm.tangents.resize(mesh.tangents.size());
      for (std::size_t k = 0; k < mesh.tangents.size(); ++k) {
        const glm::vec3 t = glm::mat3(M) * glm::vec3(mesh.tangents[k]);
        // A mirroring transform flips the bitangent's handedness.
        wm.tangents[k] = glm::vec4(t, mesh.tangents[k].w * (det < 0.0f ? -1.0f : 1.0f));
      }
    }
    for (std::uint32_t idx : mesh.indices)
      if (idx >= mesh.positions.size())
        fail("{}: mesh '{}' has an index {} past its {} vertices", scene.source, mesh.name, idx,
             mesh.positions.size());

    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, wm.positions.data(),
                               0, sizeof(glm::vec3), mesh.positions.size());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(),
                               0, 3 * sizeof(std::uint32_t), mesh.triangle_count());
    rtcSetGeometryMask(g, wm.has_alpha ? kMaskAlpha : kMaskOpaque);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(rtc_scene_, g, unsigned(i));
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(rtc_scene_);
}

SceneGeometry::~SceneGeometry() {
  if (rtc_scene_) rtcReleaseScene(rtc_scene_);
  if (device_) rtcReleaseDevice(device_);
}

bool SceneGeometry::intersect(glm::vec3 o, glm::vec3 d, float tfar, unsigned mask,
                              std::uint32_t& geom, std::uint32_t& prim, float& t, float& u,
                              float& v) const {
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
  rh.ray.time = 0.0f;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(rtc_scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  geom = rh.hit.geomID;
  prim = rh.hit.primID;
  t = rh.ray.tfar;
  u = rh.hit.u;
  v = rh.hit.v;
  return true;
}

void SceneGeometry::intersect_packet(const glm::vec3* origins, const glm::vec3* directions,
                                     PacketHit* hits) const {
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
    rh.ray.time[k] = 0.0f;
    rh.ray.flags[k] = 0;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, rtc_scene_, &context, &rh);
  for (int k = 0; k < 16; ++k)
    hits[k] = {rh.hit.geomID[k], rh.hit.primID[k], rh.ray.tfar[k], rh.hit.u[k], rh.hit.v[k]};
}

bool SceneGeometry::occluded(glm::vec3 o, glm::vec3 d, float tfar) const {
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
  ray.time = 0.0f;
  ray.flags = 0;
  rtcOccluded1(rtc_scene_, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

SurfaceHit SceneGeometry::resolve(std::uint32_t geom, std::uint32_t prim, float t, float u,
                                  float v) const {
  const WorldMesh& wm = meshes_[geom];
  const Mesh& mesh = *wm.mesh;
  const std::uint32_t i0 = mesh.indices[3 * prim], i1 = mesh.indices[3 * prim + 1],
                      i2 = mesh.indices[3 * prim + 2];
  const float w = 1.0f - u - v;
  SurfaceHit hit;
  hit.t = t;
  hit.geom = geom;
  hit.prim = prim;
  const glm::vec3 p0 = wm.positions[i0], p1 = wm.positions[i1], p2 = wm.positions[i2];
  hit.p = w * p0 + u * p1 + v * p2;
  const glm::vec3 c = glm::cross(p1 - p0, p2 - p0);
  const float len = glm::length(c);
  hit.area = 0.5f * len;
  hit.ng = len > 0.0f ? c / len : glm::vec3(0.0f, 0.0f, 1.0f);
  hit.ns = hit.ng;
  if (!wm.normals.empty()) {
    const glm::vec3 n = w * wm.normals[i0] + u * wm.normals[i1] + v * wm.normals[i2];
    const float nl = glm::length(n);
    if (nl > 0.0f) hit.ns = n / nl;
  }
  if (!wm.tangents.empty())
    hit.tangent = w * wm.tangents[i0] + u * wm.tangents[i1] + v * wm.tangents[i2];
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
  return hit;
}

}  // namespace pbrkit
