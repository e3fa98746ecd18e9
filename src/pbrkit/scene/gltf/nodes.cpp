// Nodes (glTF 2.0 section 3.5): the hierarchy is checked to be a set of disjoint trees
// without recursion, then walked from the scene's roots, accumulating transforms and
// instancing meshes, cameras and lights.
#include <algorithm>
#include <cmath>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "pbrkit/scene/gltf/loader.h"
#include "pbrkit/util/log.h"

namespace pbrkit::gltf {

namespace {

bool finite_matrix(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

}  // namespace

glm::mat4 Loader::local_transform(int node) const {
  const auto& n = model_.nodes[std::size_t(node)];
  const std::string where = fmt::format("nodes[{}]", node);
  glm::mat4 m(1.0f);
  if (n.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i)
      glm::value_ptr(m)[i] = float(n.matrix[std::size_t(i)]);  // column-major
  } else {
    if (!n.matrix.empty()) error(where + ".matrix", "must have 16 numbers");
    glm::vec3 t(0.0f), s(1.0f);
    glm::quat r(1.0f, 0.0f, 0.0f, 0.0f);
    if (n.translation.size() == 3)
      t = {float(n.translation[0]), float(n.translation[1]), float(n.translation[2])};
    else if (!n.translation.empty())
      error(where + ".translation", "must have 3 numbers");
    if (n.rotation.size() == 4)  // glTF stores (x, y, z, w); glm::quat takes (w, x, y, z)
      r = glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                    float(n.rotation[2]));
    else if (!n.rotation.empty())
      error(where + ".rotation", "must have 4 numbers");
    if (n.scale.size() == 3)
      s = {float(n.scale[0]), float(n.scale[1]), float(n.scale[2])};
    else if (!n.scale.empty())
      error(where + ".scale", "must have 3 numbers");
    const float len = glm::length(r);
    if (std::isfinite(len) && len > 0.0f) r = r / len;
    m = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.0f), s);
  }
  if (!finite_matrix(m)) error(where, "transform has NaN or infinite values");
  return m;
}

