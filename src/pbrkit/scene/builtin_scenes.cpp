// The built-in scenes, generated in code so every renderer (and any other glTF tool,
// through write_glb) sees exactly the same geometry, materials and camera. This file
// names them; each family's scenes are in builtin/.
#include <algorithm>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/builtin/builtin.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace builtin {

Camera look_at_camera(const std::string& name, glm::vec3 eye, glm::vec3 target, float yfov) {
  Camera camera;
  camera.name = name;
  camera.type = Camera::Type::kPerspective;
  camera.yfov = yfov;
  camera.aspect_ratio = 1.0f;
  camera.znear = 0.05f;
  camera.camera_to_world = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  return camera;
}

Material diffuse(const std::string& name, glm::vec3 color) {
  Material m;
  m.name = name;
  m.base_color_factor = glm::vec4(color, 1.0f);
  m.metallic_factor = 0.0f;
  m.roughness_factor = 1.0f;
  return m;
}

Material base_material(glm::vec3 color, float metallic, float roughness) {
  Material m;
  m.base_color_factor = glm::vec4(color, 1.0f);
  m.metallic_factor = metallic;
  m.roughness_factor = roughness;
  return m;
}

}  // namespace builtin

std::vector<std::string> builtin_scene_names() {
  return {"spheres",    "furnace",     "cornell",   "clearcoat", "sheen",
          "anisotropy", "iridescence", "specular",  "ior",       "unlit",
          "glass",      "liquid",      "instances", "lights",    "interior"};
}

bool is_builtin_scene(const std::string& name) {
  const auto names = builtin_scene_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Scene builtin_scene(const std::string& name) {
  if (name == "spheres") return builtin::make_spheres();
  if (name == "furnace") return builtin::make_furnace();
  if (name == "cornell") return builtin::make_cornell();
  if (name == "clearcoat") return builtin::make_clearcoat();
  if (name == "sheen") return builtin::make_sheen();
  if (name == "anisotropy") return builtin::make_anisotropy();
  if (name == "iridescence") return builtin::make_iridescence();
  if (name == "specular") return builtin::make_specular();
  if (name == "ior") return builtin::make_ior();
  if (name == "unlit") return builtin::make_unlit();
  if (name == "glass") return builtin::make_glass();
  if (name == "liquid") return builtin::make_liquid();
  if (name == "instances") return builtin::make_instances();
  if (name == "lights") return builtin::make_lights();
  if (name == "interior") return builtin::make_interior();
  std::string known;
  for (const std::string& n : builtin_scene_names()) known += (known.empty() ? "" : ", ") + n;
  fail("unknown built-in scene '{}' (known: {})", name, known);
}

}  // namespace pbrkit
