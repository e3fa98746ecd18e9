// Posing a scene: node transforms from the animation's channels (glTF 2.0 section 3.11),
// morph targets (section 3.7.2.2) and linear blend skinning (section 3.7.3).
#include "pbrkit/scene/pose.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/scene.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

struct LocalPose {
  glm::vec3 translation;
  glm::quat rotation;
  glm::vec3 scale;
};

std::string describe(const SceneMotion& motion, const PoseTime& pose) {
  if (pose.animation < 0) return "the rest pose";
  const auto& a = motion.animations[std::size_t(pose.animation)];
  return fmt::format("animation {} ('{}') at {} s", pose.animation, a.name, pose.time);
}

// Rigid part of a node transform: glTF cameras ignore scale (section 3.10.1).
glm::mat4 rigid(glm::mat4 m, const std::string& what) {
  for (int axis = 0; axis < 3; ++axis) {
    const float len = glm::length(glm::vec3(m[axis]));
    if (!(len > 0.0f)) throw Error(fmt::format("{}: the camera's node has a zero scale", what));
    m[axis] = glm::vec4(glm::vec3(m[axis]) / len, 0.0f);
  }
  return m;
}

// A deforming mesh's vertices at a pose.
struct Vertices {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;
};

void deform(const SceneMotion& motion, const DeformingMesh& d,
            const std::vector<std::uint32_t>& indices, const std::vector<float>& weights,
            const std::vector<glm::mat4>& world, Vertices& out) {
  const std::size_t n = d.positions.size();
  out.positions = d.positions;
  out.normals = d.flat_normals ? std::vector<glm::vec3>{} : d.normals;
  out.tangents = d.tangents;
  // Morph targets: the weighted sum of displacements (section 3.7.2.2); TANGENT targets
  // move xyz only, the handedness stays.
  for (std::size_t t = 0; t < d.targets.size() && t < weights.size(); ++t) {
    const float w = weights[t];
    if (w == 0.0f) continue;
    const MorphTarget& target = d.targets[t];
    for (std::size_t i = 0; i < target.positions.size() && i < n; ++i)
      out.positions[i] += w * target.positions[i];
    for (std::size_t i = 0; i < target.normals.size() && i < out.normals.size(); ++i)
      out.normals[i] += w * target.normals[i];
    for (std::size_t i = 0; i < target.tangents.size() && i < out.tangents.size(); ++i)
      out.tangents[i] += glm::vec4(w * target.tangents[i], 0.0f);
  }
  if (d.skin >= 0) {
    // Linear blend skinning: the joint matrix of joint j is world(joint j) times its
    // inverse bind matrix, and the skinned mesh's own node transform is ignored
    // (section 3.7.3.1): the vertices come out in world space.
    const std::vector<glm::mat4> joint = joint_matrices(motion.skins[std::size_t(d.skin)], world);
    const std::size_t k = std::size_t(d.influences);
    for (std::size_t i = 0; i < n; ++i) {
      glm::mat4 m(0.0f);
      for (std::size_t c = 0; c < k; ++c) {
        const float w = d.weights[i * k + c];
        if (w != 0.0f) m += w * joint[d.joints[i * k + c]];
      }
      out.positions[i] = glm::vec3(m * glm::vec4(out.positions[i], 1.0f));
      const glm::mat3 linear(m);
      // Normals transform by the inverse transpose; tangents lie in the surface and
      // transform by the matrix itself.
      if (i < out.normals.size())
        out.normals[i] = glm::transpose(glm::inverse(linear)) * out.normals[i];
      if (i < out.tangents.size())
        out.tangents[i] = glm::vec4(linear * glm::vec3(out.tangents[i]), out.tangents[i].w);
    }
  }
  for (glm::vec3& v : out.normals) {
    const float len = glm::length(v);
    v = len > 0.0f && std::isfinite(len) ? v / len : glm::vec3(0, 0, 1);
  }
  for (glm::vec4& v : out.tangents) {
    const float len = glm::length(glm::vec3(v));
    v = len > 0.0f && std::isfinite(len) ? glm::vec4(glm::vec3(v) / len, v.w)
                                         : glm::vec4(1, 0, 0, v.w);
  }
  if (d.flat_normals) {
    // The loader unwelded the triangles (one vertex per corner): each gets its face's normal.
    out.normals.assign(n, glm::vec3(0, 0, 1));
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
      const std::uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
      const glm::vec3 f =
          glm::cross(out.positions[b] - out.positions[a], out.positions[c] - out.positions[a]);
      const float len = glm::length(f);
      const glm::vec3 unit = len > 0.0f && std::isfinite(len) ? f / len : glm::vec3(0, 0, 1);
      out.normals[a] = out.normals[b] = out.normals[c] = unit;
    }
  }
}

