// Cameras (glTF 2.0 section 3.10): perspective (infinite when zfar is absent) or
// orthographic, placed by the rigid part of their node's transform.
#include <cmath>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

void Loader::add_camera(int camera, const glm::mat4& world, const std::string& where) {
  if (std::size_t(camera) >= model_.cameras.size())
    error(where + ".camera", fmt::format("camera {} does not exist", camera));
  const auto& g = model_.cameras[std::size_t(camera)];
  const std::string cpath = fmt::format("cameras[{}]", camera);
  Camera c;
  c.name = g.name.empty() ? cpath : g.name;
  if (g.type == "perspective") {
    const auto& p = g.perspective;
    if (!(p.yfov > 0.0 && p.yfov < 3.14159))
      error(cpath + ".perspective.yfov", fmt::format("{} is not in (0, pi)", p.yfov));
    if (!(p.znear > 0.0) || !std::isfinite(p.znear))
      error(cpath + ".perspective.znear", "must be positive");
    if (p.zfar != 0.0 && !(p.zfar > p.znear))
      error(cpath + ".perspective.zfar", "must be greater than znear");
    if (p.aspectRatio < 0.0 || !std::isfinite(p.aspectRatio))
      error(cpath + ".perspective.aspectRatio", "must be positive");
    c.type = Camera::Type::kPerspective;
    c.yfov = float(p.yfov);
    if (p.aspectRatio > 0.0) c.aspect_ratio = float(p.aspectRatio);
    c.znear = float(p.znear);
    if (p.zfar > 0.0 && std::isfinite(p.zfar)) c.zfar = float(p.zfar);
  } else if (g.type == "orthographic") {
    const auto& o = g.orthographic;
    if (!(std::fabs(o.xmag) > 0.0) || !(std::fabs(o.ymag) > 0.0) || !std::isfinite(o.xmag) ||
        !std::isfinite(o.ymag))
      error(cpath + ".orthographic", "xmag and ymag must be non-zero");
    if (!(o.znear >= 0.0) || !(o.zfar > o.znear) || !std::isfinite(o.zfar))
      error(cpath + ".orthographic", "needs 0 <= znear < zfar");
    c.type = Camera::Type::kOrthographic;
    c.xmag = float(o.xmag);
    c.ymag = float(o.ymag);
    c.znear = float(o.znear);
    c.zfar = float(o.zfar);
  } else {
    error(cpath + ".type", fmt::format("invalid camera type '{}'", g.type));
  }
  // Rigid part of the node transform: the spec's cameras ignore scale.
  glm::mat4 rigid = world;
  for (int axis = 0; axis < 3; ++axis) {
    const float len = glm::length(glm::vec3(rigid[axis]));
    if (!(len > 0.0f)) error(where, "camera node has a degenerate (zero-scale) transform");
    rigid[axis] = glm::vec4(glm::vec3(rigid[axis]) / len, 0.0f);
  }
  c.camera_to_world = rigid;
  scene_.cameras.push_back(c);
}

}  // namespace pbrkit::gltf
