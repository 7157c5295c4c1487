// Text from files, drivers and the command line, made fit for one-line messages and JSON.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace glrc {

// Whether `s` is valid UTF-8 (JSON, which results.json and the journal are, holds only that).
bool is_utf8(std::string_view s);
// `s` for a one-line message: control characters and bytes that are not UTF-8 as \xNN; cut
// to at most `max` characters of `s` (then "..." and the full length in bytes).
std::string printable(std::string_view s, size_t max = std::string_view::npos);
// `text` as lines of words of at most `width` characters (a longer word on a line of its own),
// each line `prefix`, the words joined by single spaces, and "\n": comment blocks of generated
// files. Spaces alone break words; runs of them count as one.
std::string wrap_words(std::string_view text, size_t width, std::string_view prefix);
// `s` as one word of a POSIX shell, for a command printed for a person to paste: as it is where
// it is plain, else in single quotes; one that starts with '-' (a file "-dash.c") gets "./",
// or the command would take it for an option.
std::string shell_word(std::string_view s);

// What a path that is not a regular file is, for a message, from its status (followed through
// links): "a directory", "a FIFO", "a socket", "a character device", "a block device", "a broken
// symbolic link" (not found: the path was listed, its link's target is gone), or "something
// other than a regular file".
std::string file_kind(const std::filesystem::file_status& st);
// The same of a path, "no such file" where nothing is there.
std::string file_kind(const std::filesystem::path& path);

}  // namespace glrc
