// The KHR_materials_* extensions as one table (material_schema.h). Each row follows its
// README's "Properties" table (KhronosGroup/glTF, extensions/2.0/Khronos/<name>/README.md)
// and JSON schema: the property names, the ranges, the channels each texture is read from
// and its colour space. Where this loader is stricter than a schema, the row says why.
#include "pbrkit/scene/material_schema.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <limits>
#include <type_traits>

#include <fmt/format.h>

#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kPi = 3.14159265358979f;

// Accessors of a Material's optional extension `kExtension` and of its member `kMember`
// (a float, or a glm::vec3 as 3 contiguous floats).
template <auto kExtension>
bool has(const Material& m) {
  return (m.*kExtension).has_value();
}

template <auto kExtension>
void add(Material& m) {
  (m.*kExtension).emplace();
}

template <auto kExtension, auto kMember>
float* member(Material& m) {
  auto& value = (*(m.*kExtension)).*kMember;
  if constexpr (std::is_same_v<std::remove_reference_t<decltype(value)>, glm::vec3>)
    return &value.x;
  else
    return &value;
}

template <auto kMember>
float* own_member(Material& m) {
  return &(m.*kMember);
}

// KHR_materials_ior has no extension struct: the index is the material's own (1.5, the
// README's default, when the extension is absent).
bool has_ior(const Material& m) {
  return m.ior != Material{}.ior;
}
void add_ior(Material& m) {
  m.ior = Material{}.ior;
}

// KHR_materials_emissive_strength has no extension struct either: the strength is the
// material's own (1, the README's default, when the extension is absent).
bool has_emissive_strength(const Material& m) {
  return m.emissive_strength != Material{}.emissive_strength;
}
void add_emissive_strength(Material& m) {
  m.emissive_strength = Material{}.emissive_strength;
}

bool has_unlit(const Material& m) {
  return m.unlit;
}
void add_unlit(Material& m) {
  m.unlit = true;
}

// KHR_materials_ior, "Properties": ior >= 1, or exactly 0, the specular-glossiness
// compatibility mode (an infinite index: f0 = ((ior - 1) / (ior + 1))^2 = 1), which a range
// cannot express. Any other value below 1 becomes 1, the nearest index of the ordinary range.
const char* check_ior(float& ior) {
  if (ior == 0.0f || ior >= 1.0f) return nullptr;
  ior = 1.0f;
  return "(the index must be >= 1, or 0 for the specular-glossiness mode); using 1";
}

// KHR_materials_emissive_strength, "Properties": emissiveStrength >= 0. A negative strength
// would make the surface absorb light it never received; no value in range means what the
// file meant, so the file is refused (rejected_is_error) rather than clamped.
const char* check_emissive_strength(float& strength) {
  return strength >= 0.0f ? nullptr : "must not be negative";
}

// KHR_materials_volume, "Properties": attenuationDistance is in (0, +inf), an open range,
// and its default is +inf (no absorption), which JSON cannot write. sigma_t = -ln(c) / d
// has no finite value at d <= 0, so such a distance is ignored rather than clamped.
const char* check_attenuation_distance(float& distance) {
  if (distance > 0.0f) return nullptr;
  distance = kInf;
  return "(the distance must be > 0); ignored: the medium does not absorb";
}

// `pbrkit info`'s notes: what a value means that its number does not show.
std::string volume_note(const Material& m) {
  // KHR_materials_volume: "thicknessFactor ... 0 ... means the material is thin-walled".
  return m.volume->thickness_factor == 0.0f ? "(thin-walled)" : "";
}
std::string dispersion_note(const Material& m) {
  // KHR_materials_dispersion: dispersion = 20 / V, V the Abbe number.
  const float d = m.dispersion->dispersion;
  return fmt::format("(Abbe {:g})", d > 0.0f ? 20.0f / d : kInf);
}

using S = TextureSlot;

// A factor's control (the viewer's override panel): a slider over [min, max] from `start`.
constexpr FactorControl slider(float min, float max, float start) {
  return {min, max, start};
}
constexpr FactorControl log_slider(float min, float max, float start) {
  return {min, max, start, true};
}

