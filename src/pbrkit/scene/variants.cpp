// KHR_materials_variants: switching the materials of a loaded scene.
#include "pbrkit/scene/variants.h"

#include <charconv>
#include <string>

#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

// The entry of `mesh` for `variant`: its own, or the file's material (the first entry)
// when no mapping names the variant.
const VariantMaterial& variant_entry(const Mesh& mesh, int variant) {
  for (const VariantMaterial& v : mesh.variant_materials)
    if (v.variant == variant) return v;
  return mesh.variant_materials.front();
}

}  // namespace

void apply_variant(Scene& scene, int variant) {
  if (variant < -1 || variant >= int(scene.variants.size()))
    fail("{}: variant {} does not exist (the scene has {})", scene.source, variant,
         scene.variants.size());
  for (Mesh& mesh : scene.meshes) {
    if (mesh.variant_materials.empty()) continue;
    const VariantMaterial& v = variant_entry(mesh, variant);
    mesh.material = v.material;
    mesh.closed = v.closed;
  }
  scene.active_variant = variant;
}

int find_variant(const Scene& scene, std::string_view name_or_index) {
  for (std::size_t i = 0; i < scene.variants.size(); ++i)
    if (scene.variants[i] == name_or_index) return int(i);
  int index = -1;
  const char* end = name_or_index.data() + name_or_index.size();
  const auto [ptr, ec] = std::from_chars(name_or_index.data(), end, index);
  if (ec == std::errc() && ptr == end && index >= 0 && index < int(scene.variants.size()))
    return index;
  if (scene.variants.empty())
    fail(
        "{}: variant '{}' does not exist: the scene has no material variants "
        "(KHR_materials_variants)",
        scene.source, name_or_index);
  std::string list;
  for (std::size_t i = 0; i < scene.variants.size(); ++i)
    list += fmt::format("{}{} '{}'", i == 0 ? "" : ", ", i, scene.variants[i]);
  fail("{}: variant '{}' does not exist; the scene's variants are {}", scene.source, name_or_index,
       list);
}

std::size_t variant_mesh_count(const Scene& scene, int variant) {
  std::size_t count = 0;
  for (const Mesh& mesh : scene.meshes)
    if (!mesh.variant_materials.empty() &&
        variant_entry(mesh, variant).material != mesh.variant_materials.front().material)
      ++count;
  return count;
}

}  // namespace pbrkit
