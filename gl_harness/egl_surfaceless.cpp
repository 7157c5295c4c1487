// Backend "egl": Mesa's surfaceless EGL platform (EGL_MESA_platform_surfaceless). No window
// system, no device file needed: the natural home of llvmpipe/softpipe without OSMesa, which
// upstream Mesa removed in 25.1.
#include "gl_harness/egl_context.hpp"

namespace glrc::gl {

std::unique_ptr<Context> create_egl_surfaceless_context(const Target&) {
  const EglLibrary& egl = egl_library();
  constexpr const char* kHow = "install Debian's libegl-mesa0 (apt-get install libegl-mesa0)";
  require_client_extension(egl, "EGL_EXT_platform_base", kHow);
  require_client_extension(egl, "EGL_MESA_platform_surfaceless", kHow);
  auto get_platform_display = egl.extension_function<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      "eglGetPlatformDisplayEXT", "EGL_EXT_platform_base");
  EGLDisplay display =
      get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY)
    throw Unavailable(std::string("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA) "
                                  "failed: ") +
                      egl_error_name(egl.GetError()) + "; " + kHow);
  return create_egl_context(egl, display, "EGL surfaceless platform");
}

}  // namespace glrc::gl
