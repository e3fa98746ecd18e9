#pragma once
// The bake's first stage (BakeResult::environment): the lat-long environment resampled to a
// cube, and the cube's box-filtered mip chain, which the prefilter reads.
#include "pbrkit/ibl/cubemap.h"
#include "pbrkit/image/environment.h"

namespace pbrkit {

/// Supersampling factor per axis used when resampling a `source_width` lat-long map to
/// faces of `face_size` (at least 2x2, about two samples per source texel, at most 8x8).
int cube_supersampling(int source_width, int face_size);

/// Resamples `env` (rotation and intensity applied) to a cube of `face_size` px (>= 1) with
/// one level, each texel the box-filtered average over its (s, t) square. RGBA, A = 1.
Cubemap resample_to_cube(const Environment& env, int face_size);

/// Appends 2x2 box-filtered levels to `cube` until the face size would drop below
/// `min_size` (face sizes must be powers of two).
void build_mip_chain(Cubemap& cube, int min_size);

}  // namespace pbrkit