// One KHR_animation_pointer value into the scene: a material's factor (clamped to its
// range), a texture transform, or every placement of a light or camera.
void write_pointer(Scene& scene, const SceneMotion& motion, const PointerTarget& p,
                   const float* v) {
  switch (p.kind) {
    case PointerTarget::Kind::kMaterial: {
      float* dst = p.material_value(scene.materials[std::size_t(p.index)]);
      for (int c = 0; c < p.components; ++c) dst[c] = std::clamp(v[c], p.min, p.max);
      return;
    }
    case PointerTarget::Kind::kTextureTransform: {
      TextureRef& ref = texture_in(scene.materials[std::size_t(p.index)], p.slot);
      if (!ref.transform) ref.transform = TextureTransform{};
      if (p.field == 0) ref.transform->offset = {v[0], v[1]};
      if (p.field == 1) ref.transform->rotation = v[0];
      if (p.field == 2) ref.transform->scale = {v[0], v[1]};
      return;
    }
    case PointerTarget::Kind::kLight:
      for (std::size_t i = 0; i < motion.light_sources.size() && i < scene.lights.size(); ++i) {
        if (motion.light_sources[i] != p.index) continue;
        Light& l = scene.lights[i];
        if (p.field == 0) l.color = glm::max(glm::vec3(v[0], v[1], v[2]), glm::vec3(0.0f));
        if (p.field == 1) l.intensity = std::max(v[0], 0.0f);
        if (p.field == 2)
          l.range = v[0] > 0.0f && std::isfinite(v[0]) ? std::optional(v[0]) : std::nullopt;
        // The cones keep 0 <= inner < outer <= pi/2 (KHR_lights_punctual, "Spot").
        if (p.field == 3) l.inner_cone_angle = std::clamp(v[0], 0.0f, l.outer_cone_angle * 0.999f);
        if (p.field == 4)
          l.outer_cone_angle = std::clamp(v[0], l.inner_cone_angle * 1.001f + 1e-6f, 1.5707964f);
      }
      return;
    case PointerTarget::Kind::kVisibility:
      return;  // not called for it: hide_invisible()
    case PointerTarget::Kind::kCamera:
      for (std::size_t i = 0; i < motion.camera_sources.size() && i < scene.cameras.size(); ++i) {
        if (motion.camera_sources[i] != p.index) continue;
        Camera& c = scene.cameras[i];
        const float tiny = 1e-6f;
        if (p.field == 0) c.yfov = std::clamp(v[0], 1e-4f, 3.1415f);  // (0, pi)
        if (p.field == 1)
          c.znear = std::max(v[0], c.type == Camera::Type::kPerspective ? tiny : 0.0f);
        if (p.field == 2 && v[0] > c.znear && std::isfinite(v[0])) c.zfar = v[0];
        if (p.field == 3) c.aspect_ratio = v[0] > 0.0f ? std::optional(v[0]) : std::nullopt;
        if (p.field == 4 && std::abs(v[0]) > tiny) c.xmag = v[0];
        if (p.field == 5 && std::abs(v[0]) > tiny) c.ymag = v[0];
      }
      return;
  }
}

// KHR_animation_pointer: every target at rest, then the animation's channels on top
// (visibility targets are hide_invisible's: it needs every node's flag at once).
void pose_pointers(Scene& scene, const SceneMotion& motion, const PoseTime& pose) {
  for (const PointerTarget& p : motion.pointers)
    if (p.kind != PointerTarget::Kind::kVisibility) write_pointer(scene, motion, p, p.rest.data());
  if (pose.animation < 0) return;
  const Animation& a = motion.animations[std::size_t(pose.animation)];
  float v[4];
  for (const AnimationChannel& ch : a.channels) {
    if (ch.property != AnimatedProperty::kPointer) continue;
    const PointerTarget& p = motion.pointers[std::size_t(ch.pointer)];
    if (p.kind == PointerTarget::Kind::kVisibility) continue;
    sample_animation(a.samplers[std::size_t(ch.sampler)], pose.time, false, v);
    write_pointer(scene, motion, p, v);
  }
}

