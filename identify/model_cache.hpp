// The models `glrefcheck identify` found, kept between runs. Identification needs a GL context
// and about half a second, and its answer depends only on the implementation, so run, diff and
// selftest look the implementation up first. One JSON file, $XDG_CACHE_HOME/glrefcheck/
// models.json (~/.cache/glrefcheck/models.json when XDG_CACHE_HOME is unset), keyed by
// GL_RENDERER, GL_VERSION and a SHA-256 of the driver's library files, so a rebuilt or other
// Mesa with the same strings is identified again. A cache file that cannot be read or parsed is
// ignored and replaced on the next save; a folder that cannot be written means no cache. Neither
// is ever an error.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/model.hpp"
#include "gl_harness/gl_harness.hpp"

namespace glrc::identify {

// One implementation's entry in the cache.
struct ModelCacheSlot {
  std::filesystem::path file;                    // empty: no cache
  std::string renderer, version, driver_digest;  // driver_digest empty: library unknown
  // Whether load and save do anything: a file, and a driver whose library files were read.
  bool usable() const { return !file.empty() && !driver_digest.empty(); }
  // The model stored for this key; nullopt when there is none, or the file is unreadable or
  // not what save writes.
  std::optional<Model> load() const;
  // Stores `m` for this key (replacing its old entry), best effort: never throws. Writes a new
  // file and renames it over the old one, so a concurrent run reads one or the other.
  void save(const Model& m) const;
};

// $XDG_CACHE_HOME/glrefcheck/models.json, or $HOME/.cache/glrefcheck/models.json when
// XDG_CACHE_HOME is unset or not an absolute path; empty when neither variable helps.
std::filesystem::path model_cache_file();

// The slot of an implementation whose driver code is `driver_files` (driver_files()), its
// digest remembered_files_digest's with the store beside `file`.
ModelCacheSlot model_cache_slot(const std::string& renderer, const std::string& version,
                                const std::vector<std::string>& driver_files,
                                const std::filesystem::path& file = model_cache_file());

// A SHA-256 (hex) over the contents of `files`, in the order given; "" when the list is empty
// or a file cannot be read.
std::string files_digest(const std::vector<std::string>& files);

// files_digest(files), remembered in `store` (JSON, next to the models: driver_digests.json)
// with every file's identity: device, inode, size, and modification and status-change times in
// nanoseconds. Hashing a driver (libOSMesa is 12 MB, libgallium more) costs every run 15 to 30
// ms; a file changed since has another change time (no user can set it back), so a remembered
// digest is used only where every file's identity is the same. Recorded only for files last
// changed a second or more before `now` (the filesystem's clock is coarse: a change within the
// same tick as the hashing could keep the change time). `store` unreadable or not ours: the
// digest is computed, and the store rewritten when possible; never an error.
std::string remembered_files_digest(
    const std::vector<std::string>& files, const std::filesystem::path& store,
    std::filesystem::file_time_type now = std::filesystem::file_time_type::clock::now());

// The driver's code in this process: gl.library (libOSMesa, libEGL_mesa, ...) and the Mesa
// driver modules the loader mapped (swrast_dri.so, libgallium-*.so, and for zink the Vulkan
// driver libvulkan_*.so), sorted. Empty when gl.library is unknown: such a driver is not cached.
std::vector<std::string> driver_files(const gl::GlInfo& gl);

// A Model as {"subpixel_bits", "planes", "tie_break"} (the command line's names), and back;
// nullopt for anything else.
nlohmann::json model_json(const Model& m);
std::optional<Model> model_from_json(const nlohmann::json& j);

}  // namespace glrc::identify
