// pbrkit brdf: placeholder, replaced by the plots of the foundation issue.
#include "commands.h"

namespace pbrkit::cli {

void register_brdf_command(CLI::App& /*app*/) {}

}  // namespace pbrkit::cli
