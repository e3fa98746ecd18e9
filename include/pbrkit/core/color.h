#pragma once
// Colour: the exact sRGB transfer functions (IEC 61966-2-1, not pow(1/2.2)), Rec.709
// luminance, exposure in EV, and the named tone mappers used by every renderer.
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit {

/// IEC 61966-2-1 sRGB encoding of a linear value in [0,1].
float srgb_encode(float linear);
/// Inverse of srgb_encode.
float srgb_decode(float encoded);
glm::vec3 srgb_encode(glm::vec3 linear);
glm::vec3 srgb_decode(glm::vec3 encoded);

/// Rec.709 / sRGB-primaries relative luminance Y = 0.2126 R + 0.7152 G + 0.0722 B.
inline float luminance(glm::vec3 c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

/// Multiplier for an exposure of `ev` stops: 2^ev.
float exposure_scale(float ev);

enum class ToneMapper {
  kNone,        ///< clamp to [0,1]
  kPbrNeutral,  ///< Khronos PBR Neutral (2024)
  kAces,        ///< ACES filmic, Stephen Hill's fit (RRT+ODT with sRGB matrices)
  kAgx,         ///< AgX (Troy Sobotka), base look, Blender/three.js formulation
};

/// Parses "none", "pbr-neutral", "aces", "agx". Throws pbrkit::Error listing the names.
ToneMapper parse_tone_mapper(std::string_view name);
std::string_view tone_mapper_name(ToneMapper t);
std::vector<std::string> tone_mapper_names();

/// Maps linear scene-referred RGB to linear display RGB in [0,1] (before sRGB encoding).
glm::vec3 tone_map(ToneMapper t, glm::vec3 linear);

/// The full display transform used for PNG output and previews:
/// exposure -> tone mapper -> sRGB encode. Output in [0,1].
glm::vec3 display_transform(glm::vec3 linear, float exposure_ev, ToneMapper t);

}  // namespace pbrkit
