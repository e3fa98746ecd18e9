#include "pbrkit/gl/occluders.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "pbrkit/core/transmission.h"
#include "pbrkit/gl/shader_permutations.h"
#include "pbrkit/gl/surface_bindings.h"

namespace pbrkit::gl {

namespace {

// The cosine-weighted hemispherical average of the Fresnel reflectance, 2 int F(mu) mu dmu
// (midpoint rule, 64 steps: well within 1e-3 of the integral for ior 1-3).
float average_fresnel(float ior) {
  if (ior <= 1.0f) return 0.0f;
  constexpr int kSteps = 64;
  float sum = 0.0f;
  for (int i = 0; i < kSteps; ++i) {
    const float mu = (float(i) + 0.5f) / kSteps;
    sum += fresnel_dielectric(mu, ior) * mu;  // core/transmission.h's, exact
  }
  return 2.0f * sum / kSteps;
}

// The mean of the texture `ref` names (GpuScene::texture_means), 1 where it names none.
glm::vec3 mean_of(const TextureRef& ref, std::span<const glm::vec3> texture_means) {
  const int t = ref.texture;
  return t >= 0 && std::size_t(t) < texture_means.size() ? texture_means[std::size_t(t)]
                                                         : glm::vec3(1.0f);
}

}  // namespace

ParallelepipedFaces parallelepiped_faces(const glm::vec3 axes[3]) {
  glm::vec3 a[3] = {axes[0], axes[1], axes[2]};
  const float largest = std::max({glm::length(a[0]), glm::length(a[1]), glm::length(a[2])});
  const float thin = 1e-4f * largest;
  for (int k = 0; k < 3; ++k) {
    if (glm::length(a[k]) >= thin) continue;
    glm::vec3 across = glm::cross(a[(k + 1) % 3], a[(k + 2) % 3]);
    if (glm::length(across) == 0.0f) {  // a second axis is 0 too: any direction across
      const glm::vec3 other = glm::length(a[(k + 1) % 3]) > 0.0f ? a[(k + 1) % 3] : a[(k + 2) % 3];
      across =
          glm::cross(other, std::abs(other.x) < 0.9f * glm::length(other) ? glm::vec3(1, 0, 0)
                                                                          : glm::vec3(0, 1, 0));
    }
    if (glm::length(across) > 0.0f) a[k] = thin * glm::normalize(across);
  }
  ParallelepipedFaces faces;
  for (int k = 0; k < 3; ++k) {
    // The pair's area vector: a face's area along its normal.
    const glm::vec3 S = 4.0f * glm::cross(a[(k + 1) % 3], a[(k + 2) % 3]);
    const float area = glm::length(S);
    if (area == 0.0f) continue;  // every axis 0: a point, which covers nothing
    faces.normals[k] = glm::vec4(S / area, std::abs(glm::dot(a[k], S)) / area);
    faces.areas[k] = area;
  }
  return faces;
}

glm::vec3 occluder_transmittance(const Material& m, bool volume, float chord) {
  const float t = m.transmission ? std::clamp(m.transmission->factor, 0.0f, 1.0f) : 0.0f;
  const float dt =
      m.diffuse_transmission ? std::clamp(m.diffuse_transmission->factor, 0.0f, 1.0f) : 0.0f;
  const glm::vec3 base = glm::clamp(glm::vec3(m.base_color_factor), 0.0f, 1.0f);
  const glm::vec3 dt_color = m.diffuse_transmission
                                 ? glm::clamp(m.diffuse_transmission->color_factor, 0.0f, 1.0f)
                                 : glm::vec3(0.0f);
  glm::vec3 through =
      (1.0f - std::clamp(m.metallic_factor, 0.0f, 1.0f)) * (t * base + (1.0f - t) * dt * dt_color);
  const float leave = 1.0f - average_fresnel(m.ior);
  through *= volume ? leave * leave : leave;
  if (volume && m.volume && std::isfinite(m.volume->attenuation_distance) &&
      m.volume->attenuation_distance > 0.0f)
    through *= glm::pow(glm::max(m.volume->attenuation_color, glm::vec3(1e-6f)),
                        glm::vec3(chord / m.volume->attenuation_distance));
  return glm::clamp(through, 0.0f, 1.0f);
}

glm::vec3 opaque_albedo(const Material& m, std::span<const glm::vec3> texture_means) {
  return glm::clamp(glm::vec3(m.base_color_factor) * mean_of(m.base_color_texture, texture_means),
                    0.0f, 1.0f);
}

glm::vec3 opaque_emission(const Material& m, std::span<const glm::vec3> texture_means) {
  // The surface's own emission as the renderer draws it (uEmissive), times the texture's mean.
  return m.emissive_factor * m.emissive_strength * mean_of(m.emissive_texture, texture_means);
}

std::vector<Occluder> ibl_occluders(const GpuScene& scene, OccluderKinds kinds) {
  std::vector<Occluder> out;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    if (inst.mesh < 0 || std::size_t(inst.mesh) >= scene.meshes.size()) continue;
    const GpuMesh& g = scene.meshes[std::size_t(inst.mesh)];
    const Material& m = scene.material_of(g);
    SurfaceFeatures f;  // the permutation it is drawn with says whether it transmits
    set_transmission_features(m, g.closed, f);
    const bool opaque = !f.transmission && !f.diffuse_transmission;
    // A blended or masked surface lets some light through where its alpha says so: not a
    // solid proxy.
    if ((opaque ? !kinds.opaque || m.alpha_mode != AlphaMode::kOpaque : !kinds.transmissive) ||
        g.index_count == 0)
      continue;
    const bool volume = f.volume;
    const glm::mat4& M = inst.transform;
    Occluder o;
    o.slot = int(scene.slot_of[i]);
    o.opaque = opaque;
    const glm::vec3 half = 0.5f * (g.bounds_max - g.bounds_min);
    glm::vec3 axes[3];
    for (int k = 0; k < 3; ++k) axes[k] = glm::vec3(M[k]) * half[k];
    const glm::vec3 scale(glm::length(glm::vec3(M[0])), glm::length(glm::vec3(M[1])),
                          glm::length(glm::vec3(M[2])));
    const bool uniform = std::abs(scale.x - scale.y) <= 1e-3f * scale.x &&
                         std::abs(scale.x - scale.z) <= 1e-3f * scale.x;
    float chord;
    if (g.sphere_radius > 0.0f && uniform) {
      o.sphere = true;
      o.radius = g.sphere_radius * scale.x;
      o.center = glm::vec3(M * glm::vec4(g.center, 1.0f));
      chord = 4.0f / 3.0f * o.radius;  // a convex body's mean chord, 4 V / S (Cauchy)
    } else {
      // A convex body inside a box has at most the box's area (Cauchy's surface area
      // formula is monotone): a mesh with more (an engine part's fins, interlocking pieces)
      // is too far from its bounding box for the box to stand in for it as a solid, and
      // surfaces beside or within the box would be shadowed by what is not there.
      if (opaque &&
          g.surface_area > 1.05f * 8.0f * (half.x * half.y + half.y * half.z + half.z * half.x))
        continue;
      o.center = glm::vec3(M * glm::vec4(0.5f * (g.bounds_min + g.bounds_max), 1.0f));
      o.faces = parallelepiped_faces(axes);
      // 4 V / S with V = 8 abc, S = 8 (ab + bc + ca) (a box; a parallelepiped's is less).
      const float a = glm::length(axes[0]), b = glm::length(axes[1]), c = glm::length(axes[2]);
      const float surface = a * b + b * c + c * a;
      chord = surface > 0.0f ? 4.0f * a * b * c / surface : 0.0f;
    }
    if (opaque) {
      o.transmittance = glm::vec3(0.0f);
      if (m.unlit) {
        o.emission = opaque_albedo(m, scene.texture_means);
      } else {
        o.albedo = opaque_albedo(m, scene.texture_means);
        o.emission = opaque_emission(m, scene.texture_means);
      }
    } else {
      o.transmittance = occluder_transmittance(m, volume, chord);
    }
    // A proxy written into a shader must be finite (a degenerate transform is not), and so
    // must the light it sends (an emission past the float range).
    if (!std::isfinite(o.radius + glm::dot(o.center, o.center) + o.faces.areas.x + o.faces.areas.y +
                       o.faces.areas.z + o.emission.x + o.emission.y + o.emission.z))
      continue;
    out.push_back(o);
  }
  return out;
}

