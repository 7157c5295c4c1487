// Internal to gl_harness: the one thing that differs between backends is how a GL context is
// made and how GL entry points are found. Everything after that (gl_functions, renderer) is
// shared. Each backend lives in its own file and implements Context.
#pragma once

#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>

#include "gl_harness/gl_harness.hpp"

namespace glrc::gl {

// A current-able GL 3.3+ core context with no default framebuffer the renderer relies on: all
// rendering goes to an FBO.
class Context {
 public:
  virtual ~Context() = default;  // destroys the context (unbinding it first if current)
  Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Makes this context current on the calling thread; a no-op when it already is.
  virtual void make_current() = 0;
  // The GL entry point `name` for this context, or nullptr.
  virtual void* proc_address(const char* name) const = 0;
  // One line about the platform for messages, e.g. "EGL 1.5 surfaceless (Mesa Project)".
  virtual std::string describe() const = 0;
};

// The backends. Each throws Unavailable, naming what is missing and how to get it. The caller
// has run select_driver(t) first.
std::unique_ptr<Context> create_osmesa_context(const Target& t);
std::unique_ptr<Context> create_egl_surfaceless_context(const Target& t);
std::unique_ptr<Context> create_egl_device_context(const Target& t);

// --- Shared helpers (context.cpp) ---

// dlopen()s the first soname of `sonames` that loads (RTLD_NOW | RTLD_LOCAL, so libOSMesa's own
// gl* symbols never leak into the process) and never closes it: Mesa and LLVM do not survive
// being unloaded. Throws Unavailable(missing_library_message(...)) when none loads.
void* open_library(std::initializer_list<const char*> sonames, std::string_view how_to_get);

// "libOSMesa.so.8 not found (<dlerror>): install Debian's libosmesa6 (apt-get install
// libosmesa6)". `tried` are the sonames tried, first one named as the missing library.
std::string missing_library_message(std::initializer_list<const char*> tried,
                                    std::string_view dl_error, std::string_view how_to_get);

// dlsym() that throws Unavailable naming the symbol and library when it is missing.
void* library_symbol(void* library, const char* library_name, const char* symbol);

// Sets the function pointer `fn` to library_symbol(...), cast to its type: one place for the
// cast every backend's library table needs.
template <class Function>
void load_symbol(Function*& fn, void* library, const char* library_name, const char* symbol) {
  fn = reinterpret_cast<Function*>(library_symbol(library, library_name, symbol));
}

// The path of the first loaded shared object whose file name starts with one of `prefixes`
// (dl_iterate_phdr, so it is the file the loader really mapped), or "".
std::string loaded_library(std::initializer_list<const char*> prefixes);

// Mesa's software rasterizers, llvmpipe and softpipe: what OSMesa runs.
bool is_mesa_software_driver(std::string_view driver);
// Mesa's drivers that run on the CPU, picked through GALLIUM_DRIVER with LIBGL_ALWAYS_SOFTWARE
// on EGL: llvmpipe, softpipe, and zink (GL on Vulkan), which then runs on lavapipe, Mesa's CPU
// Vulkan driver (Debian's mesa-vulkan-drivers).
bool is_mesa_cpu_driver(std::string_view driver);

// Sets GALLIUM_DRIVER (and for EGL, LIBGL_ALWAYS_SOFTWARE) for t.driver before the library
// creates its screen. Mesa reads them once per process, so a second call with another driver
// throws Unavailable instead of silently running the first driver again.
void select_driver(const Target& t);

// Throws Unavailable unless GL_RENDERER names the driver asked for (case-insensitive). `where`
// is the context's describe(), for the message.
void check_driver(const Target& t, std::string_view gl_renderer, std::string_view where);

}  // namespace glrc::gl
