#pragma once
// glTF material evaluation at a path-tracer hit: texture lookups (trilinear at the ray
// cone's level of detail when the integrator set hit.footprint, else level 0 filtered
// bilinearly), alpha, emission and the normal-mapped shading frame.
#include <glm/glm.hpp>

#include "pbrkit/core/bsdf.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit {

struct ShadingInputs {
  SurfaceParams params;            ///< the layered material's inputs (core/bsdf.h)
  glm::vec3 ns{0.0f, 0.0f, 1.0f};  ///< shading normal after normal mapping (world)
  glm::vec3 tangent{0.0f};         ///< anisotropy direction (world, unit, normal to ns); 0: none
  glm::vec3 coat_normal{0.0f, 0.0f, 1.0f};  ///< the clearcoat's normal (world)
  bool unlit = false;                       ///< KHR_materials_unlit: shows params.base.base_color
};

/// Texture coordinates of `ref` at the hit (TEXCOORD_n and KHR_texture_transform).
glm::vec2 texture_uv(const TextureRef& ref, const SurfaceHit& hit);
/// alpha = baseColorFactor.a x texture alpha x COLOR_0 alpha.
float material_alpha(const Scene& scene, const Material& m, const SurfaceHit& hit);
/// Emitted radiance (emissiveFactor x strength x emissiveTexture), both sides.
glm::vec3 material_emission(const Scene& scene, const Material& m, const SurfaceHit& hit);
/// Every material input at the hit (glTF's core and the KHR_materials_* extensions, factors
/// times textures) and the normal-mapped shading and coat normals, turned to the side of
/// `hit.ng`, which must already face the viewer. `hit.ns` is the interpolated vertex
/// normal as the mesh gives it.
ShadingInputs shade_inputs(const Scene& scene, const Material& m, const SurfaceHit& hit);

}  // namespace pbrkit