// KHR_node_visibility when an animation drives it: a node is visible when its own flag
// (the file's, or the animation's: a value >= 0.5 is true) and every ancestor's are. An
// invisible node's instances get a zero transform (no area: the path tracer leaves them out
// of its BVH, the rasteriser draws nothing) and its lights a zero intensity.
void hide_invisible(Scene& scene, const SceneMotion& motion, const PoseTime& pose) {
  std::vector<char> own(motion.nodes.size());
  for (std::size_t i = 0; i < own.size(); ++i) own[i] = motion.nodes[i].visible;
  if (pose.animation >= 0) {
    const Animation& a = motion.animations[std::size_t(pose.animation)];
    for (const AnimationChannel& ch : a.channels) {
      if (ch.property != AnimatedProperty::kPointer) continue;
      const PointerTarget& p = motion.pointers[std::size_t(ch.pointer)];
      if (p.kind != PointerTarget::Kind::kVisibility) continue;
      float v = 1.0f;
      sample_animation(a.samplers[std::size_t(ch.sampler)], pose.time, false, &v);
      own[std::size_t(p.index)] = v >= 0.5f;
    }
  }
  std::vector<char> visible(own.size(), 1);
  for (const int node : motion.order) {
    const int parent = motion.nodes[std::size_t(node)].parent;
    visible[std::size_t(node)] =
        own[std::size_t(node)] && (parent < 0 || visible[std::size_t(parent)]);
  }
  for (const NodePlacement& p : motion.placements)
    if (!visible[std::size_t(p.node)])
      scene.instances[std::size_t(p.instance)].transform = glm::mat4(0.0f);
  for (const DeformingMesh& d : motion.deforming)
    if (!visible[std::size_t(d.node)])
      scene.instances[std::size_t(d.instance)].transform = glm::mat4(0.0f);
  for (std::size_t i = 0; i < motion.light_nodes.size() && i < scene.lights.size(); ++i)
    if (!visible[std::size_t(motion.light_nodes[i])]) scene.lights[i].intensity = 0.0f;
}

void check_finite(const SceneMotion& motion, std::string_view source, const PoseTime& pose,
                  const std::vector<glm::mat4>& world) {
  for (const int node : motion.order)
    if (!finite(world[std::size_t(node)]))
      throw Error(fmt::format("{}: {} gives nodes[{}] a transform that is not finite", source,
                              describe(motion, pose), node));
}

}  // namespace

int find_animation(const Scene& scene, std::string_view name_or_index) {
  const std::size_t count = scene.motion ? scene.motion->animations.size() : 0;
  if (count == 0)
    throw Error(fmt::format("{} has no animations (asked for '{}')", scene.source, name_or_index));
  for (std::size_t i = 0; i < count; ++i)
    if (scene.motion->animations[i].name == name_or_index) return int(i);
  int index = -1;
  const char* end = name_or_index.data() + name_or_index.size();
  if (const auto r = std::from_chars(name_or_index.data(), end, index);
      r.ec == std::errc() && r.ptr == end && index >= 0 && std::size_t(index) < count)
    return index;
  std::string list;
  for (std::size_t i = 0; i < count; ++i)
    list += fmt::format("{}{} '{}' ({:.3g} to {:.3g} s)", i ? ", " : "", i,
                        scene.motion->animations[i].name, scene.motion->animations[i].start(),
                        scene.motion->animations[i].end());
  throw Error(
      fmt::format("{} has no animation '{}'; it has: {}", scene.source, name_or_index, list));
}

