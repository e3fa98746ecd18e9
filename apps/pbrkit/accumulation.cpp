#include "accumulation.h"

#include "pbrkit/util/error.h"

namespace pbrkit::cli {

Film read_accumulation(const std::string& path) {
  try {
    return read_film(path);
  } catch (const Error& e) {
    // The library names the problem; the command line says which commands write the file.
    throw Error(std::string(e.what()) +
                "; accumulation files are written by 'pbrkit render --sample-range A:B' and "
                "'--checkpoint FILE'");
  }
}

}  // namespace pbrkit::cli
