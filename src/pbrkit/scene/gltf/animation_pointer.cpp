// KHR_animation_pointer: channels whose target is a JSON pointer into the glTF 2.0 Asset
// Object Model (KhronosGroup/glTF, specification/2.0/ObjectModel.adoc) rather than a node's
// transform. The pointers are taken out of the JSON before tinygltf parses it (tinygltf
// requires every channel target to name a node), then resolved to the properties pbrkit
// poses: node transforms and weights, every material factor (the core material's and,
// through the material schema, every extension's), KHR_texture_transform on any texture,
// punctual lights and cameras.
#include <cmath>
#include <limits>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

namespace {

// The JSON pointer's reference tokens (RFC 6901: "~1" is "/", "~0" is "~").
std::vector<std::string> tokens(const std::string& pointer) {
  std::vector<std::string> out;
  if (pointer.empty() || pointer[0] != '/') return out;
  std::string token;
  for (std::size_t i = 1; i <= pointer.size(); ++i) {
    if (i == pointer.size() || pointer[i] == '/') {
      out.push_back(token);
      token.clear();
    } else if (pointer[i] == '~' && i + 1 < pointer.size() &&
               (pointer[i + 1] == '0' || pointer[i + 1] == '1')) {
      token += pointer[i + 1] == '1' ? '/' : '~';
      ++i;
    } else {
      token += pointer[i];
    }
  }
  return out;
}

// A non-negative array index token; -1 when it is not one.
int index_token(const std::string& t) {
  if (t.empty() || t.size() > 9) return -1;
  int v = 0;
  for (const char c : t) {
    if (c < '0' || c > '9') return -1;
    v = v * 10 + (c - '0');
  }
  return v;
}

float* base_color(Material& m) {
  return &m.base_color_factor.x;
}
float* metallic(Material& m) {
  return &m.metallic_factor;
}
float* roughness(Material& m) {
  return &m.roughness_factor;
}
float* emissive(Material& m) {
  return &m.emissive_factor.x;
}
float* alpha_cutoff(Material& m) {
  return &m.alpha_cutoff;
}
float* normal_scale(Material& m) {
  return &m.normal_scale;
}
float* occlusion_strength(Material& m) {
  return &m.occlusion_strength;
}

}  // namespace

bool Loader::prepare_animation_pointers(json& root) {
  if (!root.contains("animations") || !root["animations"].is_array()) return false;
  bool modified = false;
  json& animations = root["animations"];
  for (std::size_t a = 0; a < animations.size(); ++a) {
    if (!animations[a].is_object() || !animations[a].contains("channels") ||
        !animations[a]["channels"].is_array())
      continue;
    json& channels = animations[a]["channels"];
    for (std::size_t c = 0; c < channels.size(); ++c) {
      if (!channels[c].is_object() || !channels[c].contains("target")) continue;
      json& target = channels[c]["target"];
      if (!target.is_object() || target.value("path", json()) != "pointer") continue;
      const std::string where =
          fmt::format("animations[{}].channels[{}].target.extensions.KHR_animation_pointer", a, c);
      const json* ext = nullptr;
      if (target.contains("extensions") && target["extensions"].is_object() &&
          target["extensions"].contains("KHR_animation_pointer"))
        ext = &target["extensions"]["KHR_animation_pointer"];
      if (!ext || !ext->is_object() || !ext->contains("pointer") || !(*ext)["pointer"].is_string())
        error(where + ".pointer", "a channel whose path is \"pointer\" needs a string pointer");
      animation_pointers_[{int(a), int(c)}] = (*ext)["pointer"].get<std::string>();
      // Nodes whose visibility an animation drives keep their meshes and lights (nodes.cpp).
      const std::string& pointer = animation_pointers_[{int(a), int(c)}];
      if (pointer.rfind("/nodes/", 0) == 0 &&
          pointer.find("/extensions/KHR_node_visibility/visible") != std::string::npos)
        visibility_animated_ = true;
      // tinygltf requires a node; the channel is read from animation_pointers_ instead.
      target["node"] = 0;
      modified = true;
    }
  }
  return modified;
}

