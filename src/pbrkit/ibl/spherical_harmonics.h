#pragma once
// Order-2 (9-coefficient) spherical harmonics of irradiance (Ramamoorthi & Hanrahan 2001,
// "An Efficient Representation for Irradiance Environment Maps"). The SH9 type and its
// convention are in bake.h; eval_sh_irradiance() is declared there.
#include <array>

#include <glm/glm.hpp>

#include "pbrkit/ibl/bake.h"
#include "pbrkit/ibl/cubemap.h"

namespace pbrkit {

/// The 9 real SH basis functions at unit direction d, in SH9's order.
std::array<float, 9> sh_basis(glm::vec3 d);

/// Projects the radiance of `level` of `cube` onto SH (exact texel solid angles) and
/// folds in the cosine-lobe convolution A_l (R&H 2001 eq. 8), giving irradiance
/// coefficients in SH9's convention. Deterministic (independent of the thread count).
SH9 project_sh_irradiance(const Cubemap& cube, int level = 0);

}  // namespace pbrkit
