#include "cli/output_dir.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <fmt/core.h>
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include <nlohmann/json.hpp>

#include "cli/fuzz.hpp"
#include "cli/session.hpp"
#include "cli/workers/process.hpp"
#include "core/text.hpp"
#include "image_io/glrc_images.h"
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

std::optional<std::string> lock_holder(const fs::path& dir) {
  const int fd = open((dir / kLockFile).c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) return std::nullopt;
  std::optional<std::string> holder;
  if (flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
    std::string line(512, '\0');
    const ssize_t n = pread(fd, line.data(), line.size(), 0);
    line.resize(size_t(std::max<ssize_t>(n, 0)));
    while (!line.empty() && (line.back() == '\n' || line.back() == '\0'))
      line.pop_back();
    // This process's own lock (report holds the folder while it reads it) is no other's.
    if (!line.starts_with(fmt::format("pid {}:", getpid())))
      holder = line.empty() ? "its pid not yet written" : printable(line, 300);
  }
  close(fd);  // releases a shared lock taken to look
  return holder;
}

const std::vector<std::string>& run_output_names() {
  // mesa_egl_vendor.json: --mesa's EGL vendor file for the workers (mesa_prefix.hpp).
  static const std::vector<std::string> names = {
      "results.json", "results.csv", "failures.csv", "junit.xml",   "report.html",
      kJournalFile,   "cases",       "logs",         kInputsFolder, "mesa_egl_vendor.json"};
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
      if (fs::exists(fs::symlink_status(dir / kMarkerFile, ec)))
        throw InputError(fmt::format(
            "{}, whose {} is not glrefcheck's marker (its first line edited, or made by hand): "
            "glrefcheck replaces nothing it did not mark; delete the folder or name another",
            expected, kMarkerFile));
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
    if (fs::is_symlink(fs::symlink_status(dir, ec)))
      // create_directories says only "File exists" of a link to nothing.
      throw InputError(option + ": expected a folder that can be created, got \"" + shown +
                       "\", a symbolic link to " +
                       printable(fs::read_symlink(dir, ec).string(), 200) +
                       ", which does not exist: create that folder, or name another");
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

namespace {

// Why `file` (which exists) is not glrefcheck `writer`'s to replace, or nullopt when it is.
std::optional<std::string> not_replaceable(const fs::path& file, const fs::file_status& st,
                                           const std::string& writer) {
  // A write replaces the link, not the file it names: the user means the file.
  if (fs::is_symlink(st)) return "which is a symbolic link (name the file it points to)";
  if (!fs::is_regular_file(st)) return "which is not a regular file";
  std::ifstream in(file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  if (!in.good() && !in.eof()) return "which cannot be read";
  if (text.find(report::kStampPrefix) == std::string::npos)
    return "which glrefcheck did not write (it holds no stamp)";
  if (!report::stamp_intact(text))
    return "which was changed since glrefcheck wrote it (its stamp no longer matches)";
  if (const std::string by = report::stamp_writer(text); by != writer)
    return "which glrefcheck " + (by.empty() ? std::string("wrote otherwise") : by) +
           " wrote, not glrefcheck " + writer;
  return std::nullopt;
}

}  // namespace

void check_replaceable(const fs::path& file, const std::string& option, const std::string& writer) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(file, ec);
  if (!fs::exists(st)) return;
  if (const auto why = not_replaceable(file, st, writer))
    throw InputError(option + ": expected a new file or one glrefcheck wrote, got \"" +
                     printable(file.string(), 200) + "\", " + *why +
                     ": glrefcheck replaces nothing it did not write; name another file");
}

void check_replaceable_files(const fs::path& dir, const std::string& option,
                             const std::string& writer, const std::set<std::string>& listed) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir, ec))) return;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (const auto why = !listed.count(it->path().filename().string())
                             ? std::optional<std::string>(
                                   "which the folder's results.json does not list (added, or "
                                   "left by a campaign that was killed)")
                             : not_replaceable(it->path(), it->symlink_status(ec), writer))
      throw InputError(option + ": expected only the files glrefcheck " + writer + " wrote in " +
                       printable(dir.string(), 200) +
                       ", which a run, merge or campaign here replaces, got \"" +
                       printable(it->path().filename().string(), 100) + "\", " + *why +
                       ": move it out of the folder first");
  if (ec) throw InputError(option + ": cannot read " + printable(dir.string(), 200));
}

