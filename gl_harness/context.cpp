// Helpers every backend shares: loading libraries, naming what is missing, choosing Mesa's
// driver through the environment.
#include "gl_harness/context.hpp"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <mutex>
#include <optional>

namespace glrc::gl {

const char* to_string(Backend b) {
  return name_of(b).data();
}

std::optional<Backend> backend_from_string(std::string_view s) {
  return from_name<Backend>(s);
}

std::string missing_library_message(std::initializer_list<const char*> tried,
                                    std::string_view dl_error, std::string_view how_to_get) {
  std::string m;
  const char* const* name = tried.begin();
  m += tried.size() ? *name : "(no library)";
  m += " not found";
  if (tried.size() > 1) {
    m += " (nor";
    for (++name; name != tried.end(); ++name)
      m += std::string(" ") + *name;
    m += ")";
  }
  m += ": ";
  m += how_to_get;
  if (!dl_error.empty()) {
    // dlerror() is what tells "absent" from "present but a dependency is missing" apart.
    m += " [dlerror: ";
    m += dl_error;
    m += "]";
  }
  // what() must stay one line.
  std::replace(m.begin(), m.end(), '\n', ' ');
  return m;
}

void* open_library(std::initializer_list<const char*> sonames, std::string_view how_to_get) {
  std::string first_error;
  for (const char* soname : sonames) {
    if (void* handle = dlopen(soname, RTLD_NOW | RTLD_LOCAL)) return handle;
    const char* e = dlerror();
    if (first_error.empty() && e) first_error = e;
  }
  throw Unavailable(missing_library_message(sonames, first_error, how_to_get));
}

void* library_symbol(void* library, const char* library_name, const char* symbol) {
  dlerror();
  void* p = dlsym(library, symbol);
  if (!p)
    throw Unavailable(std::string(library_name) + " has no " + symbol +
                      ": it is too old or not the library expected; install a current Mesa");
  return p;
}

std::string loaded_library(std::initializer_list<const char*> prefixes) {
  struct Search {
    std::initializer_list<const char*> prefixes;
    std::string found;
  } search{prefixes, {}};
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* data) {
        auto& s = *static_cast<Search*>(data);
        const std::string_view path = info->dlpi_name ? info->dlpi_name : "";
        const std::string_view base = path.substr(path.rfind('/') + 1);
        for (const char* p : s.prefixes)
          if (base.starts_with(p)) {
            s.found = std::string(path);
            return 1;
          }
        return 0;
      },
      &search);
  return search.found;
}

bool is_mesa_software_driver(std::string_view driver) {
  return driver == "llvmpipe" || driver == "softpipe";
}

bool is_mesa_cpu_driver(std::string_view driver) {
  return is_mesa_software_driver(driver) || driver == "zink";
}

void select_driver(const Target& t) {
  // The driver this process committed to. Mesa creates its screen (and reads GALLIUM_DRIVER)
  // once per process and loader, so a later request for another driver would quietly get the
  // first one.
  static std::mutex mutex;
  static std::optional<std::string> chosen;
  std::lock_guard lock(mutex);
  if (chosen && *chosen != t.driver)
    throw Unavailable("this process already created a GL renderer with driver '" + *chosen +
                      "'; Mesa picks its driver once per process, so driver '" + t.driver +
                      "' needs a new process (run glrefcheck once per driver)");
  chosen = t.driver;
  if (t.driver.empty()) return;  // whatever the platform gives, e.g. a GPU's own driver
  setenv("GALLIUM_DRIVER", t.driver.c_str(), 1);
  // Without it Mesa's EGL would try hardware DRI drivers first and only fall back to swrast
  // (the one that honours GALLIUM_DRIVER) when they fail. zink needs it too: with it zink
  // picks a CPU Vulkan device (lavapipe), without it eglInitialize fails on a machine without a
  // GPU (Mesa 22.3.6). OSMesa is software only anyway.
  if (t.backend != Backend::osmesa && is_mesa_cpu_driver(t.driver))
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
}

static std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

void check_driver(const Target& t, std::string_view gl_renderer, std::string_view where) {
  if (t.driver.empty()) return;
  const std::string renderer = lower(gl_renderer), driver = lower(t.driver);
  // zink names the Vulkan driver under it ("zink (llvmpipe (LLVM 15.0.6, 256 bits))"): that
  // is not the GL driver asked for.
  const bool zink = renderer.starts_with("zink") && driver != "zink";
  if (!zink && renderer.find(driver) != std::string::npos) return;
  throw Unavailable("asked for driver " + t.driver + ", but GL_RENDERER is '" +
                    std::string(gl_renderer) + "' on " + std::string(where) +
                    "; this Mesa may lack that gallium driver, GALLIUM_DRIVER was read before "
                    "glrefcheck set it, or (egl-device) another device index is needed");
}

}  // namespace glrc::gl
