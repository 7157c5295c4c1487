// Output folders. glrefcheck writes, replaces and deletes only in a folder it owns: one it made,
// or one given to it empty, which it marks with a `.glrefcheck` file (so `run --out .` in a
// checkout is refused instead of replacing the suite's cases/). Anything else is refused, a
// folder holding a results.json of glrefcheck's but no marker too: a file anyone can write is no
// proof, and the cases/ beside it would be deleted.
#pragma once

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "casefile/casefile.hpp"

namespace glrc::cli {

inline constexpr const char* kMarkerFile = casefile::kOutputFolderMarker;
inline constexpr const char* kJournalFile = "journal.jsonl";
// Copies of --baseline, --flakes and --skips as the run read them, for --resume (a baseline may
// be the folder's own failures.csv, which the run replaces).
inline constexpr const char* kInputsFolder = ".glrefcheck-inputs";

// The lock file of an output folder (FolderLock).
inline constexpr const char* kLockFile = ".glrefcheck.lock";

// An output folder held by this process, as long as the value lives: its kLockFile locked with
// flock(2), which the kernel releases when the process ends however it ends (a lock a killed
// glrefcheck left is simply taken by the next), holding the holder's pid and command line for
// the glrefcheck it refuses. Closed across exec (workers do not hold it).
class FolderLock {
 public:
  FolderLock() = default;
  FolderLock(FolderLock&& other) noexcept;
  FolderLock& operator=(FolderLock&& other) noexcept;
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock();
  bool held() const { return fd_ >= 0; }

 private:
  friend FolderLock lock_folder(const std::filesystem::path& dir, const std::string& option);
  explicit FolderLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

// Takes `dir`'s lock (dir must exist and be glrefcheck's: marked, or being claimed by
// output_folder). InputError naming `option`, the folder and the holder (its pid and command)
// when another process holds it, or when the lock file cannot be made.
FolderLock lock_folder(const std::filesystem::path& dir, const std::string& option);

// An output folder claimed for this process: its path, and its lock held.
struct OutputFolder {
  std::filesystem::path path;
  FolderLock lock;
};

// `option` (--out) names the folder in messages. Creates and marks the folder, or checks that it
// is marked or empty, then locks it (lock_folder): a second glrefcheck writing into it at once is
// refused. InputError otherwise, and for a path that is not UTF-8, a file, or a folder that
// cannot be written. Only the folder named is marked, never a parent made on the way: that is no
// output the user named. (Declared with its default in session.hpp.)
OutputFolder output_folder(const std::string& out, const std::string& option);

// A file an option names for glrefcheck to write (`fuzz --emit`, `compare --json`, `report
// --out`, `export --out`): fine if it does not exist, or if it is a regular file whose stamp its
// text still matches (report/stamp.hpp: glrefcheck wrote it and nobody changed it since), written
// by the same command, `writer` ("fuzz", "compare", "export", "report"). Anything else is the
// user's, or another command's: InputError naming `option`, before anything is written.
void check_replaceable(const std::filesystem::path& file, const std::string& option,
                       const std::string& writer);

// check_replaceable for every entry of the folder `dir` (fuzz's failures/ before a campaign
// replaces it), each also one of `listed` (the names the folder's own record gives: a stamped
// file copied in from elsewhere is no file of this folder's): a minimal case a person edited or
// added there is theirs. Nothing when `dir` does not exist.
void check_replaceable_files(const std::filesystem::path& dir, const std::string& option,
                             const std::string& writer, const std::set<std::string>& listed);

// The holder's line ("pid N: command") when another glrefcheck holds `dir`'s lock now, else
// nullopt (no lock file, or one nobody holds): for commands that only read a folder, to name a
// live run rather than take its half-written folder for a killed one.
std::optional<std::string> lock_holder(const std::filesystem::path& dir);

// Whether `dir` carries the marker.
bool is_marked(const std::filesystem::path& dir);

// An earlier run's (or campaign's) outputs in a marked folder, set aside while a new one starts:
// renamed into kEarlierFolder, not deleted, until the new run has GL (keep_new) or has written
// its own results. A run that ends before, because its driver, prefix or wrapper cannot make a
// GL context or it was refused, gives them back when the value dies (its own partial outputs,
// a journal without a result, go). A glrefcheck killed while they were aside leaves them there;
// the next claim of the folder (set_aside_outputs, or `run --resume` through
// restore_earlier_outputs) puts them back first, since the killed one never checked a case.
inline constexpr const char* kEarlierFolder = ".glrefcheck-earlier";
class EarlierOutputs {
 public:
  EarlierOutputs() = default;
  EarlierOutputs(EarlierOutputs&& other) noexcept;
  EarlierOutputs& operator=(EarlierOutputs&&) = delete;
  EarlierOutputs(const EarlierOutputs&) = delete;
  ~EarlierOutputs();
  // The new run is under way (it has GL, or has written its results): the earlier outputs go.
  void keep_new();
  // Whether the folder held any output to set aside (a new folder's first run: none).
  bool any() const { return any_; }
  // What the folder holds once this run stops before GL, in words for the line saying so.
  std::string left_as_it_was(const std::string& folder) const;

