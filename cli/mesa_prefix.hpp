// --mesa PREFIX: running GL from a Mesa install tree instead of the system's, for the GL
// processes only. The dynamic loader reads LD_LIBRARY_PATH once, at process start, so the
// environment is built here and handed to a child process (a worker, or this program started
// again); this process never loads GL from the prefix itself.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace glrc::cli {

struct MesaPrefix {
  std::filesystem::path root;    // with links resolved
  std::filesystem::path given;   // as given, made absolute
  std::filesystem::path libdir;  // where libEGL_mesa.so.0 and/or libOSMesa.so.8 are
  bool has_egl = false, has_osmesa = false;
};

// Finds the library folder of a Mesa tree: a Debian package unpacked with dpkg -x
// (usr/lib/<multiarch>), or a `meson install` prefix (lib/<multiarch>, lib64, lib). Throws
// InputError naming the folders looked in when none holds Mesa's libraries, and when the
// backend's library is missing (Mesa 25.1 removed OSMesa: use --backend egl).
MesaPrefix find_mesa_prefix(const std::string& prefix, const std::string& backend);

// The variables to set in a GL child process: LD_LIBRARY_PATH (the prefix first), for EGL
// __EGL_VENDOR_LIBRARY_FILENAMES naming a glvnd vendor file written into `scratch` (glvnd drops
// a vendor whose library it cannot load, silently: hence the absolute path in it), and
// LIBGL_DRIVERS_PATH when the prefix has a dri/ folder (a Mesa built for /usr would otherwise
// load the system's DRI drivers).
std::vector<std::pair<std::string, std::string>> mesa_environment(
    const MesaPrefix& m, const std::filesystem::path& scratch);

// Whether the library GL came from lies in the prefix.
bool from_prefix(const MesaPrefix& m, const std::string& loaded_library);

}  // namespace glrc::cli
