#pragma once
// A headless OpenGL 4.5 core context through EGL with no display: Mesa's surfaceless
// platform (EGL_MESA_platform_surfaceless) first, then the EGL device platform
// (EGL_EXT_platform_device; on a machine with a GPU this picks the GPU's EGL). Rendering
// goes into the renderer's own framebuffer objects; there is no default framebuffer.
// The windowed path (GLFW) lives in viewer.cpp; both drive the same Renderer.
#include <memory>
#include <string>

namespace pbrkit::gl {

class HeadlessContext {
 public:
  /// Creates the context and makes it current on the calling thread. Throws pbrkit::Error
  /// explaining what failed (no EGL platform, no 4.5 core context).
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  void make_current();
  /// "surfaceless" or "device".
  const std::string& platform() const { return platform_; }

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string platform_;
};

/// GL_RENDERER and GL_VERSION of the current context, for logs and benchmark reports.
std::string describe_current_context();

}  // namespace pbrkit::gl
