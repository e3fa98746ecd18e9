#include "pbrkit/gl/context.h"

#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include "pbrkit/util/error.h"

namespace pbrkit::gl {

namespace {

// Initialises `display` and creates a 4.5 core context without a config
// (EGL_KHR_no_config_context) and without a surface (EGL_KHR_surfaceless_context);
// returns EGL_NO_CONTEXT (and terminates the display) on failure.
EGLContext create_core_context(EGLDisplay display) {
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) return EGL_NO_CONTEXT;
  if (!eglBindAPI(EGL_OPENGL_API)) {
    eglTerminate(display);
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
    eglTerminate(display);
    return EGL_NO_CONTEXT;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    eglTerminate(display);
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
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, static_cast<EGLContext>(context_));
  eglTerminate(display);
}

void HeadlessContext::make_current() {
  eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                 static_cast<EGLContext>(context_));
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
