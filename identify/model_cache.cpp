#include "identify/model_cache.hpp"

#include <fcntl.h>
#include <link.h>
#include <openssl/evp.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>

namespace glrc::identify {

namespace {

using nlohmann::json;

// Entries kept: enough for every driver and Mesa version a developer switches between.
constexpr size_t kMaxEntries = 32;
constexpr int kFormat = 1;

std::string hex(const unsigned char* md, unsigned len) {
  static const char* kHex = "0123456789abcdef";
  std::string out;
  for (unsigned i = 0; i < len; ++i)
    out += kHex[md[i] >> 4], out += kHex[md[i] & 15];
  return out;
}

// Whether `file` is one to read: opening a FIFO put in the cache's place would wait for a
// writer for good (a run that neither SIGINT nor SIGTERM could stop), a device is no cache.
bool readable_file(const std::filesystem::path& file) {
  std::error_code ec;
  return std::filesystem::is_regular_file(file, ec);
}

// The cache's entries, or none when the file is missing, unreadable or not ours.
json read_entries(const std::filesystem::path& file) {
  if (!readable_file(file)) return json::array();
  std::ifstream in(file);
  if (!in) return json::array();
  const json j = json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || j.value("format", 0) != kFormat || !j.contains("models") ||
      !j["models"].is_array())
    return json::array();
  return j["models"];
}

// Writes `j` to a new file and renames it over `file`, so that a concurrent run reads the old
// file or the new one, never half of one; best effort: a folder that cannot be made or written
// leaves `file` as it was.
void write_whole(const std::filesystem::path& file, const json& j) {
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  if (ec) return;
  const std::filesystem::path tmp =
      file.string() + ".tmp." + std::to_string(static_cast<long>(getpid()));
  {
    std::ofstream out(tmp);
    out << j.dump(2) << "\n";
    if (!out) {
      out.close();
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::filesystem::rename(tmp, file, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

bool same_key(const json& entry, const ModelCacheSlot& s) {
  const auto text = [&](const char* key) {
    return entry.is_object() && entry.contains(key) && entry[key].is_string()
               ? entry[key].get<std::string>()
               : std::string("\x01");  // matches no key
  };
  return text("gl_renderer") == s.renderer && text("gl_version") == s.version &&
         text("driver_sha256") == s.driver_digest;
}

}  // namespace

json model_json(const Model& m) {
  return {{"subpixel_bits", m.subpixel_bits},
          {"planes", m.planes == Planes::snapped ? "snapped" : "unsnapped"},
          {"tie_break", to_string(m.tie_break)}};
}

std::optional<Model> model_from_json(const json& j) {
  if (!j.is_object()) return std::nullopt;
  const auto bits = j.find("subpixel_bits");
  const auto planes = j.find("planes");
  const auto tie = j.find("tie_break");
  if (bits == j.end() || !bits->is_number_integer() || planes == j.end() || !planes->is_string() ||
      tie == j.end() || !tie->is_string())
    return std::nullopt;
  Model m;
  m.subpixel_bits = bits->get<int>();
  if (m.subpixel_bits < 0 || m.subpixel_bits > 16) return std::nullopt;
  if (*planes == "snapped")
    m.planes = Planes::snapped;
  else if (*planes == "unsnapped")
    m.planes = Planes::unsnapped;
  else
    return std::nullopt;
  bool known = false;
  for (TieBreak t :
       {TieBreak::bottom_left, TieBreak::top_left, TieBreak::bottom_right, TieBreak::top_right})
    if (*tie == to_string(t)) m.tie_break = t, known = true;
  if (!known) return std::nullopt;
  return m;
}

std::filesystem::path model_cache_file() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  std::filesystem::path base;
  // The XDG base directory specification: a relative path is invalid and to be ignored.
  if (xdg && xdg[0] == '/') {
    base = xdg;
  } else if (const char* home = std::getenv("HOME"); home && home[0] == '/') {
    base = std::filesystem::path(home) / ".cache";
  } else {
    return {};
  }
  return base / "glrefcheck" / "models.json";
}

std::string files_digest(const std::vector<std::string>& files) {
  if (files.empty()) return "";
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) return "";
  std::vector<char> buf(1 << 20);
  for (const std::string& path : files) {
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return "";
    for (;;) {
      const ssize_t n = read(fd, buf.data(), buf.size());
      if (n < 0) {
        close(fd);
        return "";
      }
      if (n == 0) break;
      EVP_DigestUpdate(ctx.get(), buf.data(), size_t(n));
    }
    close(fd);
  }
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned len = 0;
  if (EVP_DigestFinal_ex(ctx.get(), md, &len) != 1) return "";
  return hex(md, len);
}

namespace {

// A file's identity as remembered_files_digest compares it; nullopt when it cannot be stat'ed.
std::optional<json> file_identity(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return std::nullopt;
  auto ns = [](const timespec& t) { return int64_t(t.tv_sec) * 1000000000 + t.tv_nsec; };
  return json{{"path", path},
              {"device", uint64_t(st.st_dev)},
              {"inode", uint64_t(st.st_ino)},
              {"size", int64_t(st.st_size)},
              {"modified_ns", ns(st.st_mtim)},
              {"changed_ns", ns(st.st_ctim)}};
}

}  // namespace

std::string remembered_files_digest(const std::vector<std::string>& files,
                                    const std::filesystem::path& store,
                                    std::filesystem::file_time_type now) {
  json identities = json::array();
  for (const std::string& f : files) {
    auto id = file_identity(f);
    if (!id) return files_digest(files);
    identities.push_back(std::move(*id));
  }
  json kept = json::array();
  try {
    std::ifstream in;
    if (readable_file(store)) in.open(store);
    const json j =
        in.is_open() && in ? json::parse(in, nullptr, /*allow_exceptions=*/false) : json();
    if (j.is_object() && j.value("format", 0) == kFormat && j.contains("digests") &&
        j["digests"].is_array())
      for (const json& entry : j["digests"]) {
        if (!entry.is_object() || !entry.contains("files") || !entry.contains("sha256") ||
            !entry["sha256"].is_string())
          continue;
        if (entry["files"] == identities) return entry["sha256"].get<std::string>();
        kept.push_back(entry);
      }
  } catch (const std::exception&) {
    // Unreadable is a miss.
  }
  const std::string digest = files_digest(files);
  if (digest.empty() || files.empty()) return digest;
  // The store's clock is the filesystem's: `now` in nanoseconds since the same epoch as the
  // files' times (file_time_type's clock on Linux is the system clock).
  const int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                             std::chrono::file_clock::to_sys(now).time_since_epoch())
                             .count();
  for (const json& id : identities)
    if (id["changed_ns"].get<int64_t>() > now_ns - 1000000000 ||
        id["modified_ns"].get<int64_t>() > now_ns - 1000000000)
      return digest;
  try {
    kept.push_back({{"files", identities}, {"sha256", digest}});
    if (kept.size() > kMaxEntries) kept.erase(kept.begin(), kept.end() - kMaxEntries);
    write_whole(store, json{{"format", kFormat}, {"digests", kept}});
  } catch (const std::exception&) {
    // Not remembered this time.
  }
  return digest;
}

std::vector<std::string> driver_files(const gl::GlInfo& gl) {
  if (gl.library.empty()) return {};
  std::vector<std::string> files{gl.library};
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* data) {
        const std::string_view path = info->dlpi_name ? info->dlpi_name : "";
        const std::string_view base = path.substr(path.rfind('/') + 1);
        if (base.starts_with("libgallium") || base.ends_with("_dri.so") ||
            base.starts_with("libvulkan_"))
          static_cast<std::vector<std::string>*>(data)->emplace_back(path);
        return 0;
      },
      &files);
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

