#include "cli/output_dir.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <fmt/core.h>
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli/session.hpp"
#include "core/text.hpp"
#include "report/report.hpp"
#include "report/stamp.hpp"

namespace glrc::cli {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMarkerText =
    "glrefcheck output folder: glrefcheck replaces its own files here (results.json, results.csv, "
    "failures.csv, junit.xml, report.html, journal.jsonl, cases/, logs/) and nothing else.\n";

// A results.json (of `run`) or an identify.json (of `identify`) as glrefcheck writes them. Such
// a folder without the marker is still refused (its results.json proves nothing: anyone can
// write one, and cases/ beside it would be deleted), but the message says what to do.
bool looks_like_glrefcheck_output(const fs::path& dir) {
  const auto parse = [&](const char* name) -> nlohmann::json {
    std::error_code ec;
    if (!fs::is_regular_file(dir / name, ec)) return nullptr;
    try {
      std::ifstream in(dir / name);
      return nlohmann::json::parse(in);
    } catch (const std::exception&) {
      return nullptr;
    }
  };
  const auto results = parse("results.json");
  if (results.is_object() && results.contains("run") && results["run"].is_object() &&
      results["run"].contains("gl_renderer") && results.contains("cases") &&
      results["cases"].is_array())
    return true;
  const auto identify = parse("identify.json");
  return identify.is_object() && identify.contains("depth24") && identify.contains("tie_break") &&
         identify.contains("provoking_default");
}

// This process's command line as a person typed it (argv joined by spaces), for a lock's
// holder line.
std::string own_command_line() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  while (!text.empty() && text.back() == '\0')
    text.pop_back();
  std::replace(text.begin(), text.end(), '\0', ' ');
  // argv[0] as its file name: the folder it ran from says nothing here.
  const size_t space = text.find(' ');
  const size_t slash = text.rfind('/', space);
  if (slash != std::string::npos) text.erase(0, slash + 1);
  return text;
}

}  // namespace

FolderLock::FolderLock(FolderLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

FolderLock& FolderLock::operator=(FolderLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) close(fd_);  // releases the flock
}

FolderLock lock_folder(const fs::path& dir, const std::string& option) {
  const fs::path file = dir / kLockFile;
  const std::string shown = printable(dir.string(), 200);
  // Not through a symbolic link: the holder's line would be written into whatever it names.
  const int fd = open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0)
    throw InputError(fmt::format("{}: cannot lock \"{}\" ({}: {})", option, shown, kLockFile,
                                 std::strerror(errno)));
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    std::string holder(512, '\0');
    const ssize_t n = pread(fd, holder.data(), holder.size(), 0);
    close(fd);
    holder.resize(size_t(std::max<ssize_t>(n, 0)));
    while (!holder.empty() && (holder.back() == '\n' || holder.back() == '\0'))
      holder.pop_back();
    if (error != EWOULDBLOCK)
      throw InputError(
          fmt::format("{}: cannot lock \"{}\" ({})", option, shown, std::strerror(error)));
    throw InputError(fmt::format(
        "{}: \"{}\" is in use by another glrefcheck ({}): wait for it to end, or name another "
        "folder",
        option, shown, holder.empty() ? "its pid not yet written" : printable(holder, 300)));
  }
  // Ours now: who holds it, for the next one refused. A failure to write it changes nothing of
  // the lock.
  const std::string line = fmt::format("pid {}: {}\n", getpid(), own_command_line());
  if (ftruncate(fd, 0) == 0 && pwrite(fd, line.data(), line.size(), 0) < 0) {
    // The line is only a courtesy to whoever is refused.
  }
  return FolderLock(fd);
}

const std::vector<std::string>& run_output_names() {
  static const std::vector<std::string> names = {"results.json", "results.csv", "failures.csv",
                                                 "junit.xml",    "report.html", kJournalFile,
                                                 "cases",        "logs",        kInputsFolder};
  return names;
}

bool is_marked(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / kMarkerFile, ec)) return false;
  std::ifstream in(dir / kMarkerFile);
  std::string first;
  std::getline(in, first);
  return first.starts_with("glrefcheck output folder");
}

