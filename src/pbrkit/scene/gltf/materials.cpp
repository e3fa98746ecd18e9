// Materials (glTF 2.0 section 3.9, metallic-roughness) and the texture references they hold
// (texture coordinate set, KHR_texture_transform). The KHR_materials_* extensions, with
// KHR_materials_emissive_strength, are read in material_extensions.cpp.
#include <cmath>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

TextureRef Loader::texture_ref(int texture_index, int texcoord, const tinygltf::ExtensionMap& ext,
                               bool srgb, const std::string& where) {
  TextureRef ref;
  if (texture_index < 0) return ref;
  ref.texture = texture_for(texture_index, srgb, where);
  if (texcoord < 0 || texcoord > 1) {
    warning(fmt::format("{}.texCoord: set {} is not supported (only 0 and 1); using 0", where,
                        texcoord));
    texcoord = 0;
  }
  ref.texcoord = texcoord;
  if (const auto it = ext.find("KHR_texture_transform"); it != ext.end() && it->second.IsObject()) {
    const tinygltf::Value& v = it->second;
    TextureTransform t;
    auto vec2 = [&](const char* name, glm::vec2& dst) {
      const tinygltf::Value& a = v.Get(name);
      if (!a.IsArray()) return;
      if (a.ArrayLen() != 2 || !a.Get(0).IsNumber() || !a.Get(1).IsNumber())
        error(where + ".extensions.KHR_texture_transform." + name, "must be an array of 2 numbers");
      dst = {float(a.Get(0).GetNumberAsDouble()), float(a.Get(1).GetNumberAsDouble())};
    };
    vec2("offset", t.offset);
    vec2("scale", t.scale);
    if (v.Get("rotation").IsNumber()) t.rotation = float(v.Get("rotation").GetNumberAsDouble());
    if (!std::isfinite(t.offset.x + t.offset.y + t.scale.x + t.scale.y + t.rotation))
      error(where + ".extensions.KHR_texture_transform", "has non-finite values");
    if (v.Get("texCoord").IsInt()) {
      const int tc = v.Get("texCoord").GetNumberAsInt();
      if (tc == 0 || tc == 1) ref.texcoord = tc;
    }
    ref.transform = t;
  }
  return ref;
}

void Loader::build_materials() {
  for (std::size_t i = 0; i < model_.materials.size(); ++i) {
    const auto& g = model_.materials[i];
    const std::string where = fmt::format("materials[{}]", i);
    Material m;
    m.name = g.name.empty() ? fmt::format("material{}", i) : g.name;
    const auto& pbr = g.pbrMetallicRoughness;
    auto number = [&](double v, const std::string& what) {
      if (!std::isfinite(v)) error(where + what, "is not finite");
      return float(v);
    };
    if (pbr.baseColorFactor.size() == 4)
      for (int c = 0; c < 4; ++c)
        m.base_color_factor[c] =
            number(pbr.baseColorFactor[std::size_t(c)], ".pbrMetallicRoughness.baseColorFactor");
    else if (!pbr.baseColorFactor.empty())
      error(where + ".pbrMetallicRoughness.baseColorFactor", "must have 4 numbers");
    m.metallic_factor = number(pbr.metallicFactor, ".pbrMetallicRoughness.metallicFactor");
    m.roughness_factor = number(pbr.roughnessFactor, ".pbrMetallicRoughness.roughnessFactor");
    if (g.emissiveFactor.size() == 3)
      for (int c = 0; c < 3; ++c)
        m.emissive_factor[c] = number(g.emissiveFactor[std::size_t(c)], ".emissiveFactor");
    else if (!g.emissiveFactor.empty())
      error(where + ".emissiveFactor", "must have 3 numbers");
    if (g.alphaMode == "MASK")
      m.alpha_mode = AlphaMode::kMask;
    else if (g.alphaMode == "BLEND")
      m.alpha_mode = AlphaMode::kBlend;
    else if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty())
      error(where + ".alphaMode", fmt::format("invalid value '{}'", g.alphaMode));
    m.alpha_cutoff = number(g.alphaCutoff, ".alphaCutoff");
    m.double_sided = g.doubleSided;
    m.base_color_texture = texture_ref(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                       pbr.baseColorTexture.extensions, true,
                                       where + ".pbrMetallicRoughness.baseColorTexture");
    m.metallic_roughness_texture =
        texture_ref(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                    pbr.metallicRoughnessTexture.extensions, false,
                    where + ".pbrMetallicRoughness.metallicRoughnessTexture");
    m.normal_texture = texture_ref(g.normalTexture.index, g.normalTexture.texCoord,
                                   g.normalTexture.extensions, false, where + ".normalTexture");
    m.normal_scale = number(g.normalTexture.scale, ".normalTexture.scale");
    m.occlusion_texture =
        texture_ref(g.occlusionTexture.index, g.occlusionTexture.texCoord,
                    g.occlusionTexture.extensions, false, where + ".occlusionTexture");
    m.occlusion_strength = number(g.occlusionTexture.strength, ".occlusionTexture.strength");
    m.emissive_texture =
        texture_ref(g.emissiveTexture.index, g.emissiveTexture.texCoord,
                    g.emissiveTexture.extensions, true, where + ".emissiveTexture");
    read_material_extensions(
        i < material_extensions_.size() ? material_extensions_[i] : json::object(), where, m);
    scene_.materials.push_back(std::move(m));
  }
}

}  // namespace pbrkit::gltf
