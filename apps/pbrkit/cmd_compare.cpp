// pbrkit compare: placeholder until its issue lands (it is not listed in --help).
#include "commands.h"

namespace pbrkit::cli {

void register_compare_command(CLI::App& /*app*/) {}

}  // namespace pbrkit::cli