ModelCacheSlot model_cache_slot(const std::string& renderer, const std::string& version,
                                const std::vector<std::string>& driver_files,
                                const std::filesystem::path& file) {
  ModelCacheSlot s;
  s.file = file;
  s.renderer = renderer;
  s.version = version;
  if (!file.empty())
    s.driver_digest =
        remembered_files_digest(driver_files, file.parent_path() / "driver_digests.json");
  return s;
}

std::optional<Model> ModelCacheSlot::load() const {
  if (!usable()) return std::nullopt;
  try {
    for (const json& entry : read_entries(file))
      if (same_key(entry, *this)) return model_from_json(entry.value("model", json()));
  } catch (const std::exception&) {
    // Unreadable is a miss.
  }
  return std::nullopt;
}

void ModelCacheSlot::save(const Model& m) const {
  if (!usable()) return;
  try {
    json kept = json::array();
    for (const json& entry : read_entries(file))
      if (!same_key(entry, *this)) kept.push_back(entry);
    kept.push_back({{"gl_renderer", renderer},
                    {"gl_version", version},
                    {"driver_sha256", driver_digest},
                    {"model", model_json(m)},
                    {"describe", m.describe()}});
    if (kept.size() > kMaxEntries) kept.erase(kept.begin(), kept.end() - kMaxEntries);
    write_whole(file, json{{"format", kFormat}, {"models", kept}});
  } catch (const std::exception&) {
    // No cache this time.
  }
}

}  // namespace glrc::identify
