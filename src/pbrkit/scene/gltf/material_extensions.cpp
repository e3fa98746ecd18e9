// The KHR_materials_* extensions of a material: the surface ones (ior, specular,
// clearcoat, sheen, anisotropy, iridescence, unlit) and the transmission ones
// (transmission, volume, dispersion, diffuse_transmission); each README in
// KhronosGroup/glTF, extensions/2.0/Khronos/. Absent values keep the README's defaults
// (Material's own).
//
// What the loader does with values the schemas do not allow:
// - a wrong JSON type (an extension that is not an object, a factor that is not a number,
//   a colour that is not 3 numbers, a texture that is not a textureInfo) is an error;
// - a value that is not finite (also a double that overflows a float) is an error;
// - a number outside its schema range is a warning naming its JSON path, and is clamped
//   to that range;
// - KHR_materials_ior.ior: 0 is the README's specular-glossiness compatibility mode (an
//   infinite index, a Fresnel term of 1) and is kept as 0, which is exactly what
//   f0 = ((ior - 1) / (ior + 1))^2 gives; any other value below 1 is a warning and
//   becomes 1 (the nearest index of the ordinary range);
// - iridescenceThicknessMinimum may be greater than the maximum (the README allows it:
//   the thickness texture then interpolates downwards), so that is not a warning;
// - KHR_materials_volume.attenuationDistance: the README's range is (0, +inf); 0 or a
//   negative distance is a warning and is ignored (+inf: the medium does not absorb),
//   since sigma_t = -ln(c) / d has no finite value there;
// - attenuationColor and diffuseTransmissionColorFactor: the schemas bound them below
//   only, but a component above 1 makes light (transmittance c^(x/d) grows without bound
//   with the distance x; a transmission colour above 1 transmits more than arrives), so
//   it is a warning and is clamped to 1;
// - combinations that the READMEs give no effect (a volume with neither transmission nor
//   diffuse transmission, dispersion without a volume, doubleSided on a volume boundary)
//   are warnings that say so; the values are kept.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
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

glm::vec3 Loader::extension_color(const json& ext, const char* name, glm::vec3 fallback, float hi,
                                  const std::string& where) {
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
    if (color[c] < 0.0f || color[c] > hi) clamped = true;
  }
  if (clamped) {
    const glm::vec3 out = glm::clamp(color, glm::vec3(0.0f), glm::vec3(hi));
    warning(
        fmt::format("{}: ({:g}, {:g}, {:g}) is outside the valid range (each component {}); using "
                    "({:g}, {:g}, {:g})",
                    path, color.r, color.g, color.b, range_text(0.0f, hi), out.r, out.g, out.b));
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

void Loader::read_material_extensions(const json& extensions, const std::string& where,
                                      Material& m) {
  auto object = [&](const char* name) { return extension_object(extensions, name, where); };

  if (const json* e = object("KHR_materials_ior")) {
    const std::string path = where + ".extensions.KHR_materials_ior";
    const float ior = extension_factor(*e, "ior", 1.5f, -kInf, kInf, path);
    if (ior != 0.0f && ior < 1.0f) {
      warning(fmt::format(
          "{}.ior: {:g} is invalid (the index must be >= 1, or 0 for the specular-glossiness "
          "mode); using 1",
          path, ior));
      m.ior = 1.0f;
    } else {
      m.ior = ior;
    }
  }

  if (const json* e = object("KHR_materials_specular")) {
    const std::string path = where + ".extensions.KHR_materials_specular";
    SpecularExtension s;
    s.factor = extension_factor(*e, "specularFactor", s.factor, 0.0f, 1.0f, path);
    s.texture = extension_texture(*e, "specularTexture", false, path);
    // The schema bounds specularColorFactor below only: an F0 tint above 1 is allowed.
    s.color_factor = extension_color(*e, "specularColorFactor", s.color_factor, kInf, path);
    s.color_texture = extension_texture(*e, "specularColorTexture", true, path);
    m.specular = s;
  }

  if (const json* e = object("KHR_materials_clearcoat")) {
    const std::string path = where + ".extensions.KHR_materials_clearcoat";
    ClearcoatExtension c;
    c.factor = extension_factor(*e, "clearcoatFactor", c.factor, 0.0f, 1.0f, path);
    c.texture = extension_texture(*e, "clearcoatTexture", false, path);
    c.roughness_factor =
        extension_factor(*e, "clearcoatRoughnessFactor", c.roughness_factor, 0.0f, 1.0f, path);
    c.roughness_texture = extension_texture(*e, "clearcoatRoughnessTexture", false, path);
    c.normal_texture =
        extension_texture(*e, "clearcoatNormalTexture", false, path, &c.normal_scale);
    m.clearcoat = c;
  }

  if (const json* e = object("KHR_materials_sheen")) {
    const std::string path = where + ".extensions.KHR_materials_sheen";
    SheenExtension s;
    s.color_factor = extension_color(*e, "sheenColorFactor", s.color_factor, 1.0f, path);
    s.color_texture = extension_texture(*e, "sheenColorTexture", true, path);
    s.roughness_factor =
        extension_factor(*e, "sheenRoughnessFactor", s.roughness_factor, 0.0f, 1.0f, path);
    s.roughness_texture = extension_texture(*e, "sheenRoughnessTexture", false, path);
    m.sheen = s;
  }

  if (const json* e = object("KHR_materials_anisotropy")) {
    const std::string path = where + ".extensions.KHR_materials_anisotropy";
    AnisotropyExtension a;
    a.strength = extension_factor(*e, "anisotropyStrength", a.strength, 0.0f, 1.0f, path);
    a.rotation = extension_factor(*e, "anisotropyRotation", a.rotation, -kInf, kInf, path);
    a.texture = extension_texture(*e, "anisotropyTexture", false, path);
    m.anisotropy = a;
  }

  if (const json* e = object("KHR_materials_iridescence")) {
    const std::string path = where + ".extensions.KHR_materials_iridescence";
    IridescenceExtension i;
    i.factor = extension_factor(*e, "iridescenceFactor", i.factor, 0.0f, 1.0f, path);
    i.texture = extension_texture(*e, "iridescenceTexture", false, path);
    i.ior = extension_factor(*e, "iridescenceIor", i.ior, 1.0f, kInf, path);
    i.thickness_min =
        extension_factor(*e, "iridescenceThicknessMinimum", i.thickness_min, 0.0f, kInf, path);
    i.thickness_max =
        extension_factor(*e, "iridescenceThicknessMaximum", i.thickness_max, 0.0f, kInf, path);
    i.thickness_texture = extension_texture(*e, "iridescenceThicknessTexture", false, path);
    m.iridescence = i;
  }

  read_transmission_extensions(extensions, where, m);

  if (object("KHR_materials_unlit")) {
    m.unlit = true;
    // Every other extension here names KHR_materials_unlit among its exclusions.
    for (const char* other :
         {"KHR_materials_ior", "KHR_materials_specular", "KHR_materials_clearcoat",
          "KHR_materials_sheen", "KHR_materials_anisotropy", "KHR_materials_iridescence",
          "KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_dispersion",
          "KHR_materials_diffuse_transmission"})
      if (extensions.contains(other))
        warning(fmt::format(
            "{}.extensions: KHR_materials_unlit must not be combined with {}; the material is "
            "shown unlit",
            where, other));
  }
}

}  // namespace pbrkit::gltf