constexpr MaterialFactor kEmissiveStrengthFactors[] = {
    {"emissiveStrength", "{}", 1, 0.0f, kInf, slider(0.0f, 20.0f, 1.0f),
     &own_member<&Material::emissive_strength>, &check_emissive_strength, true},
};

constexpr MaterialFactor kIorFactors[] = {
    {"ior", "{}", 1, 1.0f, kInf, slider(1.0f, 3.0f, 1.5f), &own_member<&Material::ior>, &check_ior},
};

// KHR_materials_specular: the schema bounds specularColorFactor below only; an F0 tint
// above 1 is allowed (the README's "may be greater than 1").
constexpr MaterialFactor kSpecularFactors[] = {
    {"specularFactor", "{}", 1, 0.0f, 1.0f, slider(0.0f, 1.0f, 1.0f),
     &member<&Material::specular, &SpecularExtension::factor>},
    {"specularColorFactor", "{}", 3, 0.0f, kInf, slider(0.0f, 1.0f, 1.0f),
     &member<&Material::specular, &SpecularExtension::color_factor>},
};
constexpr MaterialTexture kSpecularTextures[] = {
    {"specularTexture", S::kSpecular, "A", false},
    {"specularColorTexture", S::kSpecularColor, "RGB", true},
};

constexpr MaterialFactor kClearcoatFactors[] = {
    {"clearcoatFactor", "{}", 1, 0.0f, 1.0f, slider(0.0f, 1.0f, 1.0f),
     &member<&Material::clearcoat, &ClearcoatExtension::factor>},
    {"clearcoatRoughnessFactor", "roughness {}", 1, 0.0f, 1.0f, slider(0.0f, 1.0f, 0.1f),
     &member<&Material::clearcoat, &ClearcoatExtension::roughness_factor>},
};
constexpr MaterialTexture kClearcoatTextures[] = {
    {"clearcoatTexture", S::kClearcoat, "R", false},
    {"clearcoatRoughnessTexture", S::kClearcoatRoughness, "G", false},
    {"clearcoatNormalTexture", S::kClearcoatNormal, "RGB", false,
     &member<&Material::clearcoat, &ClearcoatExtension::normal_scale>},
};

constexpr MaterialFactor kSheenFactors[] = {
    {"sheenColorFactor", "{}", 3, 0.0f, 1.0f, slider(0.0f, 1.0f, 0.5f),
     &member<&Material::sheen, &SheenExtension::color_factor>},
    {"sheenRoughnessFactor", "roughness {}", 1, 0.0f, 1.0f, slider(0.0f, 1.0f, 0.5f),
     &member<&Material::sheen, &SheenExtension::roughness_factor>},
};
constexpr MaterialTexture kSheenTextures[] = {
    {"sheenColorTexture", S::kSheenColor, "RGB", true},
    {"sheenRoughnessTexture", S::kSheenRoughness, "A", false},
};

// anisotropyRotation is an angle in radians: every number is valid.
constexpr MaterialFactor kAnisotropyFactors[] = {
    {"anisotropyStrength", "{}", 1, 0.0f, 1.0f, slider(0.0f, 1.0f, 0.5f),
     &member<&Material::anisotropy, &AnisotropyExtension::strength>},
    {"anisotropyRotation", "rotation {}", 1, -kInf, kInf, slider(-kPi, kPi, 0.0f),
     &member<&Material::anisotropy, &AnisotropyExtension::rotation>},
};
constexpr MaterialTexture kAnisotropyTextures[] = {
    {"anisotropyTexture", S::kAnisotropy, "RGB", false},  // RG direction, B strength
};