OutputFolder output_folder(const std::string& out, const std::string& option) {
  if (out.empty()) throw InputError(option + ": expected a folder, got \"\"");
  // Results record their paths in JSON, which holds UTF-8 only: refused here, not mid-run.
  if (!is_utf8(out))
    throw InputError(option + ": expected a path in UTF-8, got \"" + printable(out) + "\"");
  const fs::path dir(out);
  const std::string shown = printable(out);
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st))
      throw InputError(option + ": expected a folder, got \"" + shown + "\" (not a folder)");
    if (access(dir.c_str(), W_OK) != 0)
      throw InputError(option + ": expected a writable folder, got \"" + shown + "\"");
    std::vector<std::string> entries;
    // The lock file, or the marker's temporary file, alone is a claim another glrefcheck is
    // making now: lock_folder names it.
    if (!is_marked(dir))
      for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (const std::string name = it->path().filename().string();
            name != kLockFile && !name.starts_with("." + std::string(kMarkerFile) + ".tmp-"))
          entries.push_back(name);
    if (ec)
      throw InputError(option + ": cannot read the folder \"" + shown + "\" (" + ec.message() +
                       ")");
    if (!entries.empty()) {
      std::sort(entries.begin(), entries.end());
      const std::string expected = fmt::format(
          "{}: expected a new or empty folder, or one glrefcheck made (it holds a {} file), got "
          "\"{}\"",
          option, kMarkerFile, shown);
      if (looks_like_glrefcheck_output(dir))
        throw InputError(expected +
                         ", which holds glrefcheck's results but no marker (an older glrefcheck's, "
                         "or copied): glrefcheck replaces nothing it did not mark; delete the "
                         "folder or name another");
      throw InputError(fmt::format(
          "{}, which holds \"{}\"{}: glrefcheck replaces nothing it did not write; name another "
          "folder",
          expected, printable(entries.front(), 80),
          entries.size() > 1 ? fmt::format(" and {} more", entries.size() - 1) : ""));
    }
  } else {
    // Only the folder named is glrefcheck's: a parent made on the way (proj/ of --out proj/o1) is
    // no output the user named, and a later --out proj must not take its proj/cases/ for ours.
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
      throw InputError(option + ": expected a folder that can be created, got \"" + shown + "\"" +
                       (ec ? " (" + ec.message() + ")" : " (not a folder)"));
    if (access(dir.c_str(), W_OK) != 0)
      throw InputError(option + ": expected a writable folder, got \"" + shown + "\"");
  }
  OutputFolder folder{dir, lock_folder(dir, option)};
  try {
    report::write_file_atomically(dir / kMarkerFile, kMarkerText);
  } catch (const std::exception& e) {
    throw InputError(option + ": " + e.what());
  }
  return folder;
}

void check_replaceable(const fs::path& file, const std::string& option, const std::string& writer) {
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  if (!fs::exists(st)) return;
  const std::string shown = printable(file.string(), 200);
  const auto refuse = [&](const std::string& what) {
    throw InputError(option + ": expected a new file or one glrefcheck wrote, got \"" + shown +
                     "\", " + what +
                     ": glrefcheck replaces nothing it did not write; name another file");
  };
  if (!fs::is_regular_file(st)) refuse("which is not a regular file");
  std::ifstream in(file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  if (!in.good() && !in.eof()) refuse("which cannot be read");
  if (text.find(report::kStampPrefix) == std::string::npos)
    refuse("which glrefcheck did not write (it holds no stamp)");
  if (!report::stamp_intact(text))
    refuse("which was changed since glrefcheck wrote it (its stamp no longer matches)");
  if (const std::string by = report::stamp_writer(text); by != writer)
    refuse("which glrefcheck " + (by.empty() ? std::string("wrote otherwise") : by) +
           " wrote, not glrefcheck " + writer);
}

void clear_diff_images(const fs::path& dir) {
  if (!is_marked(dir))
    throw std::logic_error("clear_diff_images: " + dir.string() + " is not a marked folder");
  std::ifstream in(dir / kDiffImagesFile);
  for (std::string name; std::getline(in, name);) {
    const fs::path file(name);
    // One plain name in the folder, as record_diff_images writes them: nothing else is ours.
    if (name.empty() || file.has_parent_path() || name == "." || name == ".." ||
        name == kMarkerFile || name == kLockFile)
      continue;
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(dir / file, ec))) fs::remove(dir / file, ec);
  }
  std::error_code ec;
  fs::remove(dir / kDiffImagesFile, ec);
}

void record_diff_images(const fs::path& dir, const std::vector<fs::path>& files) {
  std::string text;
  for (const fs::path& f : files)
    if (f.parent_path() == dir) text += f.filename().string() + "\n";
  report::write_file_atomically(dir / kDiffImagesFile, text);
}

void clear_run_outputs(const fs::path& dir) {
  // Only ever inside a folder glrefcheck owns: anything else is the user's.
  if (!is_marked(dir))
    throw std::logic_error("clear_run_outputs: " + dir.string() + " is not a marked folder");
  for (const std::string& name : run_output_names()) {
    std::error_code ec;
    fs::remove_all(dir / name, ec);
    if (ec)
      throw InputError("--out: cannot remove the earlier run's " + (dir / name).string() + " (" +
                       ec.message() + ")");
  }
}

}  // namespace glrc::cli
