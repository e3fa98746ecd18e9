// The transmission extensions of a material (KhronosGroup/glTF, extensions/2.0/Khronos/):
// KHR_materials_transmission, KHR_materials_volume, KHR_materials_dispersion and
// KHR_materials_diffuse_transmission, read with the helpers and under the rules of
// material_extensions.cpp (wrong types and non-finite values are errors naming the JSON
// path, out-of-range numbers are clamped with a warning naming it).
//
// Whether a volume's mesh is closed is decided per primitive in meshes.cpp (Mesh::closed).
#include <limits>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

}  // namespace

void Loader::read_transmission_extensions(const json& extensions, const std::string& where,
                                          Material& m) {
  auto object = [&](const char* name) { return extension_object(extensions, name, where); };

  // KHR_materials_transmission, "Properties": transmissionFactor in [0, 1], multiplied by
  // transmissionTexture's R channel (linear).
  if (const json* e = object("KHR_materials_transmission")) {
    const std::string path = where + ".extensions.KHR_materials_transmission";
    TransmissionExtension t;
    t.factor = extension_factor(*e, "transmissionFactor", t.factor, 0.0f, 1.0f, path);
    t.texture = extension_texture(*e, "transmissionTexture", false, path);
    m.transmission = t;
  }

  // KHR_materials_volume, "Properties": thicknessFactor in [0, +inf) (0: thin-walled),
  // thicknessTexture's G channel (linear); attenuationDistance in (0, +inf), +inf when
  // absent; attenuationColor, linear, with transmittance T(x) = c^(x / d) ("Attenuation").
  if (const json* e = object("KHR_materials_volume")) {
    const std::string path = where + ".extensions.KHR_materials_volume";
    VolumeExtension v;
    v.thickness_factor =
        extension_factor(*e, "thicknessFactor", v.thickness_factor, 0.0f, kInf, path);
    v.thickness_texture = extension_texture(*e, "thicknessTexture", false, path);
    const float distance =
        extension_factor(*e, "attenuationDistance", v.attenuation_distance, -kInf, kInf, path);
    if (distance <= 0.0f)
      warning(fmt::format(
          "{}.attenuationDistance: {:g} is invalid (the distance must be > 0); ignored: the "
          "medium does not absorb",
          path, distance));
    else
      v.attenuation_distance = distance;
    // Above 1, c^(x / d) grows with the distance travelled: the medium would make light.
    v.attenuation_color = extension_color(*e, "attenuationColor", v.attenuation_color, 1.0f, path);
    m.volume = v;
  }

  // KHR_materials_dispersion: dispersion = 20 / Abbe number, in [0, +inf) (schema).
  if (const json* e = object("KHR_materials_dispersion")) {
    const std::string path = where + ".extensions.KHR_materials_dispersion";
    DispersionExtension d;
    d.dispersion = extension_factor(*e, "dispersion", d.dispersion, 0.0f, kInf, path);
    m.dispersion = d;
  }

  // KHR_materials_diffuse_transmission: diffuseTransmissionFactor in [0, 1] times the
  // texture's A channel (linear); diffuseTransmissionColorFactor times the colour texture's
  // RGB (sRGB). The schema bounds the colour below only; above 1 the surface would
  // transmit more light than reaches it, so it is clamped to 1.
  if (const json* e = object("KHR_materials_diffuse_transmission")) {
    const std::string path = where + ".extensions.KHR_materials_diffuse_transmission";
    DiffuseTransmissionExtension d;
    d.factor = extension_factor(*e, "diffuseTransmissionFactor", d.factor, 0.0f, 1.0f, path);
    d.texture = extension_texture(*e, "diffuseTransmissionTexture", false, path);
    d.color_factor =
        extension_color(*e, "diffuseTransmissionColorFactor", d.color_factor, 1.0f, path);
    d.color_texture = extension_texture(*e, "diffuseTransmissionColorTexture", true, path);
    m.diffuse_transmission = d;
  }

  // Combinations the READMEs give no effect: said, and kept as the file has them.
  if (m.volume && !m.transmission && !m.diffuse_transmission)
    // KHR_materials_volume, "Dependencies": the volume needs an extension that lets light
    // through the surface.
    warning(fmt::format(
        "{}.extensions.KHR_materials_volume: has no effect without KHR_materials_transmission "
        "or KHR_materials_diffuse_transmission (no light enters the volume)",
        where));
  if (m.dispersion && m.dispersion->dispersion > 0.0f &&
      !(m.volume && m.volume->thickness_factor > 0.0f))
    // KHR_materials_dispersion, "Dependencies": it spreads the refraction through a volume;
    // a thin-walled surface does not refract.
    warning(fmt::format(
        "{}.extensions.KHR_materials_dispersion: has no effect without KHR_materials_volume "
        "with thicknessFactor > 0 (a thin-walled surface does not refract)",
        where));
  if (m.volume && m.volume->thickness_factor > 0.0f && m.double_sided)
    // KHR_materials_volume, "Properties": doubleSided has no effect on volume boundaries.
    warning(
        fmt::format("{}.doubleSided: has no effect on a volume boundary (KHR_materials_volume with "
                    "thicknessFactor > 0): both sides of the mesh bound the medium",
                    where));
}

}  // namespace pbrkit::gltf
