#pragma once
// The sheen's image-based light from the environment's order-2 spherical harmonics, the
// real-time renderer's sheen IBL (gl/shaders/sheen.glsl's sheen_sh_radiance is its GLSL
// twin; docs/MODEL.md "Sheen maps").
//
// The sheen lobe w(l) = D_Charlie(h) V_Charlie(v, l) (n.l) (core/sheen.h) integrates an
// environment L to E(n.v) <L>_w, <L>_w = int L w dl / E. For L's bands 0-2 (a polynomial
// of degree 2 in l) <L>_w needs only the lobe's first and second moments, which
// SheenTable tabulates per (n.v, roughness) in the frame (t, n, b): so the lobe's average
// of the SH-projected environment is exact, with the lobe's real direction (its mean lies
// on the viewer's side of n: at grazing view the Charlie lobe back-scatters) and spread.
// The split sum's lookup along the mirror direction R (the Khronos Sample Viewer's
// Charlie-prefiltered cube) has neither.
#include <glm/glm.hpp>

#include "pbrkit/ibl/spherical_harmonics.h"

namespace pbrkit {

/// v's direction in n's tangent plane (n, v unit), or at normal incidence, where the lobe is
/// symmetric about n, a fixed perpendicular of n.
glm::vec3 sheen_tangent(glm::vec3 n, glm::vec3 v);

/// <L>_w: the radiance of the environment whose irradiance SH is `irradiance_sh` (SH9's
/// convention) averaged over the normalised sheen lobe at (n, v, roughness), from
/// SheenTable's moments (n, v unit, in the frame of the SH). The sheen IBL is then
/// sheenColor E(n.v) <L>_w. Not clamped (an order-2 SH can go negative).
glm::vec3 sheen_sh_radiance(const SH9& irradiance_sh, glm::vec3 n, glm::vec3 v, float roughness);

}  // namespace pbrkit