namespace {

// Removes `names` from `dir` (what a run replaces). InputError naming the first that cannot go.
void remove_outputs(const fs::path& dir, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    std::error_code ec;
    fs::remove_all(dir / name, ec);
    if (ec)
      throw InputError("--out: cannot remove the earlier run's " + (dir / name).string() + " (" +
                       ec.message() + ")");
  }
}

// Moves each of `names` present in `from` into `to` (both in one folder: a rename each).
void move_outputs(const fs::path& from, const fs::path& to, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(from / name, ec))) continue;
    fs::rename(from / name, to / name, ec);
    if (ec)
      throw InputError("--out: cannot move " + (from / name).string() + " to " +
                       (to / name).string() + " (" + ec.message() + ")");
  }
}

std::vector<std::string> with_run_outputs(const std::vector<std::string>& also) {
  std::vector<std::string> names = run_output_names();
  names.insert(names.end(), also.begin(), also.end());
  // failures/ goes with its list of the minimal cases a campaign wrote before its results.
  if (std::find(also.begin(), also.end(), "failures") != also.end())
    names.push_back(kFailuresWritten);
  return names;
}

// Everything a run or campaign may leave in its folder: what a restore replaces.
const std::vector<std::string>& every_output_name() {
  static const std::vector<std::string> names = with_run_outputs({"failures"});
  return names;
}

}  // namespace

namespace {

// In kEarlierFolder once every output is in it: before, an output not in it was not moved yet
// (it is still the earlier run's); after, one not in it is the new attempt's.
constexpr const char* kSetAsideComplete = ".complete";
// Where keep_new moves kEarlierFolder before deleting it: a delete that fails halfway must not
// leave a kEarlierFolder that a later claim would take for the folder's results.
constexpr const char* kDiscardedFolder = ".glrefcheck-discarded";

}  // namespace

EarlierOutputs::EarlierOutputs(EarlierOutputs&& other) noexcept
    : dir_(std::move(other.dir_)), any_(other.any_) {
  other.dir_.clear();
}

std::string EarlierOutputs::left_as_it_was(const std::string& folder) const {
  return any_ ? folder + " holds its earlier results as they were"
              : folder + " holds no results (it held none before)";
}

namespace {

// The earlier outputs of `dir` deleted: first renamed away, so that a delete that fails halfway
// leaves no kEarlierFolder for a later claim to restore.
void discard_earlier_outputs(const fs::path& dir) {
  std::error_code ec;
  fs::remove_all(dir / kDiscardedFolder, ec);
  fs::rename(dir / kEarlierFolder, dir / kDiscardedFolder, ec);
  fs::remove_all(dir / (ec ? kEarlierFolder : kDiscardedFolder), ec);
}

}  // namespace

void EarlierOutputs::keep_new() {
  if (dir_.empty()) return;
  discard_earlier_outputs(dir_);
  dir_.clear();
}

EarlierOutputs::~EarlierOutputs() {
  if (dir_.empty()) return;
  try {
    restore_earlier_outputs(dir_);
  } catch (const std::exception& e) {
    // A destructor may run while an error unwinds: say it, and leave the outputs where the next
    // claim of the folder restores them.
    fmt::print(stderr, "glrefcheck: the earlier outputs stay in {}: {}\n",
               (dir_ / kEarlierFolder).string(), e.what());
  }
}

