// The KHR_materials_* extensions of a material, read as the material schema
// (scene/material_schema.h) lists them: each extension's factors and textures, by their
// README's names (KhronosGroup/glTF, extensions/2.0/Khronos/). Absent values keep the
// README's defaults (Material's own).
//
// What the loader does with values the schemas do not allow:
// - a wrong JSON type (an extension that is not an object, a factor that is not a number,
//   a colour that is not 3 numbers, a texture that is not a textureInfo) is an error;
// - a value that is not finite (also a double that overflows a float) is an error;
// - a number outside its schema range is a warning naming its JSON path, and is clamped
//   to that range (the schema's rows say where the loader is stricter than a schema:
//   attenuationColor and diffuseTransmissionColorFactor are clamped to 1);
// - the values a range cannot describe have a check of their own in the schema:
//   KHR_materials_ior.ior 0 (the specular-glossiness mode),
//   KHR_materials_volume.attenuationDistance (an open range with an infinite default), and
//   a negative KHR_materials_emissive_strength.emissiveStrength, which is an error;
// - combinations that the READMEs give no effect (a volume with neither transmission nor
//   diffuse transmission, dispersion without a volume, doubleSided on a volume boundary,
//   unlit with any other) are warnings that say so; the values are kept.
//
// Whether a volume's mesh is closed is decided per primitive in meshes.cpp (Mesh::closed).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

std::string type_name(const json& v) {
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  return "null";
}

std::string range_text(float lo, float hi) {
  return hi == kInf ? fmt::format(">= {:g}", lo) : fmt::format("in [{:g}, {:g}]", lo, hi);
}

// The JSON value as tinygltf holds extension values (for texture_ref's
// KHR_texture_transform); integers outside int's range become doubles.
tinygltf::Value to_value(const json& v) {
  if (v.is_object()) {
    tinygltf::Value::Object o;
    for (const auto& [key, value] : v.items()) o[key] = to_value(value);
    return tinygltf::Value(std::move(o));
  }
  if (v.is_array()) {
    tinygltf::Value::Array a;
    for (const json& e : v) a.push_back(to_value(e));
    return tinygltf::Value(std::move(a));
  }
  if (v.is_number_integer() && v.get<std::int64_t>() >= std::numeric_limits<int>::min() &&
      v.get<std::int64_t>() <= std::numeric_limits<int>::max())
    return tinygltf::Value(int(v.get<std::int64_t>()));
  if (v.is_number()) return tinygltf::Value(v.get<double>());
  if (v.is_string()) return tinygltf::Value(v.get<std::string>());
  if (v.is_boolean()) return tinygltf::Value(v.get<bool>());
  return {};
}

}  // namespace

// `v` as a float; an error when it is not finite or a float cannot hold it.
float Loader::finite_float(const json& v, const std::string& path) const {
  const double d = v.get<double>();
  if (!std::isfinite(d) || std::fabs(d) > double(std::numeric_limits<float>::max()))
    error(path, "is not finite (or too large for a float)");
  return float(d);
}

float Loader::extension_factor(const json& ext, const char* name, float fallback, float lo,
                               float hi, const std::string& where) {
  const auto it = ext.find(name);
  if (it == ext.end()) return fallback;
  const std::string path = where + "." + name;
  if (!it->is_number()) error(path, fmt::format("must be a number, not {}", type_name(*it)));
  const float value = finite_float(*it, path);
  if (value < lo || value > hi) {
    const float clamped = std::min(std::max(value, lo), hi);
    warning(fmt::format("{}: {:g} is outside the valid range ({}); using {:g}", path, value,
                        range_text(lo, hi), clamped));
    return clamped;
  }
  return value;
}

glm::vec3 Loader::extension_color(const json& ext, const char* name, glm::vec3 fallback, float lo,
                                  float hi, const std::string& where) {
  const auto it = ext.find(name);
  if (it == ext.end()) return fallback;
  const std::string path = where + "." + name;
  const json& v = *it;
  if (!v.is_array() || v.size() != 3)
    error(path, fmt::format("must be an array of 3 numbers, not {}{}", type_name(v),
                            v.is_array() ? fmt::format(" of {}", v.size()) : ""));
  glm::vec3 color;
  bool clamped = false;
  for (int c = 0; c < 3; ++c) {
    const json& e = v[std::size_t(c)];
    const std::string element = fmt::format("{}[{}]", path, c);
    if (!e.is_number()) error(element, fmt::format("must be a number, not {}", type_name(e)));
    color[c] = finite_float(e, element);
    if (color[c] < lo || color[c] > hi) clamped = true;
  }
  if (clamped) {
    const glm::vec3 out = glm::clamp(color, glm::vec3(lo), glm::vec3(hi));
    warning(
        fmt::format("{}: ({:g}, {:g}, {:g}) is outside the valid range (each component {}); using "
                    "({:g}, {:g}, {:g})",
                    path, color.r, color.g, color.b, range_text(lo, hi), out.r, out.g, out.b));
    return out;
  }
  return color;
}

