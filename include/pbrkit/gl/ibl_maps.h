#pragma once
// The image-based lighting the OpenGL renderer draws with (Renderer::set_ibl): the
// baker's maps (ibl/bake.h) and the bake it makes on the fly from an environment.
#include "pbrkit/ibl/bake.h"
#include "pbrkit/image/environment.h"

namespace pbrkit::gl {

/// Image-based lighting maps as the baker makes them (ibl/bake.h). The cubes hold the
/// environment as it was baked, i.e. with `rotation_deg` and `intensity` already applied;
/// the renderer applies only the difference to the current settings.
struct IblMaps {
  Cubemap specular;
  Cubemap irradiance;
  Cubemap sheen;  ///< Charlie-prefiltered (KHR_materials_sheen); empty: the GGX cube stands in
  SH9 sh{};
  float rotation_deg = 0.0f;
  float intensity = 1.0f;
};
/// IblMaps from a bake of `env` (its rotation and intensity are baked in).
IblMaps ibl_maps_from_bake(BakeResult bake, const Environment& env);
/// The bake the real-time renderer makes on the fly from an environment (`pbrkit render
/// --renderer gl`, `pbrkit view`): `face_size` px specular faces down to 8 px, `samples`
/// GGX samples, a 16 px irradiance cube and a 32 px LUT, and a quadrature budget of 2^30
/// (the rough levels exact, the roughness-0.25 one sampled) so that it takes well under a
/// second on two cores.
BakeOptions realtime_bake_options(int face_size = 128, int samples = 256);

}  // namespace pbrkit::gl
