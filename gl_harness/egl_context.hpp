// Internal to gl_harness: what the two EGL backends share. They differ only in how they get an
// EGLDisplay (surfaceless platform, or one EGLDevice); loading libEGL, creating a GL 3.3 core
// context on the display and making it current without a surface are done here once.
#pragma once

// Keep Xlib (and its macros, e.g. Status, None, Bool) out: no native window types are used.
#ifndef EGL_NO_X11
#define EGL_NO_X11
#endif
#ifndef EGL_EGL_PROTOTYPES
#define EGL_EGL_PROTOTYPES 0  // function pointer types only: libEGL is dlopen()ed, not linked
#endif
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <memory>
#include <string>
#include <string_view>

#include "gl_harness/context.hpp"

namespace glrc::gl {

inline constexpr const char* kEglLibrary = "libEGL.so.1";

// libEGL's entry points, loaded once per process; the library is never unloaded.
struct EglLibrary {
  PFNEGLGETPROCADDRESSPROC GetProcAddress;
  PFNEGLGETERRORPROC GetError;
  PFNEGLQUERYSTRINGPROC QueryString;
  PFNEGLINITIALIZEPROC Initialize;
  PFNEGLTERMINATEPROC Terminate;
  PFNEGLBINDAPIPROC BindAPI;
  PFNEGLCHOOSECONFIGPROC ChooseConfig;
  PFNEGLCREATECONTEXTPROC CreateContext;
  PFNEGLDESTROYCONTEXTPROC DestroyContext;
  PFNEGLMAKECURRENTPROC MakeCurrent;
  PFNEGLGETCURRENTCONTEXTPROC GetCurrentContext;

  // Client extensions (EGL_EXT_client_extensions); "" when the library has none.
  std::string client_extensions;

  EglLibrary();

  // An extension entry point through eglGetProcAddress; throws Unavailable naming `extension`
  // when absent.
  template <typename Fn>
  Fn extension_function(const char* name, std::string_view extension) const {
    return reinterpret_cast<Fn>(extension_address(name, extension));
  }

 private:
  void* extension_address(const char* name, std::string_view extension) const;
};

const EglLibrary& egl_library();

// Whether the space-separated extension list `list` has `name` (whole word).
bool has_extension(std::string_view list, std::string_view name);

// Throws Unavailable "<extension> not supported by libEGL.so.1: <how_to_get>" unless the client
// extensions list it.
void require_client_extension(const EglLibrary& egl, std::string_view extension,
                              std::string_view how_to_get);

// "EGL_BAD_MATCH" etc.
std::string egl_error_name(EGLint error);

// Initializes `display` and creates a current OpenGL 3.3 core context on it without a surface
// (EGL_KHR_surfaceless_context). `platform` names the display in messages and describe().
std::unique_ptr<Context> create_egl_context(const EglLibrary& egl, EGLDisplay display,
                                            std::string platform);

}  // namespace glrc::gl