void check_no_output_folder_inside(const fs::path& dir, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    std::error_code ec;
    if (!fs::is_directory(fs::symlink_status(dir / name, ec))) continue;
    for (fs::recursive_directory_iterator it(dir / name, ec), end; !ec && it != end;
         it.increment(ec))
      if (it->path().filename() == kMarkerFile)
        throw InputError("--out: " + printable((dir / name).string(), 200) +
                         " holds another glrefcheck output folder (" +
                         printable(it->path().parent_path().string(), 200) +
                         "), which this run would write into: move it out, or name another --out");
  }
}

namespace {

// Whether the first `size` bytes of `file` hold `mark`: an image's Software (ahead of its pixels
// in a PNG and an EXR alike), a log's first line.
bool begins_with_mark(const fs::path& file, size_t size, std::string_view mark) {
  std::ifstream in(file, std::ios::binary);
  std::string head(size, '\0');
  in.read(head.data(), std::streamsize(size));
  head.resize(size_t(in.gcount()));
  return head.find(mark) != std::string::npos;
}

// Whether the images and logs in `dir` carry glrefcheck's marks (GLRC_IMAGES_SOFTWARE,
// kChildLogHeader): unless its results.json is an older glrefcheck's, without a stamp.
bool outputs_marked(const fs::path& dir) {
  std::error_code ec;
  return !fs::is_regular_file(dir / "results.json", ec) ||
         begins_with_mark(dir / "results.json", 4096, report::kStampPrefix);
}

// InputError naming the file when what a run replaces in `dir` holds something glrefcheck did
// not write there, checked before anything is moved: a report.html a person edited (its stamp
// no longer matches), a file in cases/ other than a case's heatmaps (cases/<case>/*.png, *.exr),
// a file in logs/ other than a worker's log, a minimal case in failures/ a person edited or
// added (check_replaceable_files). A run replaces its own files, never a person's notes.
void check_outputs_ours(const fs::path& dir, const std::vector<std::string>& names) {
  const std::string option = "--out " + printable(dir.string(), 200);
  const auto refuse = [&](const fs::path& file, const std::string& why) {
    throw InputError(option + ": " + printable(file.string(), 200) + " " + why +
                     ", and a run, merge or campaign here replaces it: move it out of the "
                     "folder, or name another --out");
  };
  std::error_code ec;
  // Each output of the kind glrefcheck writes under its name: a folder of a person's where a
  // file goes (a junit.xml/ holding notes), or a file where a folder goes (a file named logs),
  // would be replaced with all it holds. A link is replaced, not what it names.
  for (const std::string& name : names) {
    const fs::file_status st = fs::symlink_status(dir / name, ec);
    if (!fs::exists(st) || fs::is_symlink(st)) continue;
    const bool folder =
        name == "cases" || name == "logs" || name == "failures" || name == kInputsFolder;
    if (folder && !fs::is_directory(st))
      refuse(dir / name, "is not a folder, where glrefcheck writes a folder of that name");
    if (!folder && !fs::is_regular_file(st))
      refuse(dir / name, "is not a regular file, where glrefcheck writes a file of that name");
  }
  const fs::path page = dir / "report.html";
  if (const auto st = fs::symlink_status(page, ec); fs::exists(st)) {
    if (!fs::is_regular_file(st))
      refuse(page, "is not a regular file, where glrefcheck writes a file of that name");
    std::ifstream in(page, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    if (!report::stamp_intact(text))
      refuse(page,
             "is not a page glrefcheck wrote, or was changed since (its stamp no longer "
             "matches)");
    // A comparison's page (`compare --html`) is a page of its own, not this folder's report.
    if (report::stamp_writer(text) != "report")
      refuse(page, "is a page glrefcheck " + report::stamp_writer(text) +
                       " wrote, not the folder's report");
  }
  const auto entries = [&](const fs::path& folder, const auto& fits) {
    if (!fs::is_directory(fs::symlink_status(folder, ec))) return;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
      if (const char* why = fits(*it)) refuse(it->path(), why);
  };
  // An older glrefcheck's folder (results.json without a stamp) holds images and logs without
  // glrefcheck's mark: those are taken by their names alone.
  const bool marked = outputs_marked(dir);
  entries(dir / "cases", [&](const fs::directory_entry& e) -> const char* {
    if (!fs::is_directory(e.symlink_status(ec))) return "is not a case's folder of heatmaps";
    entries(e.path(), [&](const fs::directory_entry& image) -> const char* {
      const std::string ext = image.path().extension().string();
      return fs::is_regular_file(image.symlink_status(ec)) && (ext == ".png" || ext == ".exr") &&
                     (!marked || begins_with_mark(image.path(), 64 * 1024, GLRC_IMAGES_SOFTWARE))
                 ? nullptr
                 : "is not a heatmap glrefcheck wrote (a .png or .exr naming glrefcheck as its "
                   "Software)";
    });
    return nullptr;
  });
  entries(dir / "logs", [&](const fs::directory_entry& e) -> const char* {
    const std::string name = e.path().filename().string();
    return fs::is_regular_file(e.symlink_status(ec)) && name.starts_with("worker-") &&
                   name.ends_with(".log") &&
                   (!marked || begins_with_mark(e.path(), kChildLogHeader.size(), kChildLogHeader))
               ? nullptr
               : "is not a worker's log glrefcheck wrote";
  });
  if (std::find(names.begin(), names.end(), "failures") != names.end())
    check_replaceable_files(dir / "failures", option, "fuzz", listed_failure_files(dir));
}

}  // namespace

namespace {

// Removes the temporary files (report::write_file_atomically's `.<name>.tmp-<pid>`) that a
// glrefcheck killed outright left in `dir`: those of a process that no longer runs.
void remove_stale_temporaries(const fs::path& dir) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const size_t at = name.rfind(".tmp-");
    if (!name.starts_with(".") || at == std::string::npos) continue;
    const std::string digits = name.substr(at + 5);
    if (digits.empty() || digits.size() > 9 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      continue;
    if (kill(pid_t(std::stol(digits)), 0) != 0 && errno == ESRCH) {
      std::error_code removed;
      fs::remove(it->path(), removed);
    }
  }
}

}  // namespace

