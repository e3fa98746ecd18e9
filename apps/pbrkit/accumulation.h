#pragma once
// Accumulation EXRs (pt/film.h) as the CLI reads them: for --resume and `pbrkit merge`.
#include <string>

#include "pbrkit/pt/film.h"

namespace pbrkit::cli {

/// read_film, with a hint on how such a file is made when `path` is not one.
Film read_accumulation(const std::string& path);

}  // namespace pbrkit::cli
