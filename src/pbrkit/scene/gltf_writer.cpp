#include "pbrkit/scene/load.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

void write_glb(const Scene& /*scene*/, const std::filesystem::path& path) {
  fail("{}: writing .glb is not implemented yet", path.string());
}

}  // namespace pbrkit