void Loader::build_nodes() {
  const std::size_t count = model_.nodes.size();
  // The hierarchy must be a set of disjoint trees (glTF 2.0 section 3.5.3).
  std::vector<int> parent(count, -1);
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t k = 0; k < model_.nodes[i].children.size(); ++k) {
      const int c = model_.nodes[i].children[k];
      const std::string where = fmt::format("nodes[{}].children[{}]", i, k);
      if (c < 0 || std::size_t(c) >= count)
        error(where, fmt::format("node {} does not exist ({} nodes)", c, count));
      if (std::size_t(c) == i) error(where, fmt::format("node {} is its own child (cycle)", c));
      if (parent[std::size_t(c)] >= 0)
        error(where, fmt::format("node {} already has parent {} (cycle or shared child)", c,
                                 parent[std::size_t(c)]));
      parent[std::size_t(c)] = int(i);
    }
  // With one parent each, a cycle is a parent chain that never reaches a root.
  std::vector<char> state(count, 0);  // 0 unknown, 1 on the current chain, 2 reaches a root
  for (std::size_t i = 0; i < count; ++i) {
    std::vector<std::size_t> chain;
    for (std::size_t j = i;;) {
      if (state[j] == 2) break;
      if (state[j] == 1)
        error(fmt::format("nodes[{}]", j), "is part of a cycle in the node hierarchy");
      state[j] = 1;
      chain.push_back(j);
      if (parent[j] < 0) break;
      j = std::size_t(parent[j]);
    }
    for (std::size_t k : chain) state[k] = 2;
  }

  if (keep_motion_) keep_rest_pose(parent);

  std::vector<int> roots;
  std::vector<char> listed(count, 0);  // a flag per node, not a search: scenes list 10^5 roots
  if (!model_.scenes.empty()) {
    int s = model_.defaultScene;
    if (s < 0) s = 0;
    if (std::size_t(s) >= model_.scenes.size())
      error("scene", fmt::format("scene {} does not exist", s));
    if (model_.scenes.size() > 1)
      note("{}: {} scenes; showing scene {}", file_, model_.scenes.size(), s);
    for (std::size_t k = 0; k < model_.scenes[std::size_t(s)].nodes.size(); ++k) {
      const int r = model_.scenes[std::size_t(s)].nodes[k];
      const std::string where = fmt::format("scenes[{}].nodes[{}]", s, k);
      if (r < 0 || std::size_t(r) >= count) error(where, fmt::format("node {} does not exist", r));
      if (parent[std::size_t(r)] >= 0)
        error(where,
              fmt::format("node {} is not a root (its parent is {})", r, parent[std::size_t(r)]));
      if (listed[std::size_t(r)]) error(where, fmt::format("node {} is listed twice", r));
      listed[std::size_t(r)] = 1;
      roots.push_back(r);
    }
  } else {
    for (std::size_t i = 0; i < count; ++i)
      if (parent[i] < 0) roots.push_back(int(i));
  }

  std::map<int, std::vector<int>> mesh_cache;  // glTF mesh -> our meshes (default weights)
  std::vector<std::pair<int, glm::mat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::mat4(1.0f)});
  std::vector<int> morphed;  // a node's own meshes when its weights differ from the mesh's
  // Progress: the JSON and the model are parsed by now (half the time of a file of many
  // small nodes); the other half is this walk.
  std::size_t visited = 0;
  bool go_on = report_progress(0.5, "nodes");
  while (!stack.empty()) {
    // Stopped (util/progress.h): the scene keeps the nodes set up so far.
    if (!go_on) {
      scene_.interrupted = true;
      warning(fmt::format("the load was stopped: {} of {} nodes set up", visited, count));
      break;
    }
    const auto [node, parent_world] = stack.back();
    stack.pop_back();
    if (++visited % 4096 == 0)
      go_on = report_progress(0.5 + 0.5 * double(visited) / double(count),
                              fmt::format("{} of {} nodes", visited, count));
    const auto& n = model_.nodes[std::size_t(node)];
    const glm::mat4 world = parent_world * local_transform(node);
    if (!finite_matrix(world))
      error(fmt::format("nodes[{}]", node), "accumulated transform overflows");
    const std::string where = fmt::format("nodes[{}]", node);
    const auto instancing = node_instancing_.find(node);
    // KHR_node_visibility; when an animation drives it, every node is built and poses hide
    // what is invisible (scene/pose.h).
    const bool hidden = !visibility_animated_ && node_hidden_[std::size_t(node)];
    if (n.mesh >= 0 && !hidden) {
      if (std::size_t(n.mesh) >= model_.meshes.size())
        error(where + ".mesh", fmt::format("mesh {} does not exist", n.mesh));
      const auto& gmesh = model_.meshes[std::size_t(n.mesh)];
      const std::vector<int>* meshes = nullptr;
      if (n.skin >= 0 && std::size_t(n.skin) >= model_.skins.size())
        error(where + ".skin", fmt::format("skin {} does not exist", n.skin));
      const bool deforms = keep_motion_ && (n.skin >= 0 || weights_animated_[std::size_t(node)]);
      if (deforms) {
        // A skinned or morph-animated mesh is its own geometry (scene/pose.h).
        const std::size_t first = motion_.deforming.size();
        morphed = build_deforming_mesh(n.mesh, node, n.skin);
        for (std::size_t d = first; d < motion_.deforming.size(); ++d)
          motion_.deforming[d].instance = int(scene_.instances.size() + (d - first));
        meshes = &morphed;
        if (instancing != node_instancing_.end())
          warning(
              fmt::format("{}: EXT_mesh_gpu_instancing on a skinned or morph-animated node is "
                          "not supported; one instance drawn",
                          where));
      } else if (!n.weights.empty() && n.weights != gmesh.weights) {
        morphed = build_mesh(n.mesh, n.weights);
        meshes = &morphed;
      } else {
        auto cached = mesh_cache.find(n.mesh);
        if (cached == mesh_cache.end())
          cached = mesh_cache.emplace(n.mesh, build_mesh(n.mesh, gmesh.weights)).first;
        meshes = &cached->second;
      }
      // Instances share their mesh: what they cost is the renderer's to estimate (the path
      // tracer checks its geometry's memory before building, pt/geometry.h).
      const std::size_t first_instance = scene_.instances.size();
      if (instancing != node_instancing_.end() && !deforms) {
        // "When instancing is used on the node, the non-instanced version of the mesh
        // should not be rendered" (EXT_mesh_gpu_instancing README).
        add_gpu_instances(node, instancing->second, world, *meshes);  // instancing.cpp
      } else {
        for (int m : *meshes) scene_.instances.push_back({m, world, node});
      }
      // (add_gpu_instances places its own rows; a deforming mesh is placed by its pose.)
      if (keep_motion_ && !deforms && instancing == node_instancing_.end())
        for (std::size_t i = first_instance; i < scene_.instances.size(); ++i)
          motion_.placements.push_back({int(i), node, glm::mat4(1.0f)});
    } else if (n.mesh < 0 && instancing != node_instancing_.end()) {
      warning(
          fmt::format("{}: EXT_mesh_gpu_instancing on a node without a mesh has no defined "
                      "meaning (README); ignored",
                      where));
    }
    if (n.camera >= 0) {
      add_camera(n.camera, world, where);  // cameras.cpp
      if (keep_motion_) {
        motion_.camera_nodes.push_back(node);
        motion_.camera_sources.push_back(n.camera);
      }
    }
    if (const auto it = n.extensions.find("KHR_lights_punctual");
        !hidden && it != n.extensions.end()) {
      add_light(it->second, world, where);  // lights.cpp
      if (keep_motion_) {
        motion_.light_nodes.push_back(node);
        motion_.light_sources.push_back(it->second.Get("light").GetNumberAsInt());
        motion_.light_rest_intensity.push_back(scene_.lights.back().intensity);
      }
    }
    for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) {
      if (hidden) node_hidden_[std::size_t(*c)] = 1;
      stack.push_back({*c, world});
    }
  }
}

