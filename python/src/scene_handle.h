#pragma once
// The Python Scene: a shared, immutable pbrkit::Scene, so that renders on other threads
// can hold it while Python drops its reference.
#include <memory>

#include "pbrkit/scene/scene.h"

namespace pbrkit::python {

struct SceneHandle {
  std::shared_ptr<const Scene> scene;
};

}  // namespace pbrkit::python