std::vector<Occluder> select_occluders(std::span<const Occluder> all, glm::ivec2& counts) {
  std::vector<Occluder> spheres, boxes;
  for (const Occluder& o : all) (o.sphere ? spheres : boxes).push_back(o);
  const auto keep_largest = [](std::vector<Occluder>& v, auto size) {
    std::stable_sort(v.begin(), v.end(),
                     [&](const Occluder& a, const Occluder& b) { return size(a) > size(b); });
    if (v.size() > std::size_t(kMaxOccluders)) v.resize(std::size_t(kMaxOccluders));
  };
  keep_largest(spheres, [](const Occluder& o) { return o.radius; });
  keep_largest(
      boxes, [](const Occluder& o) { return o.faces.areas.x + o.faces.areas.y + o.faces.areas.z; });
  // The opaque ones last of each kind: only they send light back (occluders.glsl).
  for (auto* v : {&spheres, &boxes})
    std::stable_partition(v->begin(), v->end(), [](const Occluder& o) { return !o.opaque; });
  counts = glm::ivec2(int(spheres.size()), int(boxes.size()));
  spheres.insert(spheres.end(), boxes.begin(), boxes.end());
  return spheres;
}

std::string occluder_geometry_define(std::span<const Occluder> selected) {
  std::string d = "#define OCCLUDER_GEOMETRY vec4[](";
  const auto add = [&](glm::vec4 v, bool first) {
    d += fmt::format("{}vec4({:.9g}, {:.9g}, {:.9g}, {:.9g})", first ? "" : ", ", v.x, v.y, v.z,
                     v.w);
  };
  // Each proxy's index in the list of its kind (sphere or parallelepiped) and role
  // (transmissive or opaque), in select_occluders' order.
  std::string lists[2][2];  // [sphere][opaque]
  for (std::size_t i = 0; i < selected.size(); ++i) {
    const Occluder& o = selected[i];
    add(glm::vec4(o.center, float(o.slot)), i == 0);
    for (const glm::vec4& n : o.faces.normals) add(n, false);
    add(glm::vec4(o.faces.areas, o.radius), false);
    lists[o.sphere ? 1 : 0][o.opaque ? 1 : 0] += fmt::format(" OCCLUDER_TERM({})", i);
  }
  return d + fmt::format(
                 ")\n#define OCCLUDER_TRANSMISSIVE_SPHERES{}\n#define OCCLUDER_OPAQUE_SPHERES{}\n"
                 "#define OCCLUDER_TRANSMISSIVE_BOXES{}\n#define OCCLUDER_OPAQUE_BOXES{}\n",
                 lists[1][0], lists[1][1], lists[0][0], lists[0][1]);
}