// The thickness minimum may exceed the maximum (the README allows it: the thickness
// texture then interpolates downwards), so each is bounded on its own.
constexpr MaterialFactor kIridescenceFactors[] = {
    {"iridescenceFactor", "{}", 1, 0.0f, 1.0f, slider(0.0f, 1.0f, 1.0f),
     &member<&Material::iridescence, &IridescenceExtension::factor>},
    {"iridescenceIor", "ior {}", 1, 1.0f, kInf, slider(1.0f, 3.0f, 1.3f),
     &member<&Material::iridescence, &IridescenceExtension::ior>},
    {"iridescenceThicknessMinimum", "thickness {}", 1, 0.0f, kInf, slider(0.0f, 1200.0f, 100.0f),
     &member<&Material::iridescence, &IridescenceExtension::thickness_min>},
    {"iridescenceThicknessMaximum", "to {} nm", 1, 0.0f, kInf, slider(0.0f, 1200.0f, 400.0f),
     &member<&Material::iridescence, &IridescenceExtension::thickness_max>},
};
constexpr MaterialTexture kIridescenceTextures[] = {
    {"iridescenceTexture", S::kIridescence, "R", false},
    {"iridescenceThicknessTexture", S::kIridescenceThickness, "G", false},
};

constexpr MaterialFactor kTransmissionFactors[] = {
    {"transmissionFactor", "{}", 1, 0.0f, 1.0f, slider(0.0f, 1.0f, 1.0f),
     &member<&Material::transmission, &TransmissionExtension::factor>},
};
constexpr MaterialTexture kTransmissionTextures[] = {
    {"transmissionTexture", S::kTransmission, "R", false},
};

// attenuationColor: the schema bounds it below only, but above 1 the transmittance
// c^(x / d) grows with the distance x travelled: the medium would make light. So it is
// clamped to 1.
constexpr MaterialFactor kVolumeFactors[] = {
    {"thicknessFactor", "thickness {}", 1, 0.0f, kInf, slider(0.0f, 5.0f, 0.5f),
     &member<&Material::volume, &VolumeExtension::thickness_factor>},
    {"attenuationColor", "attenuation {}", 3, 0.0f, 1.0f, slider(0.0f, 1.0f, 1.0f),
     &member<&Material::volume, &VolumeExtension::attenuation_color>},
    {"attenuationDistance", "at {}", 1, 0.0f, kInf, log_slider(0.01f, 10.0f, 1.0f),
     &member<&Material::volume, &VolumeExtension::attenuation_distance>,
     &check_attenuation_distance},
};
constexpr MaterialTexture kVolumeTextures[] = {
    {"thicknessTexture", S::kThickness, "G", false},
};

constexpr MaterialFactor kDispersionFactors[] = {
    {"dispersion", "{}", 1, 0.0f, kInf, slider(0.0f, 5.0f, 0.5f),
     &member<&Material::dispersion, &DispersionExtension::dispersion>},
};

// diffuseTransmissionColorFactor: the schema bounds it below only; above 1 the surface
// would transmit more light than reaches it, so it is clamped to 1.
constexpr MaterialFactor kDiffuseTransmissionFactors[] = {
    {"diffuseTransmissionFactor", "{}", 1, 0.0f, 1.0f, slider(0.0f, 1.0f, 1.0f),
     &member<&Material::diffuse_transmission, &DiffuseTransmissionExtension::factor>},
    {"diffuseTransmissionColorFactor", "{}", 3, 0.0f, 1.0f, slider(0.0f, 1.0f, 1.0f),
     &member<&Material::diffuse_transmission, &DiffuseTransmissionExtension::color_factor>},
};
constexpr MaterialTexture kDiffuseTransmissionTextures[] = {
    {"diffuseTransmissionTexture", S::kDiffuseTransmission, "A", false},
    {"diffuseTransmissionColorTexture", S::kDiffuseTransmissionColor, "RGB", true},
};

// Extensions without factors or textures.
constexpr std::span<const MaterialFactor> kNoFactors;
constexpr std::span<const MaterialTexture> kNoTextures;

