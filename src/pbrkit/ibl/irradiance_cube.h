#pragma once
// The diffuse irradiance cube (BakeResult::irradiance). Its SH9 counterpart is in
// spherical_harmonics.h.
#include "pbrkit/ibl/cubemap.h"

namespace pbrkit {

/// The diffuse irradiance E(n) = int L max(0, n.w) dw (not divided by pi) as a one-level RGBA
/// cube of `size` px (>= 1), by direct quadrature over the finest level of `source` of at most
/// 64 px (its coarsest level if every level is larger).
Cubemap irradiance_cube(const Cubemap& source, int size);

}  // namespace pbrkit
