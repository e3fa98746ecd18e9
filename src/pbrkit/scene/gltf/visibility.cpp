// KHR_node_visibility (README, "Extending Nodes"): a node whose `visible` is false is not
// drawn, nor are its descendants, whatever theirs says. Its meshes and its lights are
// left out of the scene ("all its visual features ... light sources ... are not
// rendered"); its cameras are kept ("Visibility affects neither cameras ...").
// build_nodes (nodes.cpp) hands a hidden node's state down to its children.
#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

void Loader::read_node_visibility(const json& root) {
  node_hidden_.clear();
  if (!root.contains("nodes")) return;
  const json& nodes = root["nodes"];  // an array of objects (check_json)
  node_hidden_.assign(nodes.size(), 0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto extensions = nodes[i].find("extensions");
    if (extensions == nodes[i].end() || !extensions->is_object()) continue;
    const auto ext = extensions->find("KHR_node_visibility");
    if (ext == extensions->end()) continue;
    const std::string where = fmt::format("nodes[{}].extensions.KHR_node_visibility", i);
    if (!ext->is_object()) error(where, fmt::format("must be an object, not {}", ext->type_name()));
    const auto visible = ext->find("visible");
    if (visible == ext->end()) continue;  // the default: true
    if (!visible->is_boolean())
      error(where + ".visible", fmt::format("must be a boolean, not {}", visible->type_name()));
    node_hidden_[i] = visible->get<bool>() ? 0 : 1;
  }
}

}  // namespace pbrkit::gltf