std::vector<glm::mat4> posed_node_transforms(const SceneMotion& motion, const PoseTime& pose) {
  const std::size_t count = motion.nodes.size();
  std::vector<LocalPose> local(count);
  for (std::size_t i = 0; i < count; ++i)
    local[i] = {motion.nodes[i].translation, motion.nodes[i].rotation, motion.nodes[i].scale};
  if (pose.animation >= 0) {
    const Animation& a = motion.animations[std::size_t(pose.animation)];
    for (const AnimationChannel& ch : a.channels) {
      const AnimationSampler& s = a.samplers[std::size_t(ch.sampler)];
      LocalPose& l = local[std::size_t(ch.node)];
      float v[4];
      switch (ch.property) {
        case AnimatedProperty::kTranslation:
          sample_animation(s, pose.time, false, v);
          l.translation = {v[0], v[1], v[2]};
          break;
        case AnimatedProperty::kRotation:
          sample_animation(s, pose.time, true, v);
          l.rotation = glm::quat(v[3], v[0], v[1], v[2]);
          break;
        case AnimatedProperty::kScale:
          sample_animation(s, pose.time, false, v);
          l.scale = {v[0], v[1], v[2]};
          break;
        case AnimatedProperty::kWeights:
          break;  // posed_morph_weights()
        case AnimatedProperty::kPointer:
          break;  // pose_pointers()
      }
    }
  }
  std::vector<glm::mat4> world(count, glm::mat4(1.0f));
  for (const int node : motion.order) {
    const NodeRest& rest = motion.nodes[std::size_t(node)];
    const LocalPose& l = local[std::size_t(node)];
    const glm::mat4 m = rest.has_matrix
                            ? rest.matrix
                            : glm::translate(glm::mat4(1.0f), l.translation) *
                                  glm::mat4_cast(l.rotation) * glm::scale(glm::mat4(1.0f), l.scale);
    world[std::size_t(node)] = rest.parent >= 0 ? world[std::size_t(rest.parent)] * m : m;
  }
  return world;
}

void pose_scene(Scene& scene, const PoseTime& pose) {
  if (!scene.motion) {
    if (pose.animation >= 0) throw Error(fmt::format("{} has no animations", scene.source));
    return;
  }
  const SceneMotion& motion = *scene.motion;
  const std::vector<glm::mat4> world = checked_node_transforms(motion, scene.source, pose);
  place_instances_and_lights(motion, world, scene.instances, scene.lights);
  for (std::size_t i = 0; i < motion.camera_nodes.size() && i < scene.cameras.size(); ++i)
    scene.cameras[i].camera_to_world =
        rigid(world[std::size_t(motion.camera_nodes[i])],
              fmt::format("{}: {}, nodes[{}]", scene.source, describe(motion, pose),
                          motion.camera_nodes[i]));
  if (motion.visibility_animated)  // a hidden light's intensity, back before the pointers
    for (std::size_t i = 0; i < motion.light_rest_intensity.size() && i < scene.lights.size(); ++i)
      scene.lights[i].intensity = motion.light_rest_intensity[i];
  if (!motion.pointers.empty()) pose_pointers(scene, motion, pose);
  if (motion.visibility_animated) hide_invisible(scene, motion, pose);
  const std::vector<std::vector<float>> weights = posed_morph_weights(motion, pose);
  Vertices v;
  for (const DeformingMesh& d : motion.deforming) {
    Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
    deform(motion, d, mesh.indices, weights[std::size_t(d.node)], world, v);
    mesh.positions.swap(v.positions);
    mesh.normals.swap(v.normals);
    mesh.tangents.swap(v.tangents);
  }
}

std::vector<glm::mat4> checked_node_transforms(const SceneMotion& motion, std::string_view source,
                                               const PoseTime& pose) {
  if (pose.animation >= int(motion.animations.size()))
    throw Error(fmt::format("{}: animation {} does not exist ({} animations)", source,
                            pose.animation, motion.animations.size()));
  if (!std::isfinite(pose.time))
    throw Error(fmt::format("{}: the animation time is not finite", source));
  std::vector<glm::mat4> world = posed_node_transforms(motion, pose);
  check_finite(motion, source, pose, world);
  return world;
}

std::vector<std::vector<float>> posed_morph_weights(const SceneMotion& motion,
                                                    const PoseTime& pose) {
  std::vector<std::vector<float>> weights(motion.nodes.size());
  for (std::size_t i = 0; i < motion.nodes.size(); ++i) weights[i] = motion.nodes[i].weights;
  if (pose.animation < 0) return weights;
  const Animation& a = motion.animations[std::size_t(pose.animation)];
  for (const AnimationChannel& ch : a.channels) {
    if (ch.property != AnimatedProperty::kWeights) continue;
    const AnimationSampler& s = a.samplers[std::size_t(ch.sampler)];
    std::vector<float>& w = weights[std::size_t(ch.node)];
    w.resize(std::size_t(s.width), 0.0f);
    sample_animation(s, pose.time, false, w.data());
  }
  return weights;
}

