#pragma once
// glTF material evaluation at a path-tracer hit: texture lookups (level of detail 0, i.e.
// the full-resolution texture filtered bilinearly; at the sample counts the path tracer
// uses, pixel footprint filtering comes from supersampling), alpha, emission and the
// normal-mapped shading frame.
#include <glm/glm.hpp>

#include "pbrkit/pt/geometry.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit {

struct ShadingInputs {
  glm::vec3 base_color{1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;
  glm::vec3 ns{0.0f, 0.0f, 1.0f};  ///< shading normal after normal mapping (world)
};

/// Texture coordinates of `ref` at the hit (TEXCOORD_n and KHR_texture_transform).
glm::vec2 texture_uv(const TextureRef& ref, const SurfaceHit& hit);
/// alpha = baseColorFactor.a x texture alpha x COLOR_0 alpha.
float material_alpha(const Scene& scene, const Material& m, const SurfaceHit& hit);
/// Emitted radiance (emissiveFactor x strength x emissiveTexture), both sides.
glm::vec3 material_emission(const Scene& scene, const Material& m, const SurfaceHit& hit);
/// Base colour, metallic, roughness and the normal-mapped shading normal, turned to the
/// side of `hit.ng`, which must already face the viewer. `hit.ns` is the interpolated
/// vertex normal as the mesh gives it.
ShadingInputs shade_inputs(const Scene& scene, const Material& m, const SurfaceHit& hit);

}  // namespace pbrkit
