#pragma once
// Private to the OpenGL renderer: the names the surface program (pbr_vertex.glsl,
// pbr_fragment.glsl) uses for its texture slots, texture units and buffer binding points,
// and those of the background and display programs. The numbers live here once;
// surface_prelude(), background_prelude() and display_prelude() write them as #defines that
// the shaders read by name, so no GLSL file types a slot, a unit or a binding point, and
// adding a texture slot to scene.h's TextureSlot names its defines without touching this
// file. It is the one list of every unit and binding point, handed out in order, and it
// sits at the bottom of the module: gpu_scene, gpu_deformation, light_clusters and occluders
// read their binding points from it, and it includes none of the renderer's other parts
// (tests/gl/source_includes_test.cpp).
#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit::gl {

/// The texture unit of a material texture slot: the slot's own index, so the material's
/// units are 0 .. kTextureSlotCount - 1 in scene.h's TextureSlot order and a new slot takes
/// the next one.
constexpr GLuint texture_unit(TextureSlot slot) {
  return GLuint(slot);
}

// The surface program's other texture units, handed out in this order after the material
// slots' (surface_bindings() lists them in the same order).
inline constexpr GLuint kEnergyDirectUnit = GLuint(kTextureSlotCount);  ///< EnergyTable, direct G
inline constexpr GLuint kEnergyIblUnit = kEnergyDirectUnit + 1;  ///< EnergyTable of the IBL's G
inline constexpr GLuint kSpecularCubeUnit = kEnergyIblUnit + 1;
inline constexpr GLuint kIrradianceCubeUnit = kSpecularCubeUnit + 1;
inline constexpr GLuint kCoatEnergyUnit = kIrradianceCubeUnit + 1;  ///< EnergyTable, reference G
inline constexpr GLuint kSheenCubeUnit = kCoatEnergyUnit + 1;
inline constexpr GLuint kSheenLutUnit = kSheenCubeUnit + 1;
inline constexpr GLuint kTransmissionFrameUnit = kSheenLutUnit + 1;
inline constexpr GLuint kBackPositionUnit = kTransmissionFrameUnit + 1;
inline constexpr GLuint kBackNormalUnit = kBackPositionUnit + 1;
inline constexpr GLuint kFrameDepthUnit = kBackNormalUnit + 1;
inline constexpr GLuint kAnisotropicAlbedoUnit = kFrameDepthUnit + 1;  ///< AnisotropicAlbedoTable
/// AnisotropicEnergyTable (core/anisotropic_energy.h): the anisotropic lobe's compensation.
inline constexpr GLuint kAnisotropicEnergyUnit = kAnisotropicAlbedoUnit + 1;
/// The highest unit the surface program samples.
inline constexpr GLuint kLastSurfaceUnit = kAnisotropicEnergyUnit;

// The surface program's buffers, each kind numbered from 0 in this order (GL numbers
// shader storage and uniform buffer binding points apart). The files that fill them read
// their points from here: gpu_scene.h, light_clusters.h, occluders.h, gpu_deformation.h.
/// GpuScene::instance_buffer (pbr_vertex.glsl's InstanceTransforms).
inline constexpr GLuint kInstanceBufferBinding = 0;
/// The light buffers (surface_light_punctual.glsl's PunctualLights, LightClusterRanges and
/// ListedLights; light_clusters.h's GpuLightBuffers).
inline constexpr GLuint kLightBufferBinding = kInstanceBufferBinding + 1;
inline constexpr GLuint kClusterRangeBufferBinding = kLightBufferBinding + 1;
inline constexpr GLuint kListedLightBufferBinding = kClusterRangeBufferBinding + 1;
/// A deforming mesh's rest vertices, joint influences, triangle corners and morph targets,
/// and the pose's joint matrices and morph weights (deformation.glsl's DeformVertices,
/// JointMatrices and MorphWeights; gpu_deformation.h's GpuDeformation).
inline constexpr GLuint kDeformVertexBufferBinding = kListedLightBufferBinding + 1;
inline constexpr GLuint kJointMatrixBufferBinding = kDeformVertexBufferBinding + 1;
inline constexpr GLuint kMorphWeightBufferBinding = kJointMatrixBufferBinding + 1;
/// The occluder block (occluders.glsl's Occluders; occluders.h's GpuOccluderBuffer), the
/// only uniform buffer.
inline constexpr GLuint kOccluderBufferBinding = 0;

/// One binding of a program (the surface's, the background's, the display's) as its
/// prelude names it: BINDING_<name>.
struct SurfaceBinding {
  /// What the point numbers: each kind has its own numbering in GL.
  enum class Kind { kSampler, kStorageBuffer, kUniformBuffer };
  std::string name;  ///< e.g. "SHEEN_LUT", "SHEEN_COLOR_TEXTURE", "PUNCTUAL_LIGHTS"
  GLuint point = 0;  ///< the texture unit, or the buffer binding point
  Kind kind = Kind::kSampler;
};

/// Every texture unit and buffer binding point of the surface program: the one list, in
/// the order the points are handed out above.
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
