// The EGL code both EGL backends share: libEGL, and a surfaceless GL 3.3 core context.
#include "gl_harness/egl_context.hpp"

#include <dlfcn.h>
#include <link.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <string>

namespace glrc::gl {

EglLibrary::EglLibrary() {
  // glvnd's libEGL.so.1 dispatches to vendor libraries (Mesa's libEGL_mesa.so.0, NVIDIA's
  // libEGL_nvidia.so.0) listed in its egl_vendor.d JSON files.
  void* h = open_library({kEglLibrary},
                         "install Debian's libegl1 and libegl-mesa0 (apt-get install libegl1 "
                         "libegl-mesa0)");
  load_symbol(GetProcAddress, h, kEglLibrary, "eglGetProcAddress");
  load_symbol(GetError, h, kEglLibrary, "eglGetError");
  load_symbol(QueryString, h, kEglLibrary, "eglQueryString");
  load_symbol(Initialize, h, kEglLibrary, "eglInitialize");
  load_symbol(Terminate, h, kEglLibrary, "eglTerminate");
  load_symbol(BindAPI, h, kEglLibrary, "eglBindAPI");
  load_symbol(ChooseConfig, h, kEglLibrary, "eglChooseConfig");
  load_symbol(CreateContext, h, kEglLibrary, "eglCreateContext");
  load_symbol(DestroyContext, h, kEglLibrary, "eglDestroyContext");
  load_symbol(MakeCurrent, h, kEglLibrary, "eglMakeCurrent");
  load_symbol(GetCurrentContext, h, kEglLibrary, "eglGetCurrentContext");
  // NULL (with EGL_BAD_DISPLAY) when the library has no client extensions at all.
  if (const char* e = QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS)) client_extensions = e;
  GetError();
}

void* EglLibrary::extension_address(const char* name, std::string_view extension) const {
  if (void* p = reinterpret_cast<void*>(GetProcAddress(name))) return p;
  throw Unavailable(std::string(kEglLibrary) + " has no " + name + " although it lists " +
                    std::string(extension) + "; install a current libegl1/libegl-mesa0");
}

const EglLibrary& egl_library() {
  static const EglLibrary library;  // a throwing first attempt is retried on the next call
  return library;
}