void Loader::keep_rest_pose(const std::vector<int>& parent) {
  const std::size_t count = model_.nodes.size();
  motion_.nodes.resize(count);
  std::vector<std::vector<int>> children(count);
  std::vector<int> roots;
  for (std::size_t i = 0; i < count; ++i) {
    const auto& n = model_.nodes[i];
    const std::string where = fmt::format("nodes[{}]", i);
    NodeRest& rest = motion_.nodes[i];
    rest.parent = parent[i];
    rest.visible = i >= node_hidden_.size() || !node_hidden_[i];  // its own flag
    // Every node, in the scene or not: a skin's joints need not be under its roots.
    const glm::mat4 m = local_transform(int(i));  // checks the numbers
    if (n.matrix.size() == 16) {
      rest.has_matrix = true;
      rest.matrix = m;
    } else {
      if (n.translation.size() == 3)
        rest.translation = {float(n.translation[0]), float(n.translation[1]),
                            float(n.translation[2])};
      if (n.rotation.size() == 4) {
        const glm::quat r(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                          float(n.rotation[2]));
        const float len = glm::length(r);
        if (std::isfinite(len) && len > 0.0f) rest.rotation = r / len;
      }
      if (n.scale.size() == 3)
        rest.scale = {float(n.scale[0]), float(n.scale[1]), float(n.scale[2])};
    }
    const std::vector<double>* w = &n.weights;
    if (w->empty() && n.mesh >= 0 && std::size_t(n.mesh) < model_.meshes.size())
      w = &model_.meshes[std::size_t(n.mesh)].weights;
    for (std::size_t k = 0; k < w->size(); ++k) {
      if (!std::isfinite((*w)[k])) error(fmt::format("{}.weights[{}]", where, k), "is not finite");
      rest.weights.push_back(float((*w)[k]));
    }
    if (parent[i] < 0)
      roots.push_back(int(i));
    else
      children[std::size_t(parent[i])].push_back(int(i));
  }
  // Parents before children (build_nodes checked that the hierarchy is a forest).
  std::vector<int> stack(roots.rbegin(), roots.rend());
  while (!stack.empty()) {
    const int node = stack.back();
    stack.pop_back();
    motion_.order.push_back(node);
    for (auto c = children[std::size_t(node)].rbegin(); c != children[std::size_t(node)].rend();
         ++c)
      stack.push_back(*c);
  }
}

}  // namespace pbrkit::gltf
