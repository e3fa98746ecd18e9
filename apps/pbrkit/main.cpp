// pbrkit: the command-line program. Parsing and error reporting live here; every
// subcommand is in its own cmd_<name>.cpp and calls the library.
#include <cstdio>
#include <exception>

#include "commands.h"
#include "numeric_options.h"
#include "pbrkit/util/error.h"

int main(int argc, char** argv) {
  CLI::App app{"pbrkit " PBRKIT_VERSION
               ": a physically based rendering toolkit. One material model (docs/MODEL.md)\n"
               "for image-based-lighting bakes, a real-time OpenGL renderer and a Monte Carlo path "
               "tracer.\nRun 'pbrkit <command> --help' for each command's options."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "pbrkit " PBRKIT_VERSION);

  using namespace pbrkit::cli;
  register_brdf_command(app);
  register_scene_command(app);
  register_info_command(app);
  register_bake_command(app);
  register_render_command(app);
  register_merge_command(app);
  register_denoise_command(app);
  register_compare_command(app);
  register_view_command(app);
  require_finite_numbers(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const ExitRequest& request) {
    return request.code;
  } catch (const pbrkit::Error& e) {
    std::fprintf(stderr, "pbrkit: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pbrkit: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
