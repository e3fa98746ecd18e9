#pragma once
// Where pbrkit finds the data it ships (the default environment): never through a path
// into the source tree, so a build, an install and a relocated install all work.
#include <filesystem>

namespace pbrkit {

/// The directory holding pbrkit's shipped data (`env/city.exr`, ...). Searched in order:
/// 1. the environment variable `PBRKIT_DATA_DIR`, when set;
/// 2. `../share/pbrkit` relative to the executable or shared library that holds this code
///    (a build tree's `bin/` and an install prefix's `bin/` or `lib/` both have it beside);
/// 3. the install prefix's data directory configured at build time (`<prefix>/share/pbrkit`),
///    for programs built elsewhere against an installed static library.
/// Throws pbrkit::Error naming every place tried when none holds `env/city.exr`.
std::filesystem::path data_dir();

}  // namespace pbrkit
