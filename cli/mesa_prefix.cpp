#include "cli/mesa_prefix.hpp"

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli/session.hpp"

namespace glrc::cli {

namespace {

#if defined(__x86_64__)
constexpr const char* kMultiarch = "x86_64-linux-gnu";
#elif defined(__aarch64__)
constexpr const char* kMultiarch = "aarch64-linux-gnu";
#else
constexpr const char* kMultiarch = "";
#endif

}  // namespace

MesaPrefix find_mesa_prefix(const std::string& prefix, const std::string& backend) {
  namespace fs = std::filesystem;
  std::error_code ec;
  MesaPrefix m;
  m.root = fs::absolute(prefix, ec);
  if (!fs::is_directory(m.root, ec))
    throw InputError("--mesa " + prefix + ": expected a Mesa install tree (a folder), got " +
                     (fs::exists(m.root, ec) ? "a file" : "no such folder"));
  m.given = m.root.lexically_normal();
  m.root = fs::canonical(m.root, ec);
  std::vector<fs::path> looked;
  for (const char* base : {"usr/", "", "usr/local/"})
    for (const std::string& lib :
         {std::string("lib/") + kMultiarch, std::string("lib64"), std::string("lib")})
      looked.push_back(m.root / (base + lib));
  for (const fs::path& dir : looked) {
    m.has_egl = fs::exists(dir / "libEGL_mesa.so.0", ec);
    m.has_osmesa = fs::exists(dir / "libOSMesa.so.8", ec);
    if (m.has_egl || m.has_osmesa) {
      m.libdir = dir;
      break;
    }
  }
  if (m.libdir.empty()) {
    std::string where;
    for (size_t k = 0; k < 3; ++k)
      where += (k ? ", " : "") + fs::relative(looked[k], m.root).string();
    throw InputError("--mesa " + prefix +
                     ": expected libEGL_mesa.so.0 or libOSMesa.so.8 under it (looked in " + where +
                     ", ...); scripts/mesa-fetch.sh VERSION makes such a tree");
  }
  if (backend == "osmesa" && !m.has_osmesa)
    throw InputError("--mesa " + prefix + ": no libOSMesa.so.8 in " + m.libdir.string() +
                     " (Mesa 25.1 removed OSMesa): use --backend egl");
  if (backend != "osmesa" && !m.has_egl)
    throw InputError("--mesa " + prefix + ": no libEGL_mesa.so.0 in " + m.libdir.string() +
                     ": use --backend osmesa, or build Mesa with EGL");
  return m;
}

std::vector<std::pair<std::string, std::string>> mesa_environment(
    const MesaPrefix& m, const std::filesystem::path& scratch) {
  std::vector<std::pair<std::string, std::string>> env;
  const char* old = std::getenv("LD_LIBRARY_PATH");
  // Appended, not `":" + string`: GCC 12's Release inlining reports a false -Wrestrict there.
  std::string library_path = m.libdir.string();
  if (old && *old) library_path.append(":").append(old);
  env.emplace_back("LD_LIBRARY_PATH", library_path);
  if (m.has_egl) {
    const auto json = scratch / "mesa_egl_vendor.json";
    std::ofstream out(json);
    const nlohmann::json vendor = {
        {"file_format_version", "1.0.0"},
        {"ICD", {{"library_path", (m.libdir / "libEGL_mesa.so.0").string()}}}};
    out << vendor.dump(2) << '\n';
    if (!out) throw InputError("--mesa: cannot write " + json.string());
    env.emplace_back("__EGL_VENDOR_LIBRARY_FILENAMES", std::filesystem::absolute(json).string());
  }
  std::error_code ec;
  if (std::filesystem::is_directory(m.libdir / "dri", ec))
    env.emplace_back("LIBGL_DRIVERS_PATH", (m.libdir / "dri").string());
  return env;
}

bool from_prefix(const MesaPrefix& m, const std::string& loaded_library) {
  if (loaded_library.empty()) return false;
  // The path as the loader opened it: a prefix may hold links to libraries elsewhere.
  const auto lib = std::filesystem::absolute(loaded_library).lexically_normal();
  for (const auto& root : {m.root, m.given}) {
    const auto rel = lib.lexically_relative(root);
    if (!rel.empty() && *rel.begin() != "..") return true;
  }
  return false;
}

}  // namespace glrc::cli