EarlierOutputs set_aside_outputs(const fs::path& dir, const std::vector<std::string>& also) {
  if (!is_marked(dir))
    throw std::logic_error("set_aside_outputs: " + dir.string() + " is not a marked folder");
  restore_earlier_outputs(dir);
  remove_stale_temporaries(dir);
  std::error_code ec;
  fs::remove_all(dir / kDiscardedFolder, ec);
  const std::vector<std::string> names = with_run_outputs(also);
  check_no_output_folder_inside(dir, names);
  check_outputs_ours(dir, names);
  const fs::path aside = dir / kEarlierFolder;
  fs::create_directory(aside, ec);
  if (ec) throw InputError("--out: cannot make " + aside.string() + " (" + ec.message() + ")");
  EarlierOutputs earlier;
  earlier.dir_ = dir;
  for (const std::string& name : names)
    earlier.any_ = earlier.any_ || fs::exists(fs::symlink_status(dir / name, ec));
  move_outputs(dir, aside, names);
  report::write_file_atomically(aside / kSetAsideComplete, "");
  return earlier;
}

void settle_earlier_outputs(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir / kEarlierFolder, ec))) return;
  if (fs::exists(fs::symlink_status(dir / kJournalFile, ec)))
    discard_earlier_outputs(dir);
  else
    restore_earlier_outputs(dir);
}