std::vector<glm::mat4> joint_matrices(const Skin& skin, const std::vector<glm::mat4>& world) {
  std::vector<glm::mat4> joint(skin.joints.size());
  for (std::size_t j = 0; j < joint.size(); ++j)
    joint[j] = world[std::size_t(skin.joints[j])] * skin.inverse_bind[j];
  return joint;
}

void place_instances_and_lights(const SceneMotion& motion, const std::vector<glm::mat4>& world,
                                std::vector<Instance>& instances, std::vector<Light>& lights) {
  for (const NodePlacement& p : motion.placements)
    instances[std::size_t(p.instance)].transform = world[std::size_t(p.node)] * p.offset;
  for (const DeformingMesh& d : motion.deforming)
    instances[std::size_t(d.instance)].transform =
        d.skin >= 0 ? glm::mat4(1.0f) : world[std::size_t(d.node)];
  for (std::size_t i = 0; i < motion.light_nodes.size() && i < lights.size(); ++i) {
    const glm::mat4& m = world[std::size_t(motion.light_nodes[i])];
    Light& l = lights[i];
    l.position = glm::vec3(m[3]);
    const glm::vec3 d = glm::vec3(m * glm::vec4(0, 0, -1, 0));  // lights shine along -Z
    l.direction = glm::length(d) > 0.0f ? glm::normalize(d) : glm::vec3(0, 0, -1);
  }
}

bool ShutterMotion::moving() const {
  for (std::size_t i = 0; i < transforms.size(); ++i)
    if (moving(i)) return true;
  return false;
}

ShutterMotion shutter_motion(const Scene& scene, int animation, float open, float close,
                             int steps) {
  if (!scene.motion || scene.motion->animations.empty())
    throw Error(fmt::format("{} has no animations to blur", scene.source));
  const SceneMotion& motion = *scene.motion;
  if (animation < 0 || animation >= int(motion.animations.size()))
    throw Error(fmt::format("{}: animation {} does not exist ({} animations)", scene.source,
                            animation, motion.animations.size()));
  if (!(open < close) || !std::isfinite(open) || !std::isfinite(close))
    throw Error(
        fmt::format("{}: the shutter {}:{} must open before it closes", scene.source, open, close));
  if (steps < 2 || steps > 129)  // Embree's limit on time steps
    throw Error(fmt::format("{}: {} motion steps; 2 to 129", scene.source, steps));
  const std::size_t count = scene.instances.size();
  ShutterMotion m;
  m.steps = steps;
  m.transforms.resize(count);
  m.positions.resize(count);
  m.normals.resize(count);
  std::vector<std::vector<glm::mat4>> transforms(count);
  std::vector<std::vector<Vertices>> vertices(motion.deforming.size());
  for (int k = 0; k < steps; ++k) {
    const PoseTime pose{animation, open + (close - open) * float(k) / float(steps - 1)};
    const std::vector<glm::mat4> world = posed_node_transforms(motion, pose);
    check_finite(motion, scene.source, pose, world);
    for (const NodePlacement& p : motion.placements)
      transforms[std::size_t(p.instance)].push_back(world[std::size_t(p.node)] * p.offset);
    const std::vector<std::vector<float>> weights = posed_morph_weights(motion, pose);
    for (std::size_t i = 0; i < motion.deforming.size(); ++i) {
      const DeformingMesh& d = motion.deforming[i];
      Vertices& v = vertices[i].emplace_back();
      deform(motion, d, scene.meshes[std::size_t(d.mesh)].indices, weights[std::size_t(d.node)],
             world, v);
      transforms[std::size_t(d.instance)].push_back(d.skin >= 0 ? glm::mat4(1.0f)
                                                                : world[std::size_t(d.node)]);
    }
  }
  for (std::size_t i = 0; i < count; ++i) {
    const auto& t = transforms[i];
    for (std::size_t k = 1; k < t.size(); ++k)
      if (t[k] != t[0]) {
        m.transforms[i] = t;
        break;
      }
  }
  for (std::size_t i = 0; i < motion.deforming.size(); ++i) {
    const std::size_t inst = std::size_t(motion.deforming[i].instance);
    const auto& v = vertices[i];
    bool moves = false;
    for (std::size_t k = 1; k < v.size() && !moves; ++k) moves = v[k].positions != v[0].positions;
    if (!moves) continue;
    for (const Vertices& step : v) {
      m.positions[inst].push_back(step.positions);
      m.normals[inst].push_back(step.normals);
    }
  }
  return m;
}

}  // namespace pbrkit
