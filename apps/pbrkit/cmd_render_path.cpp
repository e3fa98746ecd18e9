// pbrkit render --renderer path: placeholder until the renderer lands.
#include "pbrkit/util/error.h"
#include "render_options.h"

namespace pbrkit::cli {

RenderRunner add_path_render_options(CLI::App& /*render*/) {
  return [](const RenderCommandOptions&) { fail("--renderer path is not available yet"); };
}

}  // namespace pbrkit::cli
