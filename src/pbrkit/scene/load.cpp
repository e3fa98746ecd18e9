#include "pbrkit/scene/load.h"

#include "pbrkit/scene/coincident_faces.h"
#include "pbrkit/scene/gltf/load_gltf.h"
#include "pbrkit/util/log.h"

namespace pbrkit {

Scene load_scene(const std::string& path_or_name, const LoadOptions& options) {
  const std::string prefix = "builtin:";
  Scene scene = path_or_name.rfind(prefix, 0) == 0
                    ? builtin_scene(path_or_name.substr(prefix.size()))
                : is_builtin_scene(path_or_name) ? builtin_scene(path_or_name)
                                                 : load_gltf(path_or_name, options);
  // A scene cut short by its progress callback is partial anyway. A search that reached
  // its work bound warns about what it found before it and says how far it got.
  if (!scene.interrupted) {
    const CoincidentFacesResult coincident = find_coincident_faces(scene);
    for (std::string& w : coincident_face_warnings(scene, coincident)) {
      warn("{}: {}", scene.source, w);
      scene.warnings.push_back(std::move(w));
    }
    if (coincident.incomplete)
      note(
          "{}: the check for transmissive faces lying on other objects' faces stopped at its "
          "work bound after {} of {} transmissive instances",
          scene.source, coincident.checked, coincident.transmissive);
  }
  return scene;
}

}  // namespace pbrkit