TextureRef Loader::extension_texture(const json& ext, const char* name, bool srgb,
                                     const std::string& where, float* scale) {
  const auto it = ext.find(name);
  if (it == ext.end()) return {};
  const std::string path = where + "." + name;
  const json& info = *it;
  if (!info.is_object())
    error(path, fmt::format("must be a textureInfo object, not {}", type_name(info)));
  const auto index = info.find("index");
  if (index == info.end() || !index->is_number_integer())
    error(path + ".index", "missing or not an integer");
  const std::int64_t texture = index->get<std::int64_t>();
  if (texture < 0 || texture > std::numeric_limits<int>::max())
    error(path + ".index", fmt::format("texture {} does not exist", texture));
  int texcoord = 0;
  if (const auto tc = info.find("texCoord"); tc != info.end()) {
    if (!tc->is_number_integer()) error(path + ".texCoord", "must be an integer");
    // texture_ref warns about any set but 0 and 1.
    texcoord = int(std::clamp<std::int64_t>(tc->get<std::int64_t>(), -1, 2));
  }
  tinygltf::ExtensionMap extensions;
  if (const auto e = info.find("extensions"); e != info.end()) {
    if (!e->is_object()) error(path + ".extensions", "must be an object");
    for (const auto& [key, value] : e->items()) extensions[key] = to_value(value);
  }
  if (scale) *scale = extension_factor(info, "scale", 1.0f, -kInf, kInf, path);
  return texture_ref(int(texture), texcoord, extensions, srgb, path);
}

const json* Loader::extension_object(const json& extensions, const char* name,
                                     const std::string& where) const {
  const auto it = extensions.find(name);
  if (it == extensions.end()) return nullptr;
  if (!it->is_object())
    error(where + ".extensions." + name, fmt::format("must be an object, not {}", type_name(*it)));
  return &*it;
}

void Loader::extension_values(const json& ext, const MaterialFactor& factor,
                              const std::string& where, float* values) {
  if (factor.components == 3) {
    const glm::vec3 color = extension_color(
        ext, factor.json_name, {values[0], values[1], values[2]}, factor.min, factor.max, where);
    for (int c = 0; c < 3; ++c) values[c] = color[c];
    return;
  }
  if (!factor.check) {
    *values = extension_factor(ext, factor.json_name, *values, factor.min, factor.max, where);
    return;
  }
  const float read = extension_factor(ext, factor.json_name, *values, -kInf, kInf, where);
  float value = read;
  if (const char* why = factor.check(value)) {
    if (factor.rejected_is_error) error(where + "." + factor.json_name, why);
    warning(fmt::format("{}.{}: {:g} is invalid {}", where, factor.json_name, read, why));
  }
  *values = value;
}

void Loader::read_material_extensions(const json& extensions, const std::string& where,
                                      Material& m) {
  for (const MaterialExtension& x : material_schema()) {
    const json* e = extension_object(extensions, x.name, where);
    if (!e) continue;
    const std::string path = where + ".extensions." + x.name;
    x.add(m);
    for (const MaterialFactor& f : x.factors) extension_values(*e, f, path, f.values(m));
    for (const MaterialTexture& t : x.textures)
      texture_in(m, t.slot) =
          extension_texture(*e, t.json_name, t.srgb, path, t.scale ? t.scale(m) : nullptr);
  }
  warn_ineffective_combinations(extensions, where, m);
}

// Combinations the READMEs give no effect: said, and kept as the file has them.
void Loader::warn_ineffective_combinations(const json& extensions, const std::string& where,
                                           const Material& m) {
  if (m.volume && !m.transmission && !m.diffuse_transmission)
    // KHR_materials_volume, "Dependencies": the volume needs an extension that lets light
    // through the surface.
    warning(fmt::format(
        "{}.extensions.KHR_materials_volume: has no effect without KHR_materials_transmission "
        "or KHR_materials_diffuse_transmission (no light enters the volume)",
        where));
  if (m.dispersion && m.dispersion->dispersion > 0.0f &&
      !(m.volume && m.volume->thickness_factor > 0.0f))
    // KHR_materials_dispersion, "Dependencies": it spreads the refraction through a volume;
    // a thin-walled surface does not refract.
    warning(fmt::format(
        "{}.extensions.KHR_materials_dispersion: has no effect without KHR_materials_volume "
        "with thicknessFactor > 0 (a thin-walled surface does not refract)",
        where));
  if (m.volume && m.volume->thickness_factor > 0.0f && m.double_sided)
    // KHR_materials_volume, "Properties": doubleSided has no effect on volume boundaries.
    warning(
        fmt::format("{}.doubleSided: has no effect on a volume boundary (KHR_materials_volume with "
                    "thicknessFactor > 0): both sides of the mesh bound the medium",
                    where));
  // KHR_materials_unlit: every other extension names it among its exclusions.
  for (const MaterialExtension& alone : material_schema()) {
    if (!alone.exclusive || !alone.present(m)) continue;
    for (const MaterialExtension& other : material_schema())
      if (&other != &alone && extensions.contains(other.name))
        warning(
            fmt::format("{}.extensions: {} must not be combined with {}; the material is shown {}",
                        where, alone.name, other.name, alone.summary));
  }
}

}  // namespace pbrkit::gltf
