#pragma once
// Mip level <-> roughness mappings of the prefiltered specular chain: which roughness the
// bake prefilters each level for, and which fractional level a shader reads for a roughness.
#include <string_view>

namespace pbrkit {

/// How a specular mip level maps to roughness.
enum class RoughnessMapping {
  /// roughness = level / (levels - 1): the Khronos glTF sample viewer's and UE4's mapping.
  kLinear,
};

/// The mapping called `name` ("linear"); throws pbrkit::Error naming it if unknown.
RoughnessMapping parse_roughness_mapping(std::string_view name);
/// The name parse_roughness_mapping() accepts for `mapping`.
std::string_view roughness_mapping_name(RoughnessMapping mapping);
/// Roughness of mip `level` of a `levels`-level chain (0 for a single level).
float mip_roughness(int level, int levels, RoughnessMapping mapping = RoughnessMapping::kLinear);
/// Fractional mip level for `roughness` in a `levels`-level chain (the inverse of
/// mip_roughness(); what shaders compute).
float roughness_lod(float roughness, int levels,
                    RoughnessMapping mapping = RoughnessMapping::kLinear);

}  // namespace pbrkit
