// Mip level <-> roughness mappings for the prefiltered specular chain (see
// roughness_mapping.h).
#include <algorithm>

#include "pbrkit/ibl/roughness_mapping.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

RoughnessMapping parse_roughness_mapping(std::string_view name) {
  if (name == "linear") return RoughnessMapping::kLinear;
  fail("unknown roughness mapping '{}' (known: linear)", name);
}

std::string_view roughness_mapping_name(RoughnessMapping mapping) {
  switch (mapping) {
    case RoughnessMapping::kLinear:
      return "linear";
  }
  return "linear";
}

float mip_roughness(int level, int levels, RoughnessMapping mapping) {
  (void)mapping;  // kLinear is the only mapping: roughness = level / (levels - 1)
  if (levels <= 1) return 0.0f;
  return float(level) / float(levels - 1);
}

float roughness_lod(float roughness, int levels, RoughnessMapping mapping) {
  (void)mapping;
  if (levels <= 1) return 0.0f;
  return std::clamp(roughness, 0.0f, 1.0f) * float(levels - 1);
}

}  // namespace pbrkit