GpuOccluderBuffer::GpuOccluderBuffer() {
  glCreateBuffers(1, &buffer_);
}

GpuOccluderBuffer::~GpuOccluderBuffer() {
  glDeleteBuffers(1, &buffer_);
}

void GpuOccluderBuffer::upload(std::span<const Occluder> selected) {
  // The shader's block (occluders.glsl's Occluders) has room for kMaxOccluders of each kind:
  // their transmittances, then their albedos and their emissions (an opaque one's; 0 sends
  // nothing).
  const std::size_t n = 2 * std::size_t(kMaxOccluders);
  std::vector<glm::vec4> data(3 * n, glm::vec4(0.0f));
  std::fill(data.begin(), data.begin() + std::ptrdiff_t(n), glm::vec4(1.0f));
  for (std::size_t i = 0; i < selected.size() && i < n; ++i) {
    const Occluder& o = selected[i];
    data[i] = glm::vec4(o.transmittance, 0.0f);
    data[n + i] = glm::vec4(o.opaque ? o.albedo : glm::vec3(0.0f), 0.0f);
    data[2 * n + i] = glm::vec4(o.opaque ? o.emission : glm::vec3(0.0f), 0.0f);
  }
  glNamedBufferData(buffer_, GLsizeiptr(data.size() * sizeof(glm::vec4)), data.data(),
                    GL_STREAM_DRAW);
  bind();
}

void GpuOccluderBuffer::bind() const {
  glBindBufferBase(GL_UNIFORM_BUFFER, kOccluderBufferBinding, buffer_);
}

}  // namespace pbrkit::gl
