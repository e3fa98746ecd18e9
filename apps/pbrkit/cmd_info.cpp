// pbrkit info FILE: a readable summary of a glTF file or built-in scene (in the spirit of
// glTF-Transform's `inspect`), or the same numbers as JSON with --json.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "pbrkit/scene/load.h"

namespace pbrkit::cli {

namespace {

struct InfoOptions {
  std::string input;
  bool json = false;
};

const char* light_type(Light::Type t) {
  return t == Light::Type::kPoint ? "point" : t == Light::Type::kSpot ? "spot" : "directional";
}

const char* alpha_mode(AlphaMode m) {
  return m == AlphaMode::kOpaque ? "opaque" : m == AlphaMode::kMask ? "mask" : "blend";
}

// The texture slots a material uses, by glTF name.
std::vector<std::string> material_textures(const Material& m) {
  std::vector<std::string> out;
  for (std::size_t t = 0; t < kTextureSlotNames.size(); ++t)
    if (m.textures()[t]->valid()) out.emplace_back(kTextureSlotNames[t]);
  return out;
}

nlohmann::json vec3_json(glm::vec3 v) {
  return {v.r, v.g, v.b};
}

// A texture reference as glTF names it: the scene texture, its texCoord and transform.
nlohmann::json texture_json(const TextureRef& ref) {
  nlohmann::json t = {{"texture", ref.texture}, {"texCoord", ref.texcoord}};
  if (ref.transform)
    t["KHR_texture_transform"] = {{"offset", {ref.transform->offset.x, ref.transform->offset.y}},
                                  {"rotation", ref.transform->rotation},
                                  {"scale", {ref.transform->scale.x, ref.transform->scale.y}}};
  return t;
}

// The KHR_materials_* extensions a material uses, each with every value (defaults
// included) and its textures, under the extension's own property names.
nlohmann::json material_extensions(const Material& m) {
  nlohmann::json out = nlohmann::json::object();
  auto texture = [](nlohmann::json& o, const char* name, const TextureRef& ref) {
    if (ref.valid()) o[name] = texture_json(ref);
  };
  if (m.ior != 1.5f) out["KHR_materials_ior"] = {{"ior", m.ior}};
  if (m.specular) {
    const SpecularExtension& e = *m.specular;
    nlohmann::json o = {{"specularFactor", e.factor},
                        {"specularColorFactor", vec3_json(e.color_factor)}};
    texture(o, "specularTexture", e.texture);
    texture(o, "specularColorTexture", e.color_texture);
    out["KHR_materials_specular"] = o;
  }
  if (m.clearcoat) {
    const ClearcoatExtension& e = *m.clearcoat;
    nlohmann::json o = {{"clearcoatFactor", e.factor},
                        {"clearcoatRoughnessFactor", e.roughness_factor}};
    texture(o, "clearcoatTexture", e.texture);
    texture(o, "clearcoatRoughnessTexture", e.roughness_texture);
    texture(o, "clearcoatNormalTexture", e.normal_texture);
    if (e.normal_texture.valid()) o["clearcoatNormalTexture"]["scale"] = e.normal_scale;
    out["KHR_materials_clearcoat"] = o;
  }
  if (m.sheen) {
    const SheenExtension& e = *m.sheen;
    nlohmann::json o = {{"sheenColorFactor", vec3_json(e.color_factor)},
                        {"sheenRoughnessFactor", e.roughness_factor}};
    texture(o, "sheenColorTexture", e.color_texture);
    texture(o, "sheenRoughnessTexture", e.roughness_texture);
    out["KHR_materials_sheen"] = o;
  }
  if (m.anisotropy) {
    const AnisotropyExtension& e = *m.anisotropy;
    nlohmann::json o = {{"anisotropyStrength", e.strength}, {"anisotropyRotation", e.rotation}};
    texture(o, "anisotropyTexture", e.texture);
    out["KHR_materials_anisotropy"] = o;
  }
  if (m.iridescence) {
    const IridescenceExtension& e = *m.iridescence;
    nlohmann::json o = {{"iridescenceFactor", e.factor},
                        {"iridescenceIor", e.ior},
                        {"iridescenceThicknessMinimum", e.thickness_min},
                        {"iridescenceThicknessMaximum", e.thickness_max}};
    texture(o, "iridescenceTexture", e.texture);
    texture(o, "iridescenceThicknessTexture", e.thickness_texture);
    out["KHR_materials_iridescence"] = o;
  }
  if (m.transmission) {
    nlohmann::json o = {{"transmissionFactor", m.transmission->factor}};
    texture(o, "transmissionTexture", m.transmission->texture);
    out["KHR_materials_transmission"] = o;
  }
  if (m.volume) {
    const VolumeExtension& e = *m.volume;
    // JSON has no infinity: an absent attenuationDistance (no absorption) is null.
    nlohmann::json o = {{"thicknessFactor", e.thickness_factor},
                        {"attenuationDistance", std::isfinite(e.attenuation_distance)
                                                    ? nlohmann::json(e.attenuation_distance)
                                                    : nlohmann::json()},
                        {"attenuationColor", vec3_json(e.attenuation_color)}};
    texture(o, "thicknessTexture", e.thickness_texture);
    out["KHR_materials_volume"] = o;
  }
  if (m.dispersion) out["KHR_materials_dispersion"] = {{"dispersion", m.dispersion->dispersion}};
  if (m.diffuse_transmission) {
    const DiffuseTransmissionExtension& e = *m.diffuse_transmission;
    nlohmann::json o = {{"diffuseTransmissionFactor", e.factor},
                        {"diffuseTransmissionColorFactor", vec3_json(e.color_factor)}};
    texture(o, "diffuseTransmissionTexture", e.texture);
    texture(o, "diffuseTransmissionColorTexture", e.color_texture);
    out["KHR_materials_diffuse_transmission"] = o;
  }
  if (m.unlit) out["KHR_materials_unlit"] = nlohmann::json::object();
  return out;
}

// The same, one short phrase per extension for the text summary.
std::string material_extensions_text(const Material& m) {
  std::string s;
  if (m.unlit) s += ", unlit";
  if (m.ior != 1.5f) s += fmt::format(", ior {:g}", m.ior);
  if (m.specular) {
    const glm::vec3 c = m.specular->color_factor;
    s += fmt::format(", specular {:g} ({:g}, {:g}, {:g})", m.specular->factor, c.r, c.g, c.b);
  }
  if (m.clearcoat)
    s += fmt::format(", clearcoat {:g} roughness {:g}", m.clearcoat->factor,
                     m.clearcoat->roughness_factor);
  if (m.sheen) {
    const glm::vec3 c = m.sheen->color_factor;
    s += fmt::format(", sheen ({:g}, {:g}, {:g}) roughness {:g}", c.r, c.g, c.b,
                     m.sheen->roughness_factor);
  }
  if (m.anisotropy)
    s += fmt::format(", anisotropy {:g} rotation {:g}", m.anisotropy->strength,
                     m.anisotropy->rotation);
  if (m.iridescence)
    s +=
        fmt::format(", iridescence {:g} ior {:g} {:g}-{:g} nm", m.iridescence->factor,
                    m.iridescence->ior, m.iridescence->thickness_min, m.iridescence->thickness_max);
  if (m.transmission) s += fmt::format(", transmission {:g}", m.transmission->factor);
  if (m.volume) {
    const VolumeExtension& v = *m.volume;
    s += v.thickness_factor > 0.0f ? fmt::format(", volume thickness {:g}", v.thickness_factor)
                                   : std::string(", volume thin-walled (thickness 0)");
    if (std::isfinite(v.attenuation_distance)) {
      const glm::vec3 c = v.attenuation_color;
      s += fmt::format(" attenuation ({:g}, {:g}, {:g}) at {:g}", c.r, c.g, c.b,
                       v.attenuation_distance);
    }
  }
  if (m.dispersion)
    s += fmt::format(", dispersion {:g} (Abbe {:g})", m.dispersion->dispersion,
                     m.dispersion->dispersion > 0.0f ? 20.0f / m.dispersion->dispersion
                                                     : std::numeric_limits<float>::infinity());
  if (m.diffuse_transmission) {
    const glm::vec3 c = m.diffuse_transmission->color_factor;
    s += fmt::format(", diffuse transmission {:g} ({:g}, {:g}, {:g})",
                     m.diffuse_transmission->factor, c.r, c.g, c.b);
  }
  return s;
}

void run_info(const InfoOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = load_scene(opt.input);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::size_t unique_triangles = 0, vertices = 0;
  for (const Mesh& m : scene.meshes) {
    unique_triangles += m.triangle_count();
    vertices += m.positions.size();
  }
  const Bounds b = scene.world_bounds();
  nlohmann::json j;
  j["source"] = scene.source;
  j["load_seconds"] = seconds;
  j["nodes"] = scene.node_count;
  j["instances"] = scene.instances.size();
  j["meshes"] = scene.meshes.size();
  j["vertices"] = vertices;
  j["triangles"] = scene.triangle_count();
  j["unique_triangles"] = unique_triangles;
  j["materials"] = scene.materials.size();
  // Per material: its factors, alpha, sides, textures, KHR_materials_* extensions and how
  // many meshes use it (as glTF-Transform's `inspect` lists them).
  std::vector<std::size_t> material_uses(scene.materials.size(), 0);
  std::size_t default_material_uses = 0;
  for (const Mesh& m : scene.meshes) {
    if (m.material >= 0 && std::size_t(m.material) < scene.materials.size())
      ++material_uses[std::size_t(m.material)];
    else
      ++default_material_uses;
  }
  j["material_list"] = nlohmann::json::array();
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const glm::vec3 e = m.emissive_factor * m.emissive_strength;
    nlohmann::json mj = {{"name", m.name},
                         {"base_color",
                          {m.base_color_factor.r, m.base_color_factor.g, m.base_color_factor.b,
                           m.base_color_factor.a}},
                         {"metallic", m.metallic_factor},
                         {"roughness", m.roughness_factor},
                         {"emissive", {e.r, e.g, e.b}},
                         {"alpha_mode", alpha_mode(m.alpha_mode)},
                         {"double_sided", m.double_sided},
                         {"textures", material_textures(m)},
                         {"meshes", material_uses[i]}};
    if (m.alpha_mode == AlphaMode::kMask) mj["alpha_cutoff"] = m.alpha_cutoff;
    if (nlohmann::json ext = material_extensions(m); !ext.empty()) mj["extensions"] = ext;
    j["material_list"].push_back(mj);
  }
  j["default_material_meshes"] = default_material_uses;
  j["textures"] = nlohmann::json::array();
  for (const Texture& t : scene.textures)
    j["textures"].push_back({{"name", t.name},
                             {"width", t.width()},
                             {"height", t.height()},
                             {"srgb", t.srgb},
                             {"mips", t.levels.size()},
                             {"bytes", t.bytes()}});
  j["lights"] = nlohmann::json::array();
  for (const Light& l : scene.lights)
    j["lights"].push_back(
        {{"name", l.name}, {"type", light_type(l.type)}, {"intensity", l.intensity}});
  j["cameras"] = nlohmann::json::array();
  for (const Camera& c : scene.cameras)
    j["cameras"].push_back(
        {{"name", c.name},
         {"type", c.type == Camera::Type::kPerspective ? "perspective" : "orthographic"},
         {"yfov", c.yfov}});
  if (!b.empty())
    j["bounds"] = {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
  j["extensions_used"] = scene.extensions_used;
  j["extensions_required"] = scene.extensions_required;
  const std::vector<std::string> supported = supported_gltf_extensions();
  std::vector<std::string> unsupported;
  for (const std::string& e : scene.extensions_used)
    if (std::find(supported.begin(), supported.end(), e) == supported.end())
      unsupported.push_back(e);
  j["extensions_unsupported"] = unsupported;
  j["warnings"] = scene.warnings;
  if (opt.json) {
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::printf("%s\n", scene.source.c_str());
  std::printf("  load time    %.3f s\n", seconds);
  std::printf("  nodes        %zu\n", scene.node_count);
  std::printf("  instances    %zu\n", scene.instances.size());
  std::printf("  meshes       %zu (%zu vertices, %zu triangles)\n", scene.meshes.size(), vertices,
              unique_triangles);
  std::printf("  triangles    %zu (instanced)\n", scene.triangle_count());
  std::printf(
      "  materials    %zu%s\n", scene.materials.size(),
      default_material_uses
          ? fmt::format(" (+ the glTF default material, {} meshes)", default_material_uses).c_str()
          : "");
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const glm::vec4 c = m.base_color_factor;
    const glm::vec3 e = m.emissive_factor * m.emissive_strength;
    std::string extra;
    if (m.alpha_mode == AlphaMode::kMask)
      extra += fmt::format(", mask {:g}", m.alpha_cutoff);
    else if (m.alpha_mode == AlphaMode::kBlend)
      extra += ", blend";
    if (m.double_sided) extra += ", double-sided";
    if (e != glm::vec3(0.0f)) extra += fmt::format(", emissive ({:g}, {:g}, {:g})", e.r, e.g, e.b);
    extra += material_extensions_text(m);
    const std::vector<std::string> textures = material_textures(m);
    if (!textures.empty()) {
      extra += ", textures:";
      for (const std::string& t : textures) extra += " " + t;
    }
    std::printf("    %-30s base (%g, %g, %g, %g), metallic %g, roughness %g%s; %zu mesh%s\n",
                m.name.empty() ? fmt::format("#{}", i).c_str() : m.name.c_str(), c.r, c.g, c.b, c.a,
                m.metallic_factor, m.roughness_factor, extra.c_str(), material_uses[i],
                material_uses[i] == 1 ? "" : "es");
  }
  std::printf("  textures     %zu\n", scene.textures.size());
  for (const Texture& t : scene.textures)
    std::printf("    %-30s %5d x %-5d %s, %zu mips, %zu bytes\n", t.name.c_str(), t.width(),
                t.height(), t.srgb ? "sRGB  " : "linear", t.levels.size(), t.bytes());
  std::printf("  lights       %zu\n", scene.lights.size());
  for (const Light& l : scene.lights)
    std::printf("    %-30s %s, intensity %g\n", l.name.c_str(), light_type(l.type), l.intensity);
  std::printf("  cameras      %zu%s\n", scene.cameras.size(),
              scene.cameras.empty() ? " (an automatic camera frames the bounds)" : "");
  for (const Camera& c : scene.cameras)
    std::printf("    %-30s %s\n", c.name.c_str(),
                c.type == Camera::Type::kPerspective ? "perspective" : "orthographic");
  if (b.empty())
    std::printf("  bounds       (empty)\n");
  else
    std::printf("  bounds       (%g, %g, %g) - (%g, %g, %g)\n", b.min.x, b.min.y, b.min.z, b.max.x,
                b.max.y, b.max.z);
  auto list = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& e : v) s += (s.empty() ? "" : ", ") + e;
    return s.empty() ? std::string("none") : s;
  };
  std::printf("  extensions   used: %s\n", list(scene.extensions_used).c_str());
  std::printf("               required: %s\n", list(scene.extensions_required).c_str());
  std::printf("               unsupported (ignored): %s\n", list(unsupported).c_str());
  std::printf("  warnings     %zu\n", scene.warnings.size());
  for (const std::string& w : scene.warnings) std::printf("    %s\n", w.c_str());
}

}  // namespace

void register_info_command(CLI::App& app) {
  auto opt = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info", "Summarise a glTF file (.gltf/.glb) or a built-in scene (`pbrkit scene list`)");
  cmd->add_option("input", opt->input, "glTF file or built-in scene name")->required();
  cmd->add_flag("--json", opt->json, "Print the summary as JSON");
  cmd->callback([opt] { run_info(*opt); });
}

}  // namespace pbrkit::cli
