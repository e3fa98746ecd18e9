#include "pbrkit/scene/load.h"

#include "pbrkit/scene/gltf/load_gltf.h"

namespace pbrkit {

Scene load_scene(const std::string& path_or_name, const LoadOptions& options) {
  const std::string prefix = "builtin:";
  if (path_or_name.rfind(prefix, 0) == 0) return builtin_scene(path_or_name.substr(prefix.size()));
  if (is_builtin_scene(path_or_name)) return builtin_scene(path_or_name);
  return load_gltf(path_or_name, options);
}

}  // namespace pbrkit
