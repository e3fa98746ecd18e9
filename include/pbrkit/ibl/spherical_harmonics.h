#pragma once
// Order-2 (9-coefficient) spherical harmonics of irradiance (Ramamoorthi & Hanrahan 2001,
// "An Efficient Representation for Irradiance Environment Maps").
#include <array>

#include <glm/glm.hpp>

#include "pbrkit/ibl/cubemap.h"

namespace pbrkit {

/// 9 SH coefficients (bands l <= 2) per colour channel. Convention: the coefficients of
/// the IRRADIANCE E(n) = int L(w) max(0, n.w) dw (Ramamoorthi & Hanrahan 2001, eq. 8:
/// the cosine-lobe convolution A_l is folded in, 1/pi is NOT), in the real SH basis order
/// (l,m) = (0,0), (1,-1), (1,0), (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2), with
/// Y_1-1 ~ y, Y_10 ~ z, Y_11 ~ x. Lambertian outgoing radiance is baseColor / pi * E(n).
using SH9 = std::array<glm::vec3, 9>;

/// The 9 real SH basis functions at unit direction d, in SH9's order.
std::array<float, 9> sh_basis(glm::vec3 d);

/// Projects the radiance of `level` of `cube` onto SH (exact texel solid angles) and
/// folds in the cosine-lobe convolution A_l (R&H 2001 eq. 8), giving irradiance
/// coefficients in SH9's convention. Deterministic (independent of the thread count).
SH9 project_sh_irradiance(const Cubemap& cube, int level = 0);

/// Evaluates the irradiance E(n) from SH9 coefficients at unit world direction `n`.
glm::vec3 eval_sh_irradiance(const SH9& sh, glm::vec3 n);

}  // namespace pbrkit
