#pragma once
// Numbers on the command line must be finite: CLI11 converts "nan", "inf" and "1e999" to
// floats, and its range validators let NaN through (every comparison with NaN is false), so
// `--exposure nan` would reach the library as a NaN. One validator, applied to every
// floating-point option of every subcommand, makes each such value an error naming its flag.
#include <string_view>

#include <CLI/CLI.hpp>

namespace pbrkit::cli {

/// Fails validation for a value that parses as a number but is not finite as a float (NaN,
/// +-inf, beyond +-3.4e38); leaves any other text to the option's own conversion.
CLI::Validator finite_number();

/// Adds finite_number() to every floating-point option (CLI11 type FLOAT, including
/// std::optional and vectors of floats) of `app` and of its subcommands, recursively. Called
/// once every command is registered.
void require_finite_numbers(CLI::App& app);

/// A float spelled by `text` within `flag`'s value (e.g. --background's "blur:<mip>"),
/// finite; an error naming `flag` and the whole value `whole` otherwise.
float parse_finite_float(std::string_view text, std::string_view flag, std::string_view whole);

}  // namespace pbrkit::cli
