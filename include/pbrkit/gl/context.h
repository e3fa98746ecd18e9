#pragma once
// A headless OpenGL 4.5 core context through EGL with no display: Mesa's surfaceless
// platform (EGL_MESA_platform_surfaceless) first, then the EGL device platform
// (EGL_EXT_platform_device; on a machine with a GPU this picks the GPU's EGL). Rendering
// goes into the renderer's own framebuffer objects; there is no default framebuffer.
// The windowed path (GLFW) is the viewer (apps/viewer/viewer.cpp, a library of its own);
// both drive the same Renderer.
#include <memory>
#include <string>
#include <string_view>

namespace pbrkit::gl {

class HeadlessContext {
 public:
  /// Creates the context and makes it current on the calling thread. Throws pbrkit::Error
  /// explaining what failed (no EGL platform, no 4.5 core context).
  HeadlessContext();
  /// Destroys the context (unbinding it first if it is current on the calling thread). The
  /// EGL display, which all contexts of a process share, is terminated only with the last
  /// context using it, so other HeadlessContexts stay usable.
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  /// Makes the context current on the calling thread; pbrkit::Error if EGL refuses.
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

/// Whether a GL_RENDERER string names a software rasteriser (Mesa's llvmpipe, softpipe or
/// swrast, Google's SwiftShader), where every MSAA sample is paid for in CPU time.
bool is_software_renderer(std::string_view gl_renderer);
/// The MSAA samples an interactive view uses unless told otherwise: 4 on a GPU, 1 on a
/// software rasteriser (there 4x MSAA makes the frame about 2.5x slower; BENCHMARKS.md).
int interactive_msaa(std::string_view gl_renderer);
/// GL_RENDERER of the current context ("" when none is current).
std::string current_renderer();

}  // namespace pbrkit::gl