void restore_earlier_outputs(const fs::path& dir) {
  const fs::path aside = dir / kEarlierFolder;
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(aside, ec))) return;
  // What is in the folder now under an output's name is the attempt's that never had GL, or,
  // where the attempt was killed while setting them aside, the earlier run's not moved yet.
  // Nothing aside (a new folder's first run): nothing to give back, and the attempt's journal
  // stays for `run --resume`.
  const bool complete = fs::exists(aside / kSetAsideComplete, ec);
  bool any = false;
  for (const std::string& name : every_output_name())
    any = any || fs::exists(fs::symlink_status(aside / name, ec));
  if (complete && !any) {
    fs::remove_all(aside, ec);
    return;
  }
  for (const std::string& name : every_output_name()) {
    const bool moved = fs::exists(fs::symlink_status(aside / name, ec));
    if (moved || complete) remove_outputs(dir, {name});
    if (moved) move_outputs(aside, dir, {name});
  }
  fs::remove_all(aside, ec);
  if (ec) throw InputError("--out: cannot remove " + aside.string() + " (" + ec.message() + ")");
}

namespace {

constexpr std::string_view kDiffListHeader = "# glrefcheck diff ";

// The list's entries, digest and name, when its stamp holds; none otherwise.
std::vector<std::pair<std::string, std::string>> diff_image_list(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(dir / kDiffImagesFile, ec))) return {};
  std::ifstream in(dir / kDiffImagesFile, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  if (!text.starts_with(kDiffListHeader) || !report::stamp_intact(text)) return {};
  std::vector<std::pair<std::string, std::string>> entries;
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);  // the header and its stamp
  while (std::getline(lines, line)) {
    const size_t space = line.find(' ');
    if (space == std::string::npos) continue;
    entries.emplace_back(line.substr(0, space), line.substr(space + 1));
  }
  return entries;
}

}  // namespace

void record_diff_images(const fs::path& dir,
                        const std::vector<std::pair<fs::path, std::string>>& images) {
  std::string text = std::string(kDiffListHeader) + report::stamp_placeholder() + "\n";
  for (const auto& [file, digest] : images)
    if (file.parent_path() == dir)
      text += (digest.empty() ? "-" : digest) + " " + file.filename().string() + "\n";
  report::write_file_atomically(dir / kDiffImagesFile, report::stamped(text));
}

void clear_diff_images(const fs::path& dir, const std::vector<std::string>& next_images) {
  if (!is_marked(dir))
    throw std::logic_error("clear_diff_images: " + dir.string() + " is not a marked folder");
  // The last diff's images: written halfway ("-"), or whole and unchanged since. A changed one,
  // or anything else in the folder, is the user's.
  std::set<std::string> ours;
  for (const auto& [digest, name] : diff_image_list(dir)) {
    const fs::path file(name);
    // One plain name in the folder, as record_diff_images writes them: nothing else is ours.
    if (name.empty() || file.has_parent_path() || name == "." || name == ".." ||
        name == kMarkerFile || name == kLockFile || name == kDiffImagesFile)
      continue;
    // Read only a regular file: a FIFO put there would block the diff for good.
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(dir / file, ec))) continue;
    if (digest != "-") {
      std::ifstream in(dir / file, std::ios::binary);
      const std::string text((std::istreambuf_iterator<char>(in)), {});
      if (report::content_digest(text) != digest) continue;
    }
    ours.insert(name);
  }
  // Refused before anything is deleted.
  for (const std::string& name : next_images) {
    std::error_code ec;
    if (ours.count(name) || !fs::exists(fs::symlink_status(dir / name, ec))) continue;
    throw InputError("diff --out " + printable(dir.string(), 200) + ": expected no \"" +
                     printable(name, 100) +
                     "\" there but an image the last diff wrote, got one of yours (or one changed "
                     "since): move it, or name another --out");
  }
  std::error_code ec;
  for (const std::string& name : ours)
    fs::remove(dir / name, ec);
  fs::remove(dir / kDiffImagesFile, ec);
}

}  // namespace glrc::cli
