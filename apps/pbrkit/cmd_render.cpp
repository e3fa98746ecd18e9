// pbrkit render: placeholder until its issue lands (it is not listed in --help).
#include "commands.h"

namespace pbrkit::cli {

void register_render_command(CLI::App& /*app*/) {}

}  // namespace pbrkit::cli
