#pragma once
// The viewer's frame loop, private to the viewer: each frame's input, panel, path tracer
// progress, raster frame, truth views and screenshot, until the window closes or
// automation is done.
#include "pbrkit/gl/renderer.h"
#include "viewer/viewer.h"
#include "viewer_state.h"

struct GLFWwindow;

namespace pbrkit::viewer {

/// The window's framebuffer aspect, width / height: what the frames are rendered at, which
/// need not be the size asked for (a window manager may place the window at another size).
/// The size asked for while the window has no area (minimised).
float framebuffer_aspect(GLFWwindow* window, const ViewerOptions& options);

/// The window's frames until it closes (or automation is done).
void run_frames(ViewerState& s, gl::Renderer& renderer, GLFWwindow* window);

}  // namespace pbrkit::viewer
