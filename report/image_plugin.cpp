#include "report/image_plugin.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace glrc::report {
namespace {

#if GLRC_IMAGES
struct Loaded {
  const glrc_images_api* api = nullptr;
  std::string error;  // why api is null
};

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

std::vector<std::string> candidates() {
  std::vector<std::string> paths;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path dir = exe.parent_path();
    paths.push_back((dir / GLRC_IMAGES_PLUGIN_FILE).string());
    // An install: bin/glrefcheck and lib/glrefcheck/glrefcheck_images.so.
    paths.push_back((dir.parent_path() / "lib" / "glrefcheck" / GLRC_IMAGES_PLUGIN_FILE).string());
  }
  // The build tree, for the test binaries in build/tests/ and a build run in place.
  paths.push_back(GLRC_IMAGES_PLUGIN_BUILD_PATH);
  return paths;
}

Loaded load() {
  std::vector<std::string> paths;
  const char* chosen = std::getenv("GLRC_IMAGES_PLUGIN");
  const bool overridden = chosen && *chosen;
  if (overridden)
    paths.push_back(chosen);  // the user's choice, and no silent fallback to another
  else
    paths = candidates();
  std::string tried;
  for (const std::string& path : paths) {
    // Never closed, and RTLD_NODELETE besides: OpenImageIO keeps thread pools and caches until
    // exit, and LeakSanitizer needs the library still mapped to name its frames.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!handle) {
      const char* why = dlerror();
      tried += (tried.empty() ? "" : "; ") + one_line(why ? why : path + ": cannot load");
      continue;
    }
    // The first library that loads decides: a stale or foreign one is reported, not skipped
    // for another that might be just as stale.
    using Entry = const glrc_images_api* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, GLRC_IMAGES_ENTRY));
    if (!entry) {
      const char* why = dlerror();
      return {nullptr, "the image plugin " + path +
                           " is not one: " + one_line(why ? why : "no " GLRC_IMAGES_ENTRY)};
    }
    const glrc_images_api* api = entry();
    if (!api || api->abi_version != GLRC_IMAGES_ABI_VERSION)
      return {nullptr,
              "the image plugin " + path + " has ABI version " +
                  (api ? std::to_string(api->abi_version) : std::string("none")) +
                  ", this glrefcheck needs " + std::to_string(GLRC_IMAGES_ABI_VERSION) +
                  " (a stale build: rebuild glrefcheck_images, or set GLRC_IMAGES_PLUGIN)"};
    return {api, ""};
  }
  return {nullptr, std::string("no image plugin could be loaded (") +
                       (overridden ? "GLRC_IMAGES_PLUGIN: " : "tried ") + tried + ")"};
}
#endif

}  // namespace

const glrc_images_api& image_plugin() {
#if GLRC_IMAGES
  // Loaded once, at the first image, and kept: the one piece of global state.
  static const Loaded loaded = load();
  if (!loaded.api) throw std::runtime_error(loaded.error);
  return *loaded.api;
#else
  throw std::runtime_error("glrefcheck was built without OpenImageIO (GLRC_IMAGES=OFF)");
#endif
}

}  // namespace glrc::report
