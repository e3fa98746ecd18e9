// pbrkit info FILE: a readable summary of a glTF file or built-in scene (in the spirit of
// glTF-Transform's `inspect`), or the same numbers as JSON with --json.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/scene/variants.h"
#include "pbrkit/util/error.h"

namespace pbrkit::cli {

namespace {

struct InfoOptions {
  std::string input;
  bool json = false;
  std::string animation;  ///< pose by this animation first (the bounds are the pose's)
  float animation_time = 0.0f;
};

const char* interpolation_name(Interpolation i) {
  return i == Interpolation::kStep     ? "STEP"
         : i == Interpolation::kLinear ? "LINEAR"
                                       : "CUBICSPLINE";
}

const char* light_type(Light::Type t) {
  return t == Light::Type::kPoint ? "point" : t == Light::Type::kSpot ? "spot" : "directional";
}

const char* alpha_mode(AlphaMode m) {
  return m == AlphaMode::kOpaque ? "opaque" : m == AlphaMode::kMask ? "mask" : "blend";
}

// The texture slots a material uses, by glTF name.
std::vector<std::string> material_textures(const Material& m) {
  std::vector<std::string> out;
  const auto slots = m.textures();
  for (int t = 0; t < kTextureSlotCount; ++t)
    if (slots[std::size_t(t)]->valid()) out.push_back(texture_slot_name(TextureSlot(t)));
  return out;
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

// A factor's value: a number, or an array for a colour (JSON has no infinity: an infinite
// value, as an absent attenuationDistance, is null).
nlohmann::json factor_json(const Material& m, const MaterialFactor& f) {
  const float* v = f.read(m);
  auto number = [](float x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
  if (f.components == 1) return number(v[0]);
  nlohmann::json a = nlohmann::json::array();
  for (int c = 0; c < f.components; ++c) a.push_back(number(v[c]));
  return a;
}

// The same for the text summary: "0.5", or "(1, 0.5, 0.2)" for a colour.
std::string factor_text(const Material& m, const MaterialFactor& f) {
  const float* v = f.read(m);
  if (f.components == 1) return fmt::format("{:g}", v[0]);
  std::string s = "(";
  for (int c = 0; c < f.components; ++c) s += fmt::format("{}{:g}", c ? ", " : "", v[c]);
  return s + ")";
}

// The KHR_materials_* extensions a material uses (as the material schema lists them), each
// with every value (defaults included) and its textures, under the extension's own
// property names.
nlohmann::json material_extensions_json(const Material& m) {
  nlohmann::json out = nlohmann::json::object();
  for (const MaterialExtension& x : material_schema()) {
    if (!x.present(m)) continue;
    nlohmann::json o = nlohmann::json::object();
    for (const MaterialFactor& f : x.factors) o[f.json_name] = factor_json(m, f);
    for (const MaterialTexture& t : x.textures) {
      const TextureRef& ref = *m.textures()[std::size_t(t.slot)];
      if (!ref.valid()) continue;
      o[t.json_name] = texture_json(ref);
      if (t.scale) o[t.json_name]["scale"] = *t.scale(const_cast<Material&>(m));
    }
    out[x.name] = o;
  }
  return out;
}

// The same, one short phrase per extension for the text summary: its name, each factor as
// the schema's summary phrase, and its note.
std::string material_extensions_text(const Material& m) {
  std::string s;
  for (const MaterialExtension& x : material_schema()) {
    if (!x.present(m)) continue;
    s += fmt::format(", {}", x.summary);
    for (const MaterialFactor& f : x.factors)
      s += " " + fmt::format(fmt::runtime(f.summary), factor_text(m, f));
    if (x.note)
      if (const std::string note = x.note(m); !note.empty()) s += " " + note;
  }
  return s;
}

// What `pbrkit info` reports beyond the scene itself: the load time and the counts
// derived from it.
struct SceneSummary {
  Scene scene;
  double load_seconds = 0.0;
  std::size_t vertices = 0, unique_triangles = 0;
  Bounds bounds;
  // Per material, how many meshes use it (as glTF-Transform's `inspect` lists them), and
  // how many use the glTF default material.
  std::vector<std::size_t> material_uses;
  std::size_t default_material_uses = 0;
  std::vector<std::string> unsupported;  // extensions used that the loader ignores
};

SceneSummary summarise(const InfoOptions& opt) {
  SceneSummary s;
  const auto start = std::chrono::steady_clock::now();
  s.scene = load_scene(opt.input);
  s.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!opt.animation.empty()) {
    try {
      pose_scene(s.scene, {find_animation(s.scene, opt.animation), opt.animation_time});
    } catch (const Error& e) {
      fail("--animation: {}", e.what());
    }
  }
  const Scene& scene = s.scene;
  for (const Mesh& m : scene.meshes) {
    s.unique_triangles += m.triangle_count();
    s.vertices += m.positions.size();
  }
  s.bounds = scene.world_bounds();
  s.material_uses.assign(scene.materials.size(), 0);
  for (const Mesh& m : scene.meshes) {
    if (m.material >= 0 && std::size_t(m.material) < scene.materials.size())
      ++s.material_uses[std::size_t(m.material)];
    else
      ++s.default_material_uses;
  }
  const std::vector<std::string> supported = supported_gltf_extensions();
  for (const std::string& e : scene.extensions_used)
    if (std::find(supported.begin(), supported.end(), e) == supported.end())
      s.unsupported.push_back(e);
  return s;
}

// A material's factors, alpha, sides, textures, KHR_materials_* extensions and users.
nlohmann::json material_json(const Material& m, std::size_t uses) {
  // The core emissiveFactor; a strength that scales it is listed with the extensions.
  const glm::vec3 e = m.emissive_factor;
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
                       {"meshes", uses}};
  if (m.alpha_mode == AlphaMode::kMask) mj["alpha_cutoff"] = m.alpha_cutoff;
  if (nlohmann::json ext = material_extensions_json(m); !ext.empty()) mj["extensions"] = ext;
  return mj;
}

nlohmann::json summary_json(const SceneSummary& s) {
  const Scene& scene = s.scene;
  nlohmann::json j;
  j["source"] = scene.source;
  j["load_seconds"] = s.load_seconds;
  j["nodes"] = scene.node_count;
  j["instances"] = scene.instances.size();
  j["meshes"] = scene.meshes.size();
  j["vertices"] = s.vertices;
  j["triangles"] = scene.triangle_count();
  j["unique_triangles"] = s.unique_triangles;
  j["materials"] = scene.materials.size();
  j["material_list"] = nlohmann::json::array();
  for (std::size_t i = 0; i < scene.materials.size(); ++i)
    j["material_list"].push_back(material_json(scene.materials[i], s.material_uses[i]));
  j["default_material_meshes"] = s.default_material_uses;
  // KHR_materials_variants: each variant and how many meshes it gives another material.
  j["variants"] = nlohmann::json::array();
  for (std::size_t i = 0; i < scene.variants.size(); ++i)
    j["variants"].push_back(
        {{"name", scene.variants[i]}, {"meshes", variant_mesh_count(scene, int(i))}});
  // Animations (glTF 2.0 section 3.11) and skins: what `render --animation` can pose.
  j["animations"] = nlohmann::json::array();
  j["skins"] = scene.motion ? scene.motion->skins.size() : 0;
  if (scene.motion)
    for (const Animation& a : scene.motion->animations) {
      nlohmann::json interpolations = nlohmann::json::array();
      for (const AnimationSampler& sampler : a.samplers)
        if (!sampler.times.empty())
          interpolations.push_back(interpolation_name(sampler.interpolation));
      j["animations"].push_back({{"name", a.name},
                                 {"start", a.start()},
                                 {"end", a.end()},
                                 {"channels", a.channels.size()},
                                 {"interpolations", interpolations}});
    }
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
  const Bounds& b = s.bounds;
  if (!b.empty())
    j["bounds"] = {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
  j["extensions_used"] = scene.extensions_used;
  j["extensions_required"] = scene.extensions_required;
  j["extensions_unsupported"] = s.unsupported;
  j["warnings"] = scene.warnings;
  return j;
}

// One line per material: its factors, then what differs from the defaults.
void print_material(const Material& m, std::size_t index, std::size_t uses) {
  const glm::vec4 c = m.base_color_factor;
  const glm::vec3 e = m.emissive_factor;  // its strength follows with the extensions
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
              m.name.empty() ? fmt::format("#{}", index).c_str() : m.name.c_str(), c.r, c.g, c.b,
              c.a, m.metallic_factor, m.roughness_factor, extra.c_str(), uses,
              uses == 1 ? "" : "es");
}

void print_summary(const SceneSummary& s) {
  const Scene& scene = s.scene;
  std::printf("%s\n", scene.source.c_str());
  std::printf("  load time    %.3f s\n", s.load_seconds);
  std::printf("  nodes        %zu\n", scene.node_count);
  std::printf("  instances    %zu\n", scene.instances.size());
  std::printf("  meshes       %zu (%zu vertices, %zu triangles)\n", scene.meshes.size(), s.vertices,
              s.unique_triangles);
  std::printf("  triangles    %zu (instanced)\n", scene.triangle_count());
  std::printf("  materials    %zu%s\n", scene.materials.size(),
              s.default_material_uses ? fmt::format(" (+ the glTF default material, {} meshes)",
                                                    s.default_material_uses)
                                            .c_str()
                                      : "");
  for (std::size_t i = 0; i < scene.materials.size(); ++i)
    print_material(scene.materials[i], i, s.material_uses[i]);
  if (!scene.variants.empty()) {
    std::printf("  variants     %zu (KHR_materials_variants; pbrkit render --variant)\n",
                scene.variants.size());
    for (std::size_t i = 0; i < scene.variants.size(); ++i) {
      const std::size_t meshes = variant_mesh_count(scene, int(i));
      std::printf("    %zu %-28s changes %zu mesh%s\n", i,
                  fmt::format("'{}'", scene.variants[i]).c_str(), meshes, meshes == 1 ? "" : "es");
    }
  }
  if (scene.motion) {
    const SceneMotion& m = *scene.motion;
    std::printf("  animations   %zu (pbrkit render --animation NAME|INDEX --animation-time S)\n",
                m.animations.size());
    for (std::size_t i = 0; i < m.animations.size(); ++i)
      std::printf("    %zu %-28s %g to %g s, %zu channels\n", i,
                  fmt::format("'{}'", m.animations[i].name).c_str(), m.animations[i].start(),
                  m.animations[i].end(), m.animations[i].channels.size());
    std::printf("  skins        %zu; %zu meshes deform (skinned or morphed)\n", m.skins.size(),
                m.deforming.size());
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
  const Bounds& b = s.bounds;
  if (b.empty())
    std::printf("  bounds       (empty)\n");
  else
    std::printf("  bounds       (%g, %g, %g) - (%g, %g, %g)\n", b.min.x, b.min.y, b.min.z, b.max.x,
                b.max.y, b.max.z);
  auto list = [](const std::vector<std::string>& v) {
    std::string text;
    for (const auto& e : v) text += (text.empty() ? "" : ", ") + e;
    return text.empty() ? std::string("none") : text;
  };
  std::printf("  extensions   used: %s\n", list(scene.extensions_used).c_str());
  std::printf("               required: %s\n", list(scene.extensions_required).c_str());
  std::printf("               unsupported (ignored): %s\n", list(s.unsupported).c_str());
  std::printf("  warnings     %zu\n", scene.warnings.size());
  for (const std::string& w : scene.warnings) std::printf("    %s\n", w.c_str());
}

void run_info(const InfoOptions& opt) {
  const SceneSummary s = summarise(opt);
  if (opt.json)
    std::printf("%s\n", summary_json(s).dump(2).c_str());
  else
    print_summary(s);
}

}  // namespace

void register_info_command(CLI::App& app) {
  auto opt = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info", "Summarise a glTF file (.gltf/.glb) or a built-in scene (`pbrkit scene list`)");
  cmd->add_option("input", opt->input, "glTF file or built-in scene name")->required();
  cmd->add_flag("--json", opt->json, "Print the summary as JSON");
  auto* animation = cmd->add_option(
      "--animation", opt->animation,
      "pose the scene by this animation (name or index) first: the bounds are the pose's");
  cmd->add_option("--animation-time", opt->animation_time, "the time in the animation, seconds")
      ->needs(animation)
      ->capture_default_str();
  cmd->callback([opt] { run_info(*opt); });
}

}  // namespace pbrkit::cli
