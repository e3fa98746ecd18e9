#pragma once
// The raster view's debug channels (the Khronos glTF Sample Viewer's debug outputs): what
// the OpenGL renderer's surfaces write instead of their shaded colour. The material's
// inputs after textures (base colour, metallic, roughness, the shading normal as
// n * 0.5 + 0.5, occlusion, emission), or one lobe's share of the shaded radiance (the
// lobes of every pixel sum to its shaded colour less its emission). Values are raw: no
// exposure and no tone mapping (shaders/debug_channels.glsl says how each is isolated).
// Two limits: an unlit material's colour (KHR_materials_unlit) is in no lobe, and a
// transmissive surface refracts the opaque frame as drawn in the same channel, so the
// transmission lobe of glass in front of opaque surfaces shows their channel, not their
// shaded colour (over the background it is exact).
#include <string>
#include <string_view>
#include <vector>

namespace pbrkit::gl {

/// The order is DEBUG_CHANNEL's in shaders/debug_channels.glsl.
enum class DebugChannel {
  kNone,  ///< the shaded colour
  kBaseColor,
  kMetallic,
  kRoughness,
  kNormal,  ///< the shading normal (world space) as n * 0.5 + 0.5
  kOcclusion,
  kEmissive,
  kDiffuse,   ///< the diffuse lobe with the diffuse transmission (the Sample Viewer's f_diffuse)
  kSpecular,  ///< the base's specular lobe (with its multiple scattering)
  kClearcoat,
  kSheen,
  kTransmission,  ///< the specular transmission (KHR_materials_transmission)
};

/// "none", "base-color", "metallic", "roughness", "normal", "occlusion", "emissive",
/// "diffuse", "specular", "clearcoat", "sheen", "transmission". Throws pbrkit::Error
/// listing the names.
DebugChannel parse_debug_channel(std::string_view name);
std::string_view debug_channel_name(DebugChannel c);
std::vector<std::string> debug_channel_names();
/// The lobe channels (diffuse ... transmission): radiance, shown like the shaded colour;
/// the others are material inputs in [0, 1].
bool is_lobe_channel(DebugChannel c);

}  // namespace pbrkit::gl