bool Loader::resolve_pointer(const std::string& pointer, const std::string& where,
                             AnimationChannel& ch, int& width) {
  const std::vector<std::string> t = tokens(pointer);
  auto unsupported = [&](const char* why) {
    warning(fmt::format("{}: the pointer '{}' {}; the channel is ignored", where, pointer, why));
    return false;
  };
  auto index_in = [&](std::size_t token, std::size_t count, const char* what) {
    const int i = token < t.size() ? index_token(t[token]) : -1;
    if (i < 0 || std::size_t(i) >= count)
      error(where, fmt::format("the pointer '{}' names {} {}, which does not exist ({} {})",
                               pointer, what, token < t.size() ? t[token] : "", count, what));
    return i;
  };
  if (t.size() < 2) return unsupported("is not a property of the Object Model");
  PointerTarget p;
  p.pointer = pointer;
  if (t[0] == "nodes") {
    ch.node = index_in(1, model_.nodes.size(), "nodes");
    if (t.size() == 3 && t[2] == "translation")
      ch.property = AnimatedProperty::kTranslation;
    else if (t.size() == 3 && t[2] == "rotation")
      ch.property = AnimatedProperty::kRotation;
    else if (t.size() == 3 && t[2] == "scale")
      ch.property = AnimatedProperty::kScale;
    else if (t.size() == 3 && t[2] == "weights")
      ch.property = AnimatedProperty::kWeights;
    else if (t.size() == 5 && t[2] == "extensions" && t[3] == "KHR_node_visibility" &&
             t[4] == "visible") {
      p.kind = PointerTarget::Kind::kVisibility;
      p.index = ch.node;
      p.rest = {node_hidden_[std::size_t(ch.node)] ? 0.0f : 1.0f};
      ch.property = AnimatedProperty::kPointer;
      ch.node = -1;
      ch.pointer = int(motion_.pointers.size());
      width = 1;
      motion_.pointers.push_back(std::move(p));
      return true;
    } else if (t.size() >= 3 && t[2] == "extensions")
      return unsupported("animates a node extension pbrkit does not play");
    else
      return unsupported("is not an animatable node property");
    width = ch.property == AnimatedProperty::kRotation  ? 4
            : ch.property == AnimatedProperty::kWeights ? -1  // the caller's morph target count
                                                        : 3;
    return true;
  }
  if (t[0] == "materials") {
    p.index = index_in(1, scene_.materials.size(), "materials");
    Material& m = scene_.materials[std::size_t(p.index)];
    const std::vector<std::string> rest(t.begin() + 2, t.end());
    // A texture's KHR_texture_transform: the textureInfo's path, then the extension's.
    const std::size_t n = rest.size();
    if (n >= 4 && rest[n - 3] == "extensions" && rest[n - 2] == "KHR_texture_transform") {
      const std::vector<std::string> info(rest.begin(), rest.end() - 3);
      bool found = false;
      auto slot_is = [&](std::initializer_list<const char*> path, TextureSlot slot) {
        if (found || info.size() != path.size()) return;
        std::size_t k = 0;
        for (const char* part : path)
          if (info[k++] != part) return;
        p.slot = slot;
        found = true;
      };
      slot_is({"pbrMetallicRoughness", "baseColorTexture"}, TextureSlot::kBaseColor);
      slot_is({"pbrMetallicRoughness", "metallicRoughnessTexture"},
              TextureSlot::kMetallicRoughness);
      slot_is({"normalTexture"}, TextureSlot::kNormal);
      slot_is({"occlusionTexture"}, TextureSlot::kOcclusion);
      slot_is({"emissiveTexture"}, TextureSlot::kEmissive);
      if (!found && info.size() == 3 && info[0] == "extensions")
        if (const MaterialExtension* e = find_material_extension(info[1]))
          for (const MaterialTexture& tex : e->textures)
            if (info[2] == tex.json_name && e->present(m)) {
              p.slot = tex.slot;
              found = true;
            }
      if (!found) return unsupported("names no texture of the material");
      TextureRef& ref = texture_in(m, p.slot);
      if (!ref.valid()) return unsupported("names a texture the material does not have");
      if (!ref.transform) ref.transform = TextureTransform{};
      const std::string& field = rest[n - 1];
      p.kind = PointerTarget::Kind::kTextureTransform;
      if (field == "offset")
        p.field = 0, p.components = 2;
      else if (field == "rotation")
        p.field = 1, p.components = 1;
      else if (field == "scale")
        p.field = 2, p.components = 2;
      else
        return unsupported("is not offset, rotation or scale of KHR_texture_transform");
      const TextureTransform& tt = *ref.transform;
      p.rest = p.field == 0   ? std::vector<float>{tt.offset.x, tt.offset.y}
               : p.field == 1 ? std::vector<float>{tt.rotation}
                              : std::vector<float>{tt.scale.x, tt.scale.y};
    } else {
      p.kind = PointerTarget::Kind::kMaterial;
      const float inf = std::numeric_limits<float>::infinity();
      // The core material's ranges (glTF 2.0 section 5.19, 5.22).
      auto core = [&](std::initializer_list<const char*> path, float* (*value)(Material&),
                      int components, float lo, float hi) {
        if (p.material_value || rest.size() != path.size()) return;
        std::size_t k = 0;
        for (const char* part : path)
          if (rest[k++] != part) return;
        p.material_value = value;
        p.components = components;
        p.min = lo;
        p.max = hi;
      };
      core({"pbrMetallicRoughness", "baseColorFactor"}, base_color, 4, 0.0f, 1.0f);
      core({"pbrMetallicRoughness", "metallicFactor"}, metallic, 1, 0.0f, 1.0f);
      core({"pbrMetallicRoughness", "roughnessFactor"}, roughness, 1, 0.0f, 1.0f);
      core({"emissiveFactor"}, emissive, 3, 0.0f, 1.0f);
      core({"alphaCutoff"}, alpha_cutoff, 1, 0.0f, inf);
      core({"normalTexture", "scale"}, normal_scale, 1, -inf, inf);
      core({"occlusionTexture", "strength"}, occlusion_strength, 1, 0.0f, 1.0f);
      if (!p.material_value && rest.size() == 3 && rest[0] == "extensions")
        if (const MaterialExtension* e = find_material_extension(rest[1]))
          for (const MaterialFactor& f : e->factors)
            if (rest[2] == f.json_name) {
              // Added with the README's defaults when absent: a value equal to no
              // extension at all, which the animation then moves.
              if (!e->present(m)) e->add(m);
              p.material_value = f.values;
              p.components = f.components;
              p.min = f.min;
              p.max = f.max;
            }
      if (!p.material_value) return unsupported("is not a material factor pbrkit renders");
      const float* v = p.material_value(m);
      p.rest.assign(v, v + p.components);
    }
  } else if (t[0] == "extensions" && t.size() >= 5 && t[1] == "KHR_lights_punctual" &&
             t[2] == "lights") {
    p.kind = PointerTarget::Kind::kLight;
    p.index = index_in(3, model_.lights.size(), "lights");
    const auto& l = model_.lights[std::size_t(p.index)];
    const std::string field = t.size() == 6 ? t[4] + "/" + t[5] : t[4];
    if (field == "color" && t.size() == 5) {
      p.field = 0, p.components = 3;
      for (std::size_t c = 0; c < 3; ++c)
        p.rest.push_back(l.color.size() == 3 ? float(l.color[c]) : 1.0f);
    } else if (field == "intensity") {
      p.field = 1, p.rest = {float(l.intensity)};
    } else if (field == "range") {
      p.field = 2,
      p.rest = {l.range > 0.0 ? float(l.range) : std::numeric_limits<float>::infinity()};
    } else if (field == "spot/innerConeAngle") {
      p.field = 3, p.rest = {float(l.spot.innerConeAngle)};
    } else if (field == "spot/outerConeAngle") {
      p.field = 4, p.rest = {float(l.spot.outerConeAngle)};
    } else {
      return unsupported("is not an animatable light property");
    }
  } else if (t[0] == "cameras" && t.size() == 4) {
    p.kind = PointerTarget::Kind::kCamera;
    p.index = index_in(1, model_.cameras.size(), "cameras");
    const auto& c = model_.cameras[std::size_t(p.index)];
    const std::string field = t[2] + "/" + t[3];
    if (field == "perspective/yfov")
      p.field = 0, p.rest = {float(c.perspective.yfov)};
    else if (field == "perspective/znear")
      p.field = 1, p.rest = {float(c.perspective.znear)};
    else if (field == "perspective/zfar")
      p.field = 2, p.rest = {c.perspective.zfar > 0.0 ? float(c.perspective.zfar)
                                                      : std::numeric_limits<float>::infinity()};
    else if (field == "perspective/aspectRatio")
      p.field = 3, p.rest = {float(c.perspective.aspectRatio)};
    else if (field == "orthographic/xmag")
      p.field = 4, p.rest = {float(c.orthographic.xmag)};
    else if (field == "orthographic/ymag")
      p.field = 5, p.rest = {float(c.orthographic.ymag)};
    else if (field == "orthographic/znear")
      p.field = 1, p.rest = {float(c.orthographic.znear)};
    else if (field == "orthographic/zfar")
      p.field = 2, p.rest = {float(c.orthographic.zfar)};
    else
      return unsupported("is not an animatable camera property");
  } else {
    return unsupported("is not a property pbrkit animates");
  }
  ch.property = AnimatedProperty::kPointer;
  ch.node = -1;
  ch.pointer = int(motion_.pointers.size());
  width = p.components;
  motion_.pointers.push_back(std::move(p));
  return true;
}

}  // namespace pbrkit::gltf
