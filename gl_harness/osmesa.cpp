// Backend "osmesa": Mesa's off-screen API, everything through dlopen/dlsym. libOSMesa exports
// its own gl* symbols, so it is never linked into the binary (it would clash with glvnd's
// libGL/libOpenGL) and is opened RTLD_LOCAL.
#include <GL/osmesa.h>

#include <array>

#include "gl_harness/context.hpp"

namespace glrc::gl {
namespace {

constexpr const char* kLibrary = "libOSMesa.so.8";

// OSMesa's entry points, looked up once per process; the library is never unloaded.
struct OsmesaLibrary {
  decltype(&OSMesaCreateContextAttribs) CreateContextAttribs;
  decltype(&OSMesaDestroyContext) DestroyContext;
  decltype(&OSMesaMakeCurrent) MakeCurrent;
  decltype(&OSMesaGetCurrentContext) GetCurrentContext;
  decltype(&OSMesaGetProcAddress) GetProcAddress;

  OsmesaLibrary() {
    // .so.6 is the soname older Debian/Ubuntu releases shipped.
    void* h = open_library({kLibrary, "libOSMesa.so.6"},
                           "install Debian's libosmesa6 (apt-get install libosmesa6), or use "
                           "the egl backend (Mesa removed OSMesa in 25.1)");
    load_symbol(CreateContextAttribs, h, kLibrary, "OSMesaCreateContextAttribs");
    load_symbol(DestroyContext, h, kLibrary, "OSMesaDestroyContext");
    load_symbol(MakeCurrent, h, kLibrary, "OSMesaMakeCurrent");
    load_symbol(GetCurrentContext, h, kLibrary, "OSMesaGetCurrentContext");
    load_symbol(GetProcAddress, h, kLibrary, "OSMesaGetProcAddress");
  }
};

const OsmesaLibrary& osmesa_library() {
  static const OsmesaLibrary library;  // a throwing first attempt is retried on the next call
  return library;
}

class OsmesaContext final : public Context {
 public:
  explicit OsmesaContext(const OsmesaLibrary& lib) : lib_(lib) {
    // GL 3.3 core: what the renderer needs, and the most softpipe offers (it refuses 4.x).
    // No depth/stencil in OSMesa's own buffer: rendering goes to an FBO.
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_STENCIL_BITS,
                           0,
                           OSMESA_ACCUM_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           3,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           3,
                           0};
    context_ = lib_.CreateContextAttribs(attribs, nullptr);
    if (!context_)
      throw Unavailable(std::string(kLibrary) +
                        ": OSMesaCreateContextAttribs refused an OpenGL 3.3 core context; the "
                        "driver (GALLIUM_DRIVER) may be missing from this Mesa build");
    try {
      make_current();
    } catch (...) {
      lib_.DestroyContext(context_);
      throw;
    }
  }

  ~OsmesaContext() override {
    if (lib_.GetCurrentContext() == context_) lib_.MakeCurrent(nullptr, nullptr, 0, 0, 0);
    lib_.DestroyContext(context_);
  }

  void make_current() override {
    if (lib_.GetCurrentContext() == context_) return;
    // OSMesa needs a colour buffer to make a context current; 1x1 is enough since nothing is
    // ever drawn to it.
    if (!lib_.MakeCurrent(context_, pixel_.data(), GL_UNSIGNED_BYTE, 1, 1))
      throw Unavailable(std::string(kLibrary) + ": OSMesaMakeCurrent failed");
  }

  void* proc_address(const char* name) const override {
    return reinterpret_cast<void*>(lib_.GetProcAddress(name));
  }

  std::string describe() const override { return std::string("OSMesa (") + kLibrary + ")"; }

 private:
  const OsmesaLibrary& lib_;
  OSMesaContext context_ = nullptr;
  alignas(4) std::array<unsigned char, 4> pixel_{};  // the 1x1 RGBA8 buffer OSMesa binds
};

}  // namespace

std::unique_ptr<Context> create_osmesa_context(const Target& t) {
  // OSMesa renders with llvmpipe and softpipe only; asked for any other, Mesa 22.3 crashes
  // inside OSMesaCreateContextAttribs instead of failing. zink too: libOSMesa has it built in,
  // but its software winsys gives zink no screen and OSMesaCreateContextAttribs segfaults
  // (Mesa 22.3.6, with and without LIBGL_ALWAYS_SOFTWARE).
  if (!t.driver.empty() && !is_mesa_software_driver(t.driver))
    throw Unavailable(
        "OSMesa runs Mesa's software drivers only: expected --driver llvmpipe or "
        "softpipe, got \"" +
        t.driver + "\" (use --backend egl" + (t.driver == "zink" ? "" : "-device for a GPU") + ")");
  return std::make_unique<OsmesaContext>(osmesa_library());
}

}  // namespace glrc::gl
