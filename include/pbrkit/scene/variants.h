#pragma once
// KHR_materials_variants: switching a loaded scene between the material variants its file
// declares. Variants are the file's, named in Scene::variants; each Mesh (one glTF
// primitive) lists the materials it takes in Mesh::variant_materials.
#include <string_view>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

/// Sets every mesh's material (and Mesh::closed with it) to what `variant` maps, or to the
/// primitive's own material where no mapping holds `variant` (README, "Mappings": "a
/// compliant viewer will fall back on vanilla glTF behaviour"). -1 restores every mesh's
/// own material. Meshes are shared by their instances, so every instance changes. Throws
/// pbrkit::Error for a variant the scene does not have.
/// @see find_variant to turn a name into the index.
void apply_variant(Scene& scene, int variant);

/// The index of the variant named `name_or_index`, or whose index it is (a name is matched
/// first, so a variant may be named "1"). Throws pbrkit::Error listing the scene's variants
/// when none matches.
int find_variant(const Scene& scene, std::string_view name_or_index);

/// How many meshes `variant` gives a material other than their own (for `pbrkit info`).
std::size_t variant_mesh_count(const Scene& scene, int variant);

}  // namespace pbrkit
