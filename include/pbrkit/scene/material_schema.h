#pragma once
// The KHR_materials_* extensions as data: for each one its glTF name, its factors (the
// Material member, JSON name, valid range, whether a colour) and its texture slots (JSON
// name, the channels the README reads, colour space, the TextureSlot it fills). The glTF
// reader, the glTF writer and `pbrkit info` iterate this one table, so an extension's JSON
// names, defaults and ranges are written once (material_schema.cpp), each row citing its
// README (KhronosGroup/glTF, extensions/2.0/Khronos/<name>/README.md).
//
// The defaults are not repeated here: a factor's default is the value of a freshly added
// extension, that is the member initialiser of its struct in scene.h (each the README's).
#include <span>
#include <string>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

/// How an interactive control edits a factor (the viewer's override panel): a slider over
/// [min, max] (inside the valid range, and finite where that is not) starting at `start`, a
/// value that shows the extension's effect (its default may show none: a sheen colour of 0).
struct FactorControl {
  float min, max, start;
  bool logarithmic = false;  ///< a slider over several decades
};

/// One number or RGB colour of an extension.
struct MaterialFactor {
  const char* json_name;  ///< the property's name in the extension object
  /// How `pbrkit info` shows it in its one-line summary: "{}" stands for the value.
  const char* summary;
  int components;  ///< 1: a number; 3: an RGB colour (linear), a JSON array of 3
  float min, max;  ///< the valid range (of each component); values outside are clamped
  FactorControl control;
  /// The value's components in `m`, whose extension is present.
  float* (*values)(Material& m);
  /// For a value the range cannot describe (null for none): replaces an invalid `value`
  /// by the one to use and returns why it is invalid (the reader's warning), or returns
  /// null when `value` is valid. The range is then not applied.
  const char* (*check)(float& value) = nullptr;
  /// Whether a value `check` rejects makes the file an error (the reason is the message)
  /// rather than a warning: for a value that no replacement would make mean what was meant.
  bool rejected_is_error = false;

  /// The components in a const material (which must hold the extension).
  const float* read(const Material& m) const { return values(const_cast<Material&>(m)); }
};

/// One texture of an extension.
struct MaterialTexture {
  const char* json_name;  ///< the textureInfo's property name
  TextureSlot slot;       ///< where Material::textures() lists it
  const char* channels;   ///< the channels the README reads ("R", "RGB", "A", ...)
  bool srgb;              ///< colour space of its colour channels: sRGB, else linear
  /// A normalTextureInfo's `scale` (null for a plain textureInfo).
  float* (*scale)(Material& m) = nullptr;
};

/// One KHR_materials_* extension.
struct MaterialExtension {
  const char* name;     ///< the glTF extension name
  const char* summary;  ///< its name in `pbrkit info`'s summary line
  /// Whether `m` uses it. KHR_materials_ior has no optional: it is "used" when the index
  /// differs from the default 1.5.
  bool (*present)(const Material& m);
  /// Makes it present in `m` with the README's defaults.
  void (*add)(Material& m);
  std::span<const MaterialFactor> factors;
  std::span<const MaterialTexture> textures;
  /// A derived fact for `pbrkit info`'s summary ("" for none), null for none.
  std::string (*note)(const Material& m) = nullptr;
  /// It excludes every other extension (KHR_materials_unlit: each other README lists it
  /// among its exclusions): the writer writes it alone, the reader warns of the others.
  bool exclusive = false;
  /// It scales a value of the core material rather than adding a surface input
  /// (KHR_materials_emissive_strength scales emissiveFactor): the renderers read the
  /// product, not the extension (material_extensions() leaves it out).
  bool scales_core = false;
};

/// Every KHR_materials_* extension the reader accepts, in the order the reader, the writer
/// and `pbrkit info` list them: the ones that scale a core value first, then
/// material_extensions().
std::span<const MaterialExtension> material_schema();

/// The extensions that add inputs to the surface (material_schema() less the ones that
/// scale a core value): what the renderers read per extension.
std::span<const MaterialExtension> material_extensions();

/// The extension `name` of material_schema() (nullptr when it is not in the schema).
const MaterialExtension* find_material_extension(const std::string& name);

/// The default of `factor`'s component `c` (the value of a freshly added `extension`).
float factor_default(const MaterialExtension& extension, const MaterialFactor& factor, int c);

/// The slot's name as `pbrkit info` prints it: "baseColor", ..., and
/// "<extension>.<jsonName>" for an extension's slot ("KHR_materials_sheen.sheenColorTexture").
std::string texture_slot_name(TextureSlot slot);

/// The slot of `m`, writable (its extension must be present in `m`).
TextureRef& texture_in(Material& m, TextureSlot slot);

}  // namespace pbrkit
