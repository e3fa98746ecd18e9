#include "pbrkit/scene/scene.h"

namespace pbrkit {

Bounds Scene::world_bounds() const {
  Bounds bounds;
  for (const Instance& instance : instances) {
    if (instance.mesh < 0 || instance.mesh >= int(meshes.size())) continue;
    // A zero transform places nothing (a node hidden by an animation, scene/pose.h).
    if (instance.transform == glm::mat4(0.0f)) continue;
    for (const glm::vec3& p : meshes[std::size_t(instance.mesh)].positions)
      bounds.extend(glm::vec3(instance.transform * glm::vec4(p, 1.0f)));
  }
  return bounds;
}

std::array<const TextureRef*, kTextureSlotCount> Material::textures() const {
  static const TextureRef kNone;
  auto in = [](const auto& ext, auto member) -> const TextureRef* {
    return ext ? &((*ext).*member) : &kNone;
  };
  return {&base_color_texture,
          &metallic_roughness_texture,
          &normal_texture,
          &occlusion_texture,
          &emissive_texture,
          in(specular, &SpecularExtension::texture),
          in(specular, &SpecularExtension::color_texture),
          in(clearcoat, &ClearcoatExtension::texture),
          in(clearcoat, &ClearcoatExtension::roughness_texture),
          in(clearcoat, &ClearcoatExtension::normal_texture),
          in(sheen, &SheenExtension::color_texture),
          in(sheen, &SheenExtension::roughness_texture),
          in(anisotropy, &AnisotropyExtension::texture),
          in(iridescence, &IridescenceExtension::texture),
          in(iridescence, &IridescenceExtension::thickness_texture),
          in(transmission, &TransmissionExtension::texture),
          in(volume, &VolumeExtension::thickness_texture),
          in(diffuse_transmission, &DiffuseTransmissionExtension::texture),
          in(diffuse_transmission, &DiffuseTransmissionExtension::color_texture)};
}

const Material& Scene::material_of(const Mesh& mesh) const {
  if (mesh.material >= 0 && mesh.material < int(materials.size()))
    return materials[std::size_t(mesh.material)];
  return default_material();
}

std::size_t Scene::triangle_count() const {
  std::size_t count = 0;
  for (const Instance& instance : instances)
    if (instance.mesh >= 0 && instance.mesh < int(meshes.size()))
      count += meshes[std::size_t(instance.mesh)].triangle_count();
  return count;
}

bool has_alpha(const Scene& scene, const Mesh& mesh) {
  const Material& m = scene.material_of(mesh);
  if (m.alpha_mode == AlphaMode::kOpaque) return false;
  if (m.alpha_mode == AlphaMode::kMask || m.base_color_factor.a < 1.0f) return true;
  for (const glm::vec4& c : mesh.colors0)
    if (c.a < 1.0f) return true;
  const TextureRef& ref = m.base_color_texture;
  if (!ref.valid() || std::size_t(ref.texture) >= scene.textures.size()) return false;
  // Smaller mips average the level above, so level 0 holds every alpha below 1.
  return scene.textures[std::size_t(ref.texture)].min_alpha() < 1.0f;
}

const Material& Scene::default_material() {
  // glTF 2.0 section 3.9.1: a primitive without a material uses the defaults of every
  // property, i.e. a rough (roughness 1), fully metallic, white material.
  static const Material kDefault = [] {
    Material m;
    m.name = "default";
    return m;
  }();
  return kDefault;
}

}  // namespace pbrkit
