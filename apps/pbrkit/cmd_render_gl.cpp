// pbrkit render --renderer gl: placeholder until the renderer lands.
#include "pbrkit/util/error.h"
#include "render_options.h"

namespace pbrkit::cli {

RenderRunner add_gl_render_options(CLI::App& /*render*/) {
  return [](const RenderCommandOptions&) { fail("--renderer gl is not available yet"); };
}

}  // namespace pbrkit::cli