// The extensions that scale a core value come first (material_extensions() is the rest).
constexpr std::size_t kScalesCoreCount = 1;
constexpr MaterialExtension kExtensions[] = {
    {"KHR_materials_emissive_strength", "emissive strength", &has_emissive_strength,
     &add_emissive_strength, kEmissiveStrengthFactors, kNoTextures, nullptr, false, true},
    {"KHR_materials_ior", "ior", &has_ior, &add_ior, kIorFactors, kNoTextures},
    {"KHR_materials_specular", "specular", &has<&Material::specular>, &add<&Material::specular>,
     kSpecularFactors, kSpecularTextures},
    {"KHR_materials_clearcoat", "clearcoat", &has<&Material::clearcoat>, &add<&Material::clearcoat>,
     kClearcoatFactors, kClearcoatTextures},
    {"KHR_materials_sheen", "sheen", &has<&Material::sheen>, &add<&Material::sheen>, kSheenFactors,
     kSheenTextures},
    {"KHR_materials_anisotropy", "anisotropy", &has<&Material::anisotropy>,
     &add<&Material::anisotropy>, kAnisotropyFactors, kAnisotropyTextures},
    {"KHR_materials_iridescence", "iridescence", &has<&Material::iridescence>,
     &add<&Material::iridescence>, kIridescenceFactors, kIridescenceTextures},
    {"KHR_materials_transmission", "transmission", &has<&Material::transmission>,
     &add<&Material::transmission>, kTransmissionFactors, kTransmissionTextures},
    {"KHR_materials_volume", "volume", &has<&Material::volume>, &add<&Material::volume>,
     kVolumeFactors, kVolumeTextures, &volume_note},
    {"KHR_materials_dispersion", "dispersion", &has<&Material::dispersion>,
     &add<&Material::dispersion>, kDispersionFactors, kNoTextures, &dispersion_note},
    {"KHR_materials_diffuse_transmission", "diffuse transmission",
     &has<&Material::diffuse_transmission>, &add<&Material::diffuse_transmission>,
     kDiffuseTransmissionFactors, kDiffuseTransmissionTextures},
    {"KHR_materials_unlit", "unlit", &has_unlit, &add_unlit, kNoFactors, kNoTextures, nullptr,
     true},
};

}  // namespace

static_assert(std::all_of(kExtensions, kExtensions + kScalesCoreCount,
                          [](const MaterialExtension& e) { return e.scales_core; }));
static_assert(std::none_of(kExtensions + kScalesCoreCount, std::end(kExtensions),
                           [](const MaterialExtension& e) { return e.scales_core; }));

std::span<const MaterialExtension> material_schema() {
  return kExtensions;
}

std::span<const MaterialExtension> material_extensions() {
  return std::span<const MaterialExtension>(kExtensions).subspan(kScalesCoreCount);
}

const MaterialExtension* find_material_extension(const std::string& name) {
  for (const MaterialExtension& e : kExtensions)
    if (name == e.name) return &e;
  return nullptr;
}

float factor_default(const MaterialExtension& extension, const MaterialFactor& factor, int c) {
  Material m;
  extension.add(m);
  return factor.values(m)[c];
}

std::string texture_slot_name(TextureSlot slot) {
  // The core material's slots, by their glTF names less "Texture" (glTF 2.0, 5.19).
  constexpr std::array<const char*, std::size_t(kFirstExtensionTextureSlot)> kCore = {
      "baseColor", "metallicRoughness", "normal", "occlusion", "emissive"};
  if (slot < kFirstExtensionTextureSlot) return kCore[std::size_t(slot)];
  for (const MaterialExtension& e : kExtensions)
    for (const MaterialTexture& t : e.textures)
      if (t.slot == slot) return fmt::format("{}.{}", e.name, t.json_name);
  fail("texture slot {} is not in the material schema", int(slot));
}

TextureRef& texture_in(Material& m, TextureSlot slot) {
  const TextureRef* ref = m.textures()[std::size_t(slot)];
  // An absent extension's slots all point at one shared empty reference.
  if (slot >= kFirstExtensionTextureSlot && ref == Material{}.textures()[std::size_t(slot)])
    fail("texture slot {} of material '{}': its extension is absent", texture_slot_name(slot),
         m.name);
  return const_cast<TextureRef&>(*ref);
}

}  // namespace pbrkit
