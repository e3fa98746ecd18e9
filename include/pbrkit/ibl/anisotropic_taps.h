#pragma once
// The image-based lighting of an anisotropic GGX lobe (KHR_materials_anisotropy) in the
// OpenGL renderer: a fixed set of directions drawn from the lobe's distribution of visible
// normals, each looked up in the prefiltered specular cube at a roughness whose lobe covers
// the direction's share of the solid angle ("filtered importance sampling", Colbert &
// Krivanek, GPU Gems 3 ch. 20, 2007; Krivanek & Colbert 2008). The stretched lobe is
// followed by the taps themselves (Heitz 2018's sampling stretches them along the major
// axis), and their mean weight is the lobe's single-scattering albedo without Fresnel,
// the same estimator the path tracer uses with random points, so the split sum's scale
// follows the anisotropic lobe the path tracer integrates, not the isotropic table's.
// shaders/anisotropy_ibl.glsl is the same code; tests/gl/anisotropy_glsl_test.cpp holds
// them equal.
#include <array>

#include <glm/glm.hpp>

namespace pbrkit {

/// Directions per shading point (each one prefiltered-cube lookup).
inline constexpr int kAnisotropicTaps = 8;

/// One direction of the lobe, in the local shading frame (n = +Z, +X the anisotropy
/// direction).
struct AnisotropicTap {
  glm::vec3 wi{0.0f};      ///< the reflected direction
  float weight = 0.0f;     ///< G2 / G1(wo) (the VNDF estimator's weight), 0 below the horizon
  float roughness = 0.0f;  ///< perceptual roughness of the cube lookup
};

/// The (u1, u2) of tap `i` in Heitz 2018's sampling: u1 stratified (one point per stratum),
/// u2 = frac(i / 4 + 5 / 16), four arms of two radii (the rank-1 lattice measured best).
glm::vec2 anisotropic_tap_point(int i);

/// Heitz 2018's visible-normal sample of the anisotropic GGX lobe for the unit square's
/// `u`, with the disk point's polar angle measured from the lobe's +X rather than from the
/// sampler's view-dependent frame: the taps hold to the lobe as the view turns (a lattice
/// turned with the view's azimuth creases the image where that azimuth swings by pi).
/// Uniform `u` gives the visible normals' distribution exactly, as the original does.
glm::vec3 anisotropic_visible_normal(glm::vec3 wo, glm::vec2 u, float alpha_x, float alpha_y);

/// Tap `i` of the lobe for `wo` (local, wo.z > 0) and the lobe's alpha_x, alpha_y.
/// The lobe's radiance without Fresnel, integral of D G2 / (4 n.v) L dwi, is estimated by
/// sum_i weight_i L(wi_i) / kAnisotropicTaps, and its albedo by the mean weight.
AnisotropicTap anisotropic_tap(glm::vec3 wo, float alpha_x, float alpha_y, int i);

/// All kAnisotropicTaps taps.
std::array<AnisotropicTap, kAnisotropicTaps> anisotropic_taps(glm::vec3 wo, float alpha_x,
                                                              float alpha_y);

}  // namespace pbrkit