bool has_extension(std::string_view list, std::string_view name) {
  for (size_t pos = 0; (pos = list.find(name, pos)) != std::string_view::npos; pos += name.size()) {
    bool starts = pos == 0 || list[pos - 1] == ' ';
    size_t end = pos + name.size();
    bool ends = end == list.size() || list[end] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

void require_client_extension(const EglLibrary& egl, std::string_view extension,
                              std::string_view how_to_get) {
  if (has_extension(egl.client_extensions, extension)) return;
  throw Unavailable(std::string(extension) + " not supported by " + kEglLibrary + ": " +
                    std::string(how_to_get));
}

std::string egl_error_name(EGLint error) {
  switch (error) {
#define GLRC_EGL_ERROR(e) \
  case e:                 \
    return #e;
    GLRC_EGL_ERROR(EGL_SUCCESS)
    GLRC_EGL_ERROR(EGL_NOT_INITIALIZED)
    GLRC_EGL_ERROR(EGL_BAD_ACCESS)
    GLRC_EGL_ERROR(EGL_BAD_ALLOC)
    GLRC_EGL_ERROR(EGL_BAD_ATTRIBUTE)
    GLRC_EGL_ERROR(EGL_BAD_CONFIG)
    GLRC_EGL_ERROR(EGL_BAD_CONTEXT)
    GLRC_EGL_ERROR(EGL_BAD_CURRENT_SURFACE)
    GLRC_EGL_ERROR(EGL_BAD_DISPLAY)
    GLRC_EGL_ERROR(EGL_BAD_MATCH)
    GLRC_EGL_ERROR(EGL_BAD_NATIVE_PIXMAP)
    GLRC_EGL_ERROR(EGL_BAD_NATIVE_WINDOW)
    GLRC_EGL_ERROR(EGL_BAD_PARAMETER)
    GLRC_EGL_ERROR(EGL_BAD_SURFACE)
    GLRC_EGL_ERROR(EGL_CONTEXT_LOST)
#undef GLRC_EGL_ERROR
  }
  return "EGL error 0x" + [error] {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%04X", unsigned(error));
    return std::string(buf);
  }();
}

namespace {

// eglTerminate is per display, not per context, and EGL hands out the same EGLDisplay for the
// same platform and native display: two renderers on one display must not terminate it under
// each other. Counts live contexts per display.
std::mutex display_mutex;
std::map<EGLDisplay, int> display_users;

#if defined(__SANITIZE_ADDRESS__)
#define GLRC_LEAK_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GLRC_LEAK_SANITIZER 1
#endif
#endif

// Under AddressSanitizer only (scripts/sanitize.sh): every library loaded now (Mesa's DRI driver,
// the Vulkan drivers under zink) stays loaded until exit. Mesa's EGL unloads its driver at
// eglTerminate, and LeakSanitizer's report at exit then names the driver's leftover allocations
// "<unknown module>", which no suppression in tests/sanitizers/lsan.supp can match; kept loaded,
// they carry their library's name and are suppressed like the rest of Mesa's.
void keep_libraries_loaded_for_leak_sanitizer() {
#ifdef GLRC_LEAK_SANITIZER
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void*) {
        // RTLD_NOLOAD: only what is loaded already; RTLD_NODELETE sticks to it, so no later
        // dlclose unloads it. The reference taken here is never given back, on purpose.
        if (info->dlpi_name && info->dlpi_name[0])
          dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        return 0;
      },
      nullptr);
#endif
}

// Runs `f` with stderr going to a temporary file. If `f` succeeds, what it wrote is passed on to
// stderr as it was; if not, it stays out of stderr and its first line comes back in `said`, for
// the one-line error (Mesa's libEGL prints "libEGL warning: egl: failed to create dri2 screen"
// before eglInitialize fails, which made a second line ahead of glrefcheck's own).
template <typename F>
bool with_stderr_kept(std::string& said, F&& f) {
  std::fflush(stderr);
  FILE* tmp = std::tmpfile();
  const int saved = tmp ? dup(STDERR_FILENO) : -1;
  if (saved < 0 || dup2(fileno(tmp), STDERR_FILENO) < 0) {
    if (saved >= 0) close(saved);
    if (tmp) std::fclose(tmp);
    return f();  // no temporary file: Mesa's lines go where they always went
  }
  const bool ok = f();
  std::fflush(stderr);
  dup2(saved, STDERR_FILENO);
  close(saved);
  std::string text;
  std::rewind(tmp);
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, tmp)) > 0 && text.size() < (1u << 20);)
    text.append(buf, n);
  std::fclose(tmp);
  if (ok) {
    if (!text.empty()) std::fwrite(text.data(), 1, text.size(), stderr);
    return ok;
  }
  std::string line = text.substr(0, text.find('\n'));
  if (line.rfind("libEGL warning: ", 0) == 0) line = line.substr(16);
  for (char& c : line)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  said = line.size() > 160 ? line.substr(0, 160) + "..." : line;
  return ok;
}

class EglContext final : public Context {
 public:
  EglContext(const EglLibrary& egl, EGLDisplay display, std::string platform)
      : egl_(egl), display_(display), platform_(std::move(platform)) {
    EGLint major = 0, minor = 0;
    std::string said;
    const bool initialized = with_stderr_kept(
        said, [&] { return egl_.Initialize(display_, &major, &minor) == EGL_TRUE; });
    if (!initialized) {
      const std::string error = egl_error_name(egl_.GetError());
      // Mesa starts the driver GALLIUM_DRIVER names (select_driver sets it from --driver) in
      // eglInitialize: a driver this Mesa lacks is the usual cause, so name it.
      const char* driver = std::getenv("GALLIUM_DRIVER");
      if (driver && *driver)
        throw Unavailable("eglInitialize failed on " + platform_ + ": driver \"" +
                          std::string(driver) + "\" (GALLIUM_DRIVER) could not start (" + error +
                          (said.empty() ? "" : "; Mesa said \"" + said + "\"") +
                          "); is it a gallium driver of this Mesa? Mesa's CPU drivers are "
                          "llvmpipe, softpipe and zink");
      throw Unavailable("eglInitialize failed on " + platform_ +
                        " with the platform's default driver: " + error);
    }
    {
      std::lock_guard lock(display_mutex);
      ++display_users[display_];
    }
    try {
      create(major, minor);
    } catch (...) {
      release_display();
      throw;
    }
    keep_libraries_loaded_for_leak_sanitizer();
  }

