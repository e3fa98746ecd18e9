#include "viewer/viewer.h"

#include <epoxy/gl.h>
// GLFW after epoxy (epoxy provides the GL declarations).
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "frame_loop.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/image/output_paths.h"
#include "pbrkit/util/error.h"
#include "viewer_state.h"

namespace pbrkit {

namespace {

// An OpenGL 4.5 core window of the asked size, its context current (GLFW initialised).
GLFWwindow* create_window(const ViewerOptions& options) {
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window =
      glfwCreateWindow(options.width, options.height, "pbrkit view", nullptr, nullptr);
  if (!window)
    fail("pbrkit view: cannot create a {}x{} OpenGL 4.5 core window", options.width,
         options.height);
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.frames > 0 || options.exit_when_done ? 0 : 1);
  return window;
}

void init_imgui(GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's working directory
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 450");
}

void shutdown_imgui() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

}  // namespace

void run_viewer(const ViewerOptions& options) {
  // A bad screenshot name is refused now, not after the frames are rendered.
  if (!options.screenshot.empty()) image_output_paths(options.screenshot, "screenshot");
  if (!glfwInit())
    fail(
        "pbrkit view: cannot open a window (GLFW could not initialise; is there an X display? "
        "For a headless machine use xvfb-run, or 'pbrkit render --renderer gl')");
  struct GlfwGuard {
    ~GlfwGuard() { glfwTerminate(); }
  } glfw_guard;
  GLFWwindow* window = create_window(options);
  init_imgui(window);
  {
    viewer::ViewerState s;
    viewer::init_state(s, options);
    gl::Renderer renderer;
    viewer::load_scene_into(s, renderer);
    viewer::reset_orbit(s, viewer::framebuffer_aspect(window, options));
    viewer::load_environment(s, renderer);
    glfwSetWindowUserPointer(window, &s);
    glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
      auto* state = static_cast<viewer::ViewerState*>(glfwGetWindowUserPointer(w));
      for (int i = 0; i < count; ++i) state->dropped.emplace_back(paths[i]);
    });
    viewer::run_frames(s, renderer, window);
    s.path.stop();
  }  // the renderer's GL objects go before the context
  shutdown_imgui();
  glfwDestroyWindow(window);
}

}  // namespace pbrkit