 private:
  friend EarlierOutputs set_aside_outputs(const std::filesystem::path& dir,
                                          const std::vector<std::string>& also);
  std::filesystem::path dir_;  // empty once kept (or moved from)
  bool any_ = false;
};

// Sets aside what an earlier run or merge wrote into the marked folder `dir`, whose lock the
// caller holds (run_output_names(): results.json, results.csv, failures.csv, junit.xml,
// report.html, the journal, cases/, logs/, the inputs' copies; and `also`, fuzz's failures/), so
// that nothing of it is taken for this run's. Nothing else: identify.json and diff's images
// stay. InputError naming the file when one cannot be moved, and before anything is moved when
// one of them holds another output folder (`diff --out RUN/logs/d`): that is no run's file.
EarlierOutputs set_aside_outputs(const std::filesystem::path& dir,
                                 const std::vector<std::string>& also = {});

// InputError when one of `names` (a run's cases/ or logs/) in `dir` holds another output folder
// (`diff --out RUN/cases/x`): a run would write into it, or replace it.
void check_no_output_folder_inside(const std::filesystem::path& dir,
                                   const std::vector<std::string>& names);

// Puts back outputs a killed glrefcheck left aside in `dir` (see EarlierOutputs); nothing when
// there are none.
void restore_earlier_outputs(const std::filesystem::path& dir);
// For `run --resume` of `dir`: outputs left aside go for good when the run killed before it had
// GL wrote its journal (that run is the one to resume), else come back
// (restore_earlier_outputs).
void settle_earlier_outputs(const std::filesystem::path& dir);

// `diff`'s images in a marked folder, listed in kDiffImagesFile (stamped "glrefcheck diff"):
// each image's name and the content digest it was written with (report::content_digest; "-"
// while it was being written). Before the next diff writes its own, clear_diff_images deletes
// the images the last diff wrote and nobody changed since (and any it was still writing), so that
// no image of another case stays beside this one's; an image someone changed stays, and so does
// everything when the list itself was changed (or is an older glrefcheck's, without a stamp). A
// name that is not a plain file name in the folder is never followed. InputError, before anything
// is deleted, when one of `next_images` (the names the next diff may write,
// report::diff_image_names) is in the folder and is not the last diff's: a file of the user's (a
// screenshot, notes), or an image someone changed.
inline constexpr const char* kDiffImagesFile = ".glrefcheck-diff-images";
void clear_diff_images(const std::filesystem::path& dir,
                       const std::vector<std::string>& next_images);
// Writes the list: `images`, each a file in `dir` and its digest ("" while being written).
void record_diff_images(const std::filesystem::path& dir,
                        const std::vector<std::pair<std::filesystem::path, std::string>>& images);

// The run's own files and folders in a run folder, relative to it.
const std::vector<std::string>& run_output_names();

}  // namespace glrc::cli
