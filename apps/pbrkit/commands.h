#pragma once
// The pbrkit CLI: one file per subcommand (cmd_<name>.cpp), each a thin shell that parses
// options and calls the library. Each file defines one register_<name>_command().
#include <string>

#include <CLI/CLI.hpp>

#include "pbrkit/scene/load.h"

namespace pbrkit::cli {

/// A subcommand's callback may throw this to make pbrkit exit with `code` (e.g. 130 after
/// SIGINT) once its outputs are written.
struct ExitRequest {
  int code;
};

/// The built-in scenes' names, comma-separated, for --help texts.
inline std::string builtin_scene_list() {
  std::string s;
  for (const std::string& name : builtin_scene_names()) s += (s.empty() ? "" : ", ") + name;
  return s;
}

void register_brdf_command(CLI::App& app);
void register_scene_command(CLI::App& app);
void register_info_command(CLI::App& app);
void register_bake_command(CLI::App& app);
void register_render_command(CLI::App& app);
void register_merge_command(CLI::App& app);
void register_compare_command(CLI::App& app);
void register_view_command(CLI::App& app);

}  // namespace pbrkit::cli
