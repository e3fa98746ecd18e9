// KHR_materials_variants (README, "Variants" and "Mappings"): the root's list of variants,
// each primitive's mappings from variants to materials, checked against both lists; then
// the materials and closures (Mesh::variant_materials) each variant gives the primitives
// of a glTF mesh, so that switching a variant (scene/variants.h) only copies them.
#include <algorithm>
#include <set>

#include "pbrkit/scene/gltf/loader.h"
#include "pbrkit/scene/mesh_attributes.h"

namespace pbrkit::gltf {

namespace {

constexpr const char* kExtension = "KHR_materials_variants";

// A glTFid: a non-negative integer.
bool is_index(const json& v) {
  return v.is_number_unsigned() || (v.is_number_integer() && v.get<std::int64_t>() >= 0);
}

}  // namespace

void Loader::read_variants(const json& root) {
  scene_.variants.clear();
  variant_mappings_.clear();
  const auto root_ext = root.find("extensions");
  if (root_ext != root.end() && root_ext->is_object() && root_ext->contains(kExtension)) {
    const std::string where = fmt::format("extensions.{}", kExtension);
    const json& ext = (*root_ext)[kExtension];
    if (!ext.is_object()) error(where, fmt::format("must be an object, not {}", ext.type_name()));
    const auto variants = ext.find("variants");
    if (variants == ext.end() || !variants->is_array())
      error(where + ".variants", "missing or not an array");
    for (std::size_t i = 0; i < variants->size(); ++i) {
      const json& v = (*variants)[i];
      const std::string at = fmt::format("{}.variants[{}]", where, i);
      if (!v.is_object()) error(at, fmt::format("must be an object, not {}", v.type_name()));
      if (!v.contains("name") || !v["name"].is_string())
        error(at + ".name", "missing or not a string");
      scene_.variants.push_back(v["name"].get<std::string>());
    }
  }
  if (!root.contains("meshes")) return;
  const std::size_t material_count = root.contains("materials") ? root["materials"].size() : 0;
  const json& meshes = root["meshes"];  // an array of objects (check_json)
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const auto primitives = meshes[m].find("primitives");
    if (primitives == meshes[m].end() || !primitives->is_array()) continue;  // tinygltf's
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const json& prim = (*primitives)[p];
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
          !prim["extensions"].contains(kExtension))
        continue;
      const std::string where =
          fmt::format("meshes[{}].primitives[{}].extensions.{}", m, p, kExtension);
      const json& ext = prim["extensions"][kExtension];
      if (!ext.is_object()) error(where, fmt::format("must be an object, not {}", ext.type_name()));
      const auto mappings = ext.find("mappings");
      if (mappings == ext.end() || !mappings->is_array())
        error(where + ".mappings", "missing or not an array");
      std::vector<VariantMaterial> out;
      for (std::size_t k = 0; k < mappings->size(); ++k) {
        const json& mapping = (*mappings)[k];
        const std::string at = fmt::format("{}.mappings[{}]", where, k);
        if (!mapping.is_object())
          error(at, fmt::format("must be an object, not {}", mapping.type_name()));
        if (!mapping.contains("material") || !is_index(mapping["material"]))
          error(at + ".material", "missing or not a non-negative integer");
        const std::uint64_t material = mapping["material"].get<std::uint64_t>();
        if (material >= material_count)
          error(at + ".material",
                fmt::format("material {} does not exist ({} materials)", material, material_count));
        if (!mapping.contains("variants") || !mapping["variants"].is_array())
          error(at + ".variants", "missing or not an array");
        const json& variants = mapping["variants"];
        for (std::size_t j = 0; j < variants.size(); ++j) {
          const std::string vat = fmt::format("{}.variants[{}]", at, j);
          if (!is_index(variants[j])) error(vat, "must be a non-negative integer");
          const std::uint64_t variant = variants[j].get<std::uint64_t>();
          if (variant >= scene_.variants.size())
            error(vat, fmt::format("variant {} does not exist ({} variants in extensions.{})",
                                   variant, scene_.variants.size(), kExtension));
          // "Across the entire mappings array, each variant index must be used no more
          // than one time" (README, "Mappings"): a second use would be ambiguous.
          if (std::any_of(out.begin(), out.end(),
                          [&](const VariantMaterial& v) { return v.variant == int(variant); }))
            error(vat, fmt::format("variant {} is mapped more than once", variant));
          out.push_back({int(variant), int(material), true});
        }
      }
      std::sort(out.begin(), out.end(), [](const VariantMaterial& a, const VariantMaterial& b) {
        return a.variant < b.variant;
      });
      if (!out.empty()) variant_mappings_[{int(m), int(p)}] = std::move(out);
    }
  }
}

void Loader::add_variant_materials(int mesh_index, const std::vector<int>& primitives,
                                   const std::vector<int>& gltf_primitive) {
  const std::size_t n = primitives.size();
  std::vector<const std::vector<VariantMaterial>*> mappings(n, nullptr);
  std::set<int> used;
  for (std::size_t i = 0; i < n; ++i) {
    const auto it = variant_mappings_.find({mesh_index, gltf_primitive[i]});
    if (it == variant_mappings_.end()) continue;
    mappings[i] = &it->second;
    for (const VariantMaterial& v : it->second) used.insert(v.variant);
  }
  if (used.empty()) return;
  auto mesh = [&](std::size_t i) -> Mesh& { return scene_.meshes[std::size_t(primitives[i])]; };
  std::vector<VariantMaterial> own(n);
  for (std::size_t i = 0; i < n; ++i) {
    own[i] = {-1, mesh(i).material, mesh(i).closed};
    if (!mappings[i]) continue;
    mesh(i).variant_materials.push_back(own[i]);
    // A variant's material may need a tangent frame the primitive's own does not.
    for (const VariantMaterial& v : *mappings[i])
      ensure_tangents(mesh(i), scene_.materials[std::size_t(v.material)]);
  }
  // Each variant's closures as decide_closure finds them for the file's materials: a
  // primitive's shell may be split across the mesh's primitives of one material, so a
  // variant can change the closure of a primitive it does not map.
  for (const int variant : used) {
    for (std::size_t i = 0; i < n; ++i) {
      mesh(i).material = own[i].material;
      if (mappings[i])
        for (const VariantMaterial& v : *mappings[i])
          if (v.variant == variant) mesh(i).material = v.material;
      mesh(i).closed = true;
    }
    decide_closure(mesh_index, primitives, gltf_primitive,
                   fmt::format(" while variant {} ('{}') is active", variant,
                               scene_.variants[std::size_t(variant)]));
    for (std::size_t i = 0; i < n; ++i) {
      Mesh& m = mesh(i);
      if (m.material == own[i].material && m.closed == own[i].closed) continue;
      if (m.variant_materials.empty()) m.variant_materials.push_back(own[i]);
      m.variant_materials.push_back({variant, m.material, m.closed});
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    mesh(i).material = own[i].material;
    mesh(i).closed = own[i].closed;
  }
}

}  // namespace pbrkit::gltf
