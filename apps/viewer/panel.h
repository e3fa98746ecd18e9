#pragma once
// The viewer's panel (Dear ImGui), private to the viewer: the view mode and the truth
// views' progress and error, the environment, display, model and renderer settings, the
// lights, the variants and animations, and the material overrides.
#include "pbrkit/gl/renderer.h"
#include "viewer_state.h"

namespace pbrkit::viewer {

/// The panel; returns true when something the path-traced image depends on changed.
bool draw_panel(ViewerState& s, gl::Renderer& renderer, double cpu_ms, double gpu_ms);

}  // namespace pbrkit::viewer