  ~EglContext() override {
    egl_.BindAPI(EGL_OPENGL_API);
    if (egl_.GetCurrentContext() == context_)
      egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    egl_.DestroyContext(display_, context_);
    release_display();
  }

  void make_current() override {
    // The bound API is per thread and eglGetCurrentContext answers for it.
    egl_.BindAPI(EGL_OPENGL_API);
    if (egl_.GetCurrentContext() == context_) return;
    // No surface at all (EGL_KHR_surfaceless_context): everything renders into an FBO.
    if (!egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw Unavailable("eglMakeCurrent without a surface failed on " + platform_ + ": " +
                        egl_error_name(egl_.GetError()));
  }

  void* proc_address(const char* name) const override {
    // Core GL functions too: EGL 1.5 / EGL_KHR_get_all_proc_addresses, which glvnd provides.
    return reinterpret_cast<void*>(egl_.GetProcAddress(name));
  }

  std::string describe() const override { return platform_ + " (EGL " + version_ + ")"; }

 private:
  void create(EGLint major, EGLint minor) {
    const char* vendor = egl_.QueryString(display_, EGL_VENDOR);
    version_ = std::to_string(major) + "." + std::to_string(minor) +
               (vendor ? std::string(", ") + vendor : std::string());
    const char* ext = egl_.QueryString(display_, EGL_EXTENSIONS);
    std::string_view extensions = ext ? ext : "";
    auto require = [&](std::string_view name, std::string_view why) {
      if (!has_extension(extensions, name))
        throw Unavailable(std::string(name) + " not supported by the EGL display of " + platform_ +
                          " (EGL " + version_ + "), needed " + std::string(why) +
                          "; install a current Mesa (libegl-mesa0) or GPU driver");
    };
    require("EGL_KHR_surfaceless_context", "to make a context current without a surface");
    // The core-profile attributes are core EGL from 1.5 on.
    if (major == 1 && minor < 5)
      require("EGL_KHR_create_context", "for an OpenGL 3.3 core profile context");

    if (!egl_.BindAPI(EGL_OPENGL_API))
      throw Unavailable("the EGL display of " + platform_ +
                        " has no desktop OpenGL (eglBindAPI(EGL_OPENGL_API): " +
                        egl_error_name(egl_.GetError()) + ")");

    // No surface is ever created, so no config is needed where the display allows that.
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
      const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                       EGL_DONT_CARE, EGL_NONE};
      EGLint count = 0;
      if (!egl_.ChooseConfig(display_, config_attribs, &config, 1, &count) || count < 1)
        throw Unavailable("no EGLConfig with EGL_OPENGL_BIT on " + platform_ + ": " +
                          egl_error_name(egl_.GetError()));
    }

    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      3,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    context_ = egl_.CreateContext(display_, config, EGL_NO_CONTEXT, context_attribs);
    if (context_ == EGL_NO_CONTEXT)
      throw Unavailable("eglCreateContext refused an OpenGL 3.3 core context on " + platform_ +
                        ": " + egl_error_name(egl_.GetError()));
    try {
      make_current();
    } catch (...) {
      egl_.DestroyContext(display_, context_);
      throw;
    }
  }

  void release_display() {
    std::lock_guard lock(display_mutex);
    if (--display_users[display_] == 0) {
      display_users.erase(display_);
      egl_.Terminate(display_);
    }
  }

  const EglLibrary& egl_;
  EGLDisplay display_;
  std::string platform_, version_;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<Context> create_egl_context(const EglLibrary& egl, EGLDisplay display,
                                            std::string platform) {
  return std::make_unique<EglContext>(egl, display, std::move(platform));
}

}  // namespace glrc::gl
