// Output folders. glrefcheck writes, replaces and deletes only in a folder it owns: one it made,
// or one given to it empty, which it marks with a `.glrefcheck` file (so `run --out .` in a
// checkout is refused instead of replacing the suite's cases/). Anything else is refused, a
// folder holding a results.json of glrefcheck's but no marker too: a file anyone can write is no
// proof, and the cases/ beside it would be deleted.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace glrc::cli {

inline constexpr const char* kMarkerFile = ".glrefcheck";
inline constexpr const char* kJournalFile = "journal.jsonl";
// Copies of --baseline, --flakes and --skips as the run read them, for --resume (a baseline may
// be the folder's own failures.csv, which the run replaces).
inline constexpr const char* kInputsFolder = ".glrefcheck-inputs";

// `option` (--out) names the folder in messages. Creates and marks the folder, or checks that it
// is marked or empty; InputError otherwise, and for a path that is not
// UTF-8, a file, or a folder that cannot be written. (Declared with its default in session.hpp.)
std::filesystem::path output_folder(const std::string& out, const std::string& option);

// A file an option names for glrefcheck to write (`compare --json`, `report --out`): fine if it
// does not exist, or if it is a regular file whose first 4 KiB hold `signature` (what glrefcheck
// writes at the top of such a file). Anything else is the user's: InputError naming `option`,
// before anything is written.
void check_replaceable(const std::filesystem::path& file, const std::string& option,
                       std::string_view signature);

// Whether `dir` carries the marker.
bool is_marked(const std::filesystem::path& dir);

// Deletes what an earlier run or merge wrote into a marked folder (results.json, results.csv,
// failures.csv, junit.xml, report.html, the journal, cases/, logs/, the inputs' copies), so that
// nothing of it is taken for this run's. Nothing else: identify.json and diff's images stay.
void clear_run_outputs(const std::filesystem::path& dir);

// The run's own files and folders in a run folder, relative to it.
const std::vector<std::string>& run_output_names();

}  // namespace glrc::cli
