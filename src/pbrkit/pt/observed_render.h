#pragma once
// A render whose every ray query a RayObserver sees (pt/geometry.h): what the benchmarks
// that record a render's rays and the tests that count them use. Private to the library's
// build tree, so the public PathTracerSettings carry no test hook.
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/path_tracer.h"

namespace pbrkit {

/// render_path (pt/path_tracer.h) with `observer` (may be null) attached to the scene's
/// geometry for the whole render; the image is the same as without it.
PathTracerResult render_path_observed(const Scene& scene, const Environment* env,
                                      const Camera& camera, const PathTracerSettings& settings,
                                      RayObserver* observer, const ProgressCallback& progress = {});

}  // namespace pbrkit
