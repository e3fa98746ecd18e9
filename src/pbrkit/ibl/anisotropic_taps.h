#pragma once
// The image-based lighting of an anisotropic GGX lobe (KHR_materials_anisotropy) in the
// OpenGL renderer: three directions drawn from the lobe's distribution of visible normals
// (Heitz 2018's sampler at fixed points of its disk: the centre and two points along the
// lobe's long axis), each looked up in the prefiltered specular cube at the roughness of
// the isotropic lobe with the whole lobe's solid angle at normal incidence ("filtered
// importance sampling", Colbert & Krivanek, GPU Gems 3 ch. 20, 2007). The taps' mean, weighted by
// the VNDF estimator's G2 / G1, says where the stretched lobe gathers light; its scale is the
// lobe's albedo from ibl/anisotropic_albedo.h, since three weights estimate the albedo
// badly where the horizon cuts a stretched lobe. shaders/anisotropy_ibl.glsl is the same
// code; tests/gl/anisotropy_glsl_test.cpp holds them equal.
#include <array>

#include <glm/glm.hpp>

namespace pbrkit {

/// Directions per shading point (each one prefiltered-cube lookup).
inline constexpr int kAnisotropicTaps = 3;

/// One direction of the lobe, in the local shading frame (n = +Z, +X the anisotropy
/// direction).
struct AnisotropicTap {
  glm::vec3 wi{0.0f};      ///< the reflected direction
  float weight = 0.0f;     ///< G2 / G1(wo) (the VNDF estimator's weight), 0 below the horizon
  float roughness = 0.0f;  ///< perceptual roughness of the cube lookup (the same for all)
};

/// Tap `i`'s point on Heitz 2018's disk, in the lobe's axes: the centre, then (+-sqrt(3/8),
/// 0) along the long axis (+X), where three equal weights keep the disk's second moment
/// along it (a rule chosen, not fitted: of the radii 0.6 to 0.85 measured against the path
/// tracer under five environments, those near it gave the smallest errors away from the two
/// the scheme was developed under).
glm::vec2 anisotropic_tap_point(int i);

/// Heitz 2018's visible-normal sample of the anisotropic GGX lobe for the disk point `d`
/// (|d| <= 1) measured from the lobe's +X rather than from the sampler's view-dependent
/// frame: the taps hold to the lobe as the view turns (a point turned with the view's
/// azimuth creases the image where that azimuth swings by pi). A uniform point of the disk
/// gives the visible normals' distribution exactly, as the original does.
glm::vec3 anisotropic_visible_normal(glm::vec3 wo, glm::vec2 d, float alpha_x, float alpha_y);

/// Tap `i` of the lobe for `wo` (local, wo.z > 0) and the lobe's alpha_x, alpha_y.
/// The lobe's radiance without Fresnel, integral of D G2 / (4 n.v) L dwi, is estimated by
/// albedo sum_i weight_i L(wi_i) / sum_i weight_i (0 where every weight is), the albedo
/// from AnisotropicAlbedoTable.
AnisotropicTap anisotropic_tap(glm::vec3 wo, float alpha_x, float alpha_y, int i);

/// All kAnisotropicTaps taps.
std::array<AnisotropicTap, kAnisotropicTaps> anisotropic_taps(glm::vec3 wo, float alpha_x,
                                                              float alpha_y);

}  // namespace pbrkit
