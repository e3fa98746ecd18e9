#include "pbrkit/gl/context.h"

#include <map>
#include <mutex>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include "pbrkit/util/error.h"

namespace pbrkit::gl {

namespace {

// eglGetPlatformDisplayEXT returns the same EGLDisplay for the same platform and device
// every time it is called in a process, and eglInitialize / eglTerminate act on that one
// display, not on a per-caller handle: eglInitialize on an initialised display does
// nothing, and one eglTerminate ends every context created on it (one current on some
// thread lives on only until it is released; measured on Mesa: the next eglMakeCurrent of
// any other fails with EGL_BAD_DISPLAY). So all HeadlessContexts share
// their display (gl_tests' shared context and render_headless's own, say), and the first
// one destroyed must not terminate it under the others: the last context using the
// display terminates it. Not terminating at all would also work but would keep the
// driver's state (llvmpipe's threads among it) until exit after the last context is gone;
// EGL_KHR_display_reference would have EGL count, but not every EGL has it. A mutex,
// because contexts may be made and destroyed on different threads.
std::mutex& displays_mutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<EGLDisplay, int>& display_users() {
  static std::map<EGLDisplay, int> users;
  return users;
}

// Initialises `display` for one more user; false if it cannot be initialised.
bool acquire_display(EGLDisplay display) {
  if (display == EGL_NO_DISPLAY) return false;
  const std::lock_guard<std::mutex> lock(displays_mutex());
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) return false;
  ++display_users()[display];
  return true;
}

// One user fewer; the last one terminates the display.
void release_display(EGLDisplay display) {
  const std::lock_guard<std::mutex> lock(displays_mutex());
  auto& users = display_users();
  const auto it = users.find(display);
  if (it == users.end() || --it->second > 0) return;
  users.erase(it);
  eglTerminate(display);
}

// Initialises `display` and creates a 4.5 core context without a config
// (EGL_KHR_no_config_context) and without a surface (EGL_KHR_surfaceless_context), current
// on the calling thread; returns EGL_NO_CONTEXT (and releases the display) on failure.
EGLContext create_core_context(EGLDisplay display) {
  if (!acquire_display(display)) return EGL_NO_CONTEXT;
  if (!eglBindAPI(EGL_OPENGL_API)) {
    release_display(display);
    return EGL_NO_CONTEXT;
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                               4,
                               EGL_CONTEXT_MINOR_VERSION,
                               5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) {
    release_display(display);
    return EGL_NO_CONTEXT;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    release_display(display);
    return EGL_NO_CONTEXT;
  }
  return context;
}

}  // namespace

HeadlessContext::HeadlessContext() {
  // 1. Mesa's surfaceless platform: needs no device node and no display server.
  EGLDisplay display =
      eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLContext context = create_core_context(display);
  if (context != EGL_NO_CONTEXT) {
    platform_ = "surfaceless";
  } else {
    // 2. The device platform: enumerate EGL devices and take the first that gives a 4.5 core
    //    context (a GPU's EGL, or Mesa's software device).
    EGLint count = 0;
    if (eglQueryDevicesEXT(0, nullptr, &count) && count > 0) {
      std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
      eglQueryDevicesEXT(count, devices.data(), &count);
      for (EGLint i = 0; i < count && context == EGL_NO_CONTEXT; ++i) {
        display =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[std::size_t(i)], nullptr);
        context = create_core_context(display);
      }
    }
    if (context == EGL_NO_CONTEXT)
      fail(
          "OpenGL: cannot create a headless OpenGL 4.5 core context (tried EGL's surfaceless "
          "and device platforms; EGL error 0x{:x}). Is Mesa's libegl-mesa0 installed?",
          eglGetError());
    platform_ = "device";
  }
  display_ = display;
  context_ = context;
}

HeadlessContext::~HeadlessContext() {
  auto display = static_cast<EGLDisplay>(display_);
  auto context = static_cast<EGLContext>(context_);
  // Unbind it if it is this thread's current context (another context current here stays
  // current), destroy it, and terminate the display if no other context uses it.
  if (eglGetCurrentContext() == context)
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, context);
  release_display(display);
}

void HeadlessContext::make_current() {
  if (!eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                      static_cast<EGLContext>(context_)))
    fail("OpenGL: cannot make the headless context current (EGL error 0x{:x})", eglGetError());
}

bool is_software_renderer(std::string_view gl_renderer) {
  for (std::string_view name : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
    if (gl_renderer.find(name) != std::string_view::npos) return true;
  return false;
}

int interactive_msaa(std::string_view gl_renderer) {
  return is_software_renderer(gl_renderer) ? 1 : 4;
}

std::string current_renderer() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return renderer ? renderer : "";
}

std::string describe_current_context() {
  const std::string renderer = current_renderer();
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return fmt::format("{} / {}", renderer.empty() ? "?" : renderer, version ? version : "?");
}

}  // namespace pbrkit::gl
