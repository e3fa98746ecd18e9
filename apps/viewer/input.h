#pragma once
// The viewer's input, private to the viewer: the mouse's orbit, pan and zoom (and the split
// view's divider), the keys, and files dropped on the window.
#include "pbrkit/gl/renderer.h"
#include "viewer_state.h"

struct GLFWwindow;
struct ImGuiIO;

namespace pbrkit::viewer {

/// Files dropped on the window: a scene or an environment; a bad file leaves the current
/// one in place and says why in the panel.
void handle_drops(ViewerState& s, gl::Renderer& renderer, float aspect);

/// Camera controls (when the panel does not want the mouse); in the split view a drag
/// that starts on the divider moves the divider.
void handle_mouse(ViewerState& s, const ImGuiIO& io);

/// The keys (when the panel does not want the keyboard): Esc, the view modes 1-4, C the
/// next channel, D the denoiser, Space play / pause the animation, R reload; true when F12 or P
/// asks for a screenshot.
bool handle_keys(ViewerState& s, gl::Renderer& renderer, GLFWwindow* window, const ImGuiIO& io);

}  // namespace pbrkit::viewer
