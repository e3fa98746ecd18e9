#pragma once
// Private to the OpenGL renderer: the names the surface program (pbr_vertex.glsl,
// pbr_fragment.glsl) uses for its texture slots, texture units and buffer binding points,
// and those of the background and display programs. The numbers live here once;
// surface_prelude(), background_prelude() and display_prelude() write them as #defines that
// the shaders read by name, so no GLSL file types a slot, a unit or a binding point, and
// adding a texture slot to scene.h's TextureSlot names its defines without touching this
// file.
#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit::gl {

/// The last slot whose unit lies among the other units below; the slots after it take
/// the units after kAnisotropicAlbedoUnit, so that a new slot needs no unit chosen by hand.
inline constexpr TextureSlot kLastInterleavedSlot = TextureSlot::kDiffuseTransmissionColor;

/// The texture unit of a material texture slot: the core slots on 0..4, kSpecular ..
/// kIridescenceThickness on 9..18, the transmission extensions' on 22..25 (the units
/// between hold the tables and cubes below), any later slot from 31 on.
GLuint texture_unit(TextureSlot slot);

// The surface program's other texture units.
inline constexpr GLuint kEnergyDirectUnit = 5;  ///< EnergyTable of the direct lights' G
inline constexpr GLuint kEnergyIblUnit = 6;     ///< EnergyTable of the IBL's G
inline constexpr GLuint kSpecularCubeUnit = 7;
inline constexpr GLuint kIrradianceCubeUnit = 8;
inline constexpr GLuint kCoatEnergyUnit = 19;  ///< EnergyTable of the reference G
inline constexpr GLuint kSheenCubeUnit = 20;
inline constexpr GLuint kSheenLutUnit = 21;
inline constexpr GLuint kTransmissionFrameUnit = 26;
inline constexpr GLuint kBackPositionUnit = 27, kBackNormalUnit = 28, kFrameDepthUnit = 29;
inline constexpr GLuint kAnisotropicAlbedoUnit = 30;  ///< AnisotropicAlbedoTable (3D)
/// The highest unit the surface program samples.
inline constexpr GLuint kLastSurfaceUnit =
    kAnisotropicAlbedoUnit + GLuint(kTextureSlotCount - 1 - int(kLastInterleavedSlot));

/// One binding of a program (the surface's, the background's, the display's) as its
/// prelude names it: BINDING_<name>.
struct SurfaceBinding {
  /// What the point numbers: each kind has its own numbering in GL.
  enum class Kind { kSampler, kStorageBuffer, kUniformBuffer };
  std::string name;  ///< e.g. "SHEEN_LUT", "SHEEN_COLOR_TEXTURE", "PUNCTUAL_LIGHTS"
  GLuint point = 0;  ///< the texture unit, or the buffer binding point
  Kind kind = Kind::kSampler;
};

/// Every texture unit and buffer binding point of the surface program.
std::vector<SurfaceBinding> surface_bindings();

/// The slot's name in the shaders' defines, from its glTF property name:
/// "BASE_COLOR_TEXTURE", ..., "SHEEN_COLOR_TEXTURE" (texture_slot_name() in upper snake
/// case, the extension dropped, "_TEXTURE" appended where the name lacks it).
std::string texture_slot_macro(TextureSlot slot);

/// The surface program's uniform for an extension's factor: "u" and the factor's JSON
/// name capitalised (sheenColorFactor: uSheenColorFactor), a float or a vec3 as the
/// factor's components.
std::string factor_uniform(const MaterialFactor& factor);

// The background program's units (background_fragment.glsl) and the display program's
// (display_fragment.glsl): programs of their own, so they number from 0 again.
inline constexpr GLuint kBackgroundEnvironmentUnit = 0;   ///< the equirect environment
inline constexpr GLuint kBackgroundSpecularCubeUnit = 1;  ///< the prefiltered cube
inline constexpr GLuint kDisplayFrameUnit = 0;            ///< the linear frame

/// Every texture unit of the background program, BINDING_<name> in its prelude.
std::vector<SurfaceBinding> background_bindings();
/// Every texture unit of the display program, BINDING_<name> in its prelude.
std::vector<SurfaceBinding> display_bindings();

/// The #defines every background permutation starts with: BINDING_<name> for each of
/// background_bindings().
const std::string& background_prelude();
/// The #defines every display permutation starts with: BINDING_<name> for each of
/// display_bindings().
const std::string& display_prelude();

/// The #defines every surface permutation starts with: SLOT_<slot> (the index into
/// uTexcoordSet and uTextureTransform) for each texture slot and BINDING_<name> for each
/// of surface_bindings().
const std::string& surface_prelude();

}  // namespace pbrkit::gl
