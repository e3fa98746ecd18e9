// KHR_lights_punctual: point, spot and directional lights at their node's position,
// shining along the node's -Z.
#include <cmath>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

void Loader::add_light(const tinygltf::Value& extension, const glm::mat4& world,
                       const std::string& where) {
  const tinygltf::Value& li = extension.Get("light");
  if (!li.IsInt()) error(where + ".extensions.KHR_lights_punctual.light", "must be an integer");
  const int index = li.GetNumberAsInt();
  if (index < 0 || std::size_t(index) >= model_.lights.size())
    error(where + ".extensions.KHR_lights_punctual.light",
          fmt::format("light {} does not exist", index));
  const auto& g = model_.lights[std::size_t(index)];
  const std::string lpath = fmt::format("extensions.KHR_lights_punctual.lights[{}]", index);
  Light l;
  l.name = g.name.empty() ? fmt::format("light{}", index) : g.name;
  if (g.type == "point")
    l.type = Light::Type::kPoint;
  else if (g.type == "spot")
    l.type = Light::Type::kSpot;
  else if (g.type == "directional")
    l.type = Light::Type::kDirectional;
  else
    error(lpath + ".type", fmt::format("invalid light type '{}'", g.type));
  if (g.color.size() == 3) l.color = {float(g.color[0]), float(g.color[1]), float(g.color[2])};
  l.intensity = float(g.intensity);
  if (g.range > 0.0) l.range = float(g.range);
  if (l.type == Light::Type::kSpot) {
    l.inner_cone_angle = float(g.spot.innerConeAngle);
    l.outer_cone_angle = float(g.spot.outerConeAngle);
    if (!(l.inner_cone_angle >= 0.0f && l.inner_cone_angle < l.outer_cone_angle &&
          l.outer_cone_angle <= 1.5707964f))
      error(lpath + ".spot", "needs 0 <= innerConeAngle < outerConeAngle <= pi/2");
  }
  if (!std::isfinite(l.intensity) || l.intensity < 0.0f ||
      !std::isfinite(l.color.x + l.color.y + l.color.z))
    error(lpath, "color and intensity must be finite and non-negative");
  l.position = glm::vec3(world[3]);
  const glm::vec3 d = glm::vec3(world * glm::vec4(0, 0, -1, 0));
  l.direction = glm::length(d) > 0.0f ? glm::normalize(d) : glm::vec3(0, 0, -1);
  scene_.lights.push_back(l);
}

}  // namespace pbrkit::gltf
