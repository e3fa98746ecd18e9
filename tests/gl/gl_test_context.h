#pragma once
// One headless GL context for the whole gl_tests program (creating an EGL context per test
// would cost start-up time on llvmpipe for nothing).
#include "pbrkit/gl/context.h"

namespace pbrkit::gl::testing {

inline HeadlessContext& context() {
  static HeadlessContext ctx;
  ctx.make_current();
  return ctx;
}

}  // namespace pbrkit::gl::testing
