// EXT_mesh_gpu_instancing (KhronosGroup/glTF, extensions/2.0/Vendor/EXT_mesh_gpu_instancing):
// a mesh node drawn once per row of its instance attributes, at
// NodeWorldXform * Translation * Rotation * Scale. The README's table gives each attribute's
// accessor type: TRANSLATION and SCALE VEC3 of FLOAT, ROTATION VEC4 of FLOAT or normalized
// BYTE or SHORT; "all attribute accessors in a given node must have the same count".
// Custom attributes (a leading underscore) are checked as accessors and otherwise ignored.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

namespace {

const char* component_name(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "FLOAT";
    default:
      return "an invalid component type";
  }
}

}  // namespace

void Loader::add_gpu_instances(int node, const json& extension, const glm::mat4& world,
                               const std::vector<int>& meshes) {
  const std::string where = fmt::format("nodes[{}].extensions.EXT_mesh_gpu_instancing", node);
  if (!extension.is_object()) error(where, "must be an object");
  const auto attrs = extension.find("attributes");
  if (attrs == extension.end() || !attrs->is_object() || attrs->empty())
    error(where + ".attributes", "must be an object with at least one attribute");

  // Every attribute an accessor, all of one count.
  std::size_t count = 0;
  std::string count_from;
  int translation = -1, rotation = -1, scale = -1;
  for (const auto& [name, value] : attrs->items()) {
    const std::string at = where + ".attributes." + name;
    if (!value.is_number_integer()) error(at, "must be an accessor index");
    const auto index = value.get<std::int64_t>();
    if (index < 0 || std::size_t(index) >= model_.accessors.size())
      error(at, fmt::format("accessor {} does not exist ({} accessors)", index,
                            model_.accessors.size()));
    const AccessorView view = accessor_view(int(index), at);
    const tinygltf::Accessor& a = *view.accessor;
    if (count_from.empty()) {
      count = a.count;
      count_from = name;
    } else if (a.count != count) {
      error(at, fmt::format("accessors[{}] has {} elements but {} has {}; all instance "
                            "attributes must have the same count",
                            index, a.count, count_from, count));
    }
    const bool is_float = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const char* type = view.components == 3 ? "VEC3" : view.components == 4 ? "VEC4" : "other";
    if (name == "TRANSLATION" || name == "SCALE") {
      if (view.components != 3 || !is_float)
        error(at, fmt::format("accessors[{}] is {} of {}; {} must be VEC3 of FLOAT", index, type,
                              component_name(a.componentType), name));
      (name == "TRANSLATION" ? translation : scale) = int(index);
    } else if (name == "ROTATION") {
      const bool normalized_int =
          a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                           a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT);
      if (view.components != 4 || !(is_float || normalized_int))
        error(at, fmt::format("accessors[{}] is {} of {}{}; ROTATION must be VEC4 of FLOAT, or of "
                              "normalized BYTE or SHORT",
                              index, type, a.normalized ? "normalized " : "",
                              component_name(a.componentType)));
      rotation = int(index);
    } else if (name.empty() || name[0] != '_') {
      warning(
          fmt::format("{}: attribute '{}' is not TRANSLATION, ROTATION, SCALE or a custom "
                      "(_NAME) attribute; ignored",
                      at, name));
    }
  }

  // Instanced triangles do not count toward max_triangles (which limits unique ones): the
  // instances share their mesh, and the path tracer estimates its memory before building.

  // One allocation per attribute, none per instance (10^6 instances load in well under a
  // second).
  const std::vector<float> t =
      translation >= 0 ? read_floats(translation, where + ".attributes.TRANSLATION", 3, false)
                       : std::vector<float>();
  const std::vector<float> r = rotation >= 0
                                   ? read_floats(rotation, where + ".attributes.ROTATION", 4, true)
                                   : std::vector<float>();
  const std::vector<float> s =
      scale >= 0 ? read_floats(scale, where + ".attributes.SCALE", 3, false) : std::vector<float>();
  scene_.instances.reserve(scene_.instances.size() + count * meshes.size());
  for (std::size_t i = 0; i < count; ++i) {
    glm::mat4 local(1.0f);
    if (!t.empty()) {
      const glm::vec3 v(t[3 * i], t[3 * i + 1], t[3 * i + 2]);
      if (!std::isfinite(v.x + v.y + v.z))
        error(
            fmt::format("{}.attributes.TRANSLATION", where),
            fmt::format("instance {}'s translation ({}, {}, {}) is not finite", i, v.x, v.y, v.z));
      local = glm::translate(local, v);
    }
    if (!r.empty()) {
      // glTF stores (x, y, z, w); glm::quat takes (w, x, y, z). A rotation is a unit
      // quaternion; quantized ones are only nearly so, and are renormalized.
      glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
      const float len = glm::length(q);
      if (!std::isfinite(len) || len < 1e-3f)
        error(fmt::format("{}.attributes.ROTATION", where),
              fmt::format("instance {}'s rotation ({}, {}, {}, {}) is not a unit quaternion", i,
                          q.x, q.y, q.z, q.w));
      local = local * glm::mat4_cast(q / len);
    }
    if (!s.empty()) {
      const glm::vec3 v(s[3 * i], s[3 * i + 1], s[3 * i + 2]);
      // A zero scale makes the instance matrix singular: its normals (the inverse
      // transpose) do not exist.
      if (!std::isfinite(v.x + v.y + v.z) || v.x == 0.0f || v.y == 0.0f || v.z == 0.0f)
        error(fmt::format("{}.attributes.SCALE", where),
              fmt::format("instance {}'s scale ({}, {}, {}) makes a singular or non-finite "
                          "transform",
                          i, v.x, v.y, v.z));
      local = glm::scale(local, v);
    }
    const glm::mat4 instance_world = world * local;
    const float det = glm::determinant(glm::mat3(instance_world));
    const glm::vec4 origin = instance_world[3];
    if (!std::isfinite(det + origin.x + origin.y + origin.z))
      error(where, fmt::format("instance {}'s world transform is not finite", i));
    for (const int m : meshes) {
      if (keep_motion_)  // the row moves with its node (scene/pose.h)
        motion_.placements.push_back({int(scene_.instances.size()), node, local});
      scene_.instances.push_back({m, instance_world, node});
    }
  }
}

}  // namespace pbrkit::gltf
