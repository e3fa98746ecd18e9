#pragma once
// The pbrkit CLI: one file per subcommand (cmd_<name>.cpp), each a thin shell that parses
// options and calls the library. Each file defines one register_<name>_command().
#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/util/progress.h"

namespace pbrkit::cli {

/// A subcommand's callback may throw this to make pbrkit exit with `code` (e.g. 130 after
/// SIGINT) once its outputs are written.
struct ExitRequest {
  int code;
};

/// The built-in scenes' names, comma-separated, for --help texts.
/// load_scene with a progress bar on stderr once the load has taken a second (a file of
/// 10^5 nodes takes a few).
inline Scene load_scene_showing_progress(const std::string& scene) {
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<ProgressBar> bar;
  LoadOptions options;
  options.progress = [&](double fraction, const std::string& detail) {
    if (!bar && std::chrono::steady_clock::now() - start > std::chrono::seconds(1))
      bar = std::make_unique<ProgressBar>("load");
    if (bar) bar->update(fraction, detail);
    return true;
  };
  Scene loaded = load_scene(scene, options);
  if (bar) bar->finish();
  return loaded;
}

inline std::string builtin_scene_list() {
  std::string s;
  for (const std::string& name : builtin_scene_names()) s += (s.empty() ? "" : ", ") + name;
  return s;
}

/// --multiscatter / --no-multiscatter into `value`, which stays unset without either (the
/// model then decides). Two callbacks: CLI11 2.3's add_flag on a std::optional<bool> sets
/// it to false when neither flag is given.
inline void add_multiscatter_flags(CLI::App& cmd, std::optional<bool>& value,
                                   const std::string& what) {
  auto* on = cmd.add_flag_callback(
      "--multiscatter", [&value] { value = true; }, what);
  auto* off = cmd.add_flag_callback(
      "--no-multiscatter", [&value] { value = false; }, "no multiple-scattering compensation");
  on->excludes(off);
}

void register_brdf_command(CLI::App& app);
void register_scene_command(CLI::App& app);
void register_info_command(CLI::App& app);
void register_bake_command(CLI::App& app);
void register_render_command(CLI::App& app);
void register_merge_command(CLI::App& app);
void register_denoise_command(CLI::App& app);
void register_compare_command(CLI::App& app);
void register_view_command(CLI::App& app);

}  // namespace pbrkit::cli
