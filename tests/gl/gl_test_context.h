#pragma once
// One headless GL context for the whole gl_tests program (creating an EGL context per test
// would cost start-up time on llvmpipe for nothing).
#include "pbrkit/gl/context.h"
#include "pbrkit/gl/ibl_maps.h"
#include "pbrkit/ibl/bake.h"

namespace pbrkit::gl::testing {

inline HeadlessContext& context() {
  static HeadlessContext ctx;
  ctx.make_current();
  return ctx;
}

/// The small bake the GL image tests light with (16-texel faces, 16 samples, a 4-texel
/// irradiance map, an 8x8 LUT): enough for a uniform or smooth environment, quick to bake.
inline IblMaps small_ibl_maps(const Environment& env) {
  BakeOptions bake;
  bake.face_size = 16;
  bake.min_face_size = 4;
  bake.samples = 16;
  bake.irradiance_size = 4;
  bake.lut_size = 8;
  return ibl_maps_from_bake(bake_environment(env, bake), env);
}

}  // namespace pbrkit::gl::testing
