// Reading cases/*.json into Case values, with validation: every error names the file, the
// field and what was expected.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "typed_json/error.hpp"

namespace glrc::casefile {

// what() is one line: "<file>: <field>: expected <what>, got <what>". A typed_json::Error (the
// case loader's reader throws it), and so a std::runtime_error.
struct CaseError : typed_json::Error {
  using typed_json::Error::Error;
};

// The case in `file`, validated (cases/README.md). Throws CaseError naming the file, the field
// and what was expected: for a path that is no readable regular file, bytes no JSON text holds
// (NUL, not UTF-8), invalid JSON, a key twice in one object, an unknown key, or any field out of
// its type or range.
Case load(const std::filesystem::path& file);

// The case a case file's text holds, named `name`; messages name `source` as load()'s name the
// file. Throws CaseError as load() does for the text. `fuzz` checks every shrunk candidate
// with it, so that a minimal case is always one the loader takes.
Case parse(std::string text, const std::string& source, const std::string& name);

// The file that marks a folder as glrefcheck's output (cli/output_dir.hpp): collect() searches
// no such folder below the ones named.
inline constexpr const char* kOutputFolderMarker = ".glrefcheck";

// Case files named by the arguments: files as given, directories searched recursively for
// *.json (following symbolic links, each folder once, so that a link loop ends; a folder below
// them holding kOutputFolderMarker is passed over with a note); sorted by path, duplicates
// removed. A FIFO, socket, device or unfollowable link found as *.json in a folder is
// ignored with one line to `note` (default: stderr). Throws CaseError for a path that does not
// exist or is neither a regular file nor a folder (never read), a path that is not UTF-8, an
// unreadable folder, a case name (file stem) with a control character, or two cases of one name.
std::vector<std::filesystem::path> collect(
    const std::vector<std::string>& files_or_dirs,
    const std::function<void(const std::string&)>& note = nullptr);

}  // namespace glrc::casefile
