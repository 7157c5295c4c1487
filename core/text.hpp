// Text from files, drivers and the command line, made fit for one-line messages and JSON.
#pragma once

#include <string>
#include <string_view>

namespace glrc {

// Whether `s` is valid UTF-8 (JSON, which results.json and the journal are, holds only that).
bool is_utf8(std::string_view s);
// `s` for a one-line message: control characters and bytes that are not UTF-8 as \xNN; cut
// to at most `max` characters of `s` (then "..." and the full length in bytes).
std::string printable(std::string_view s, size_t max = std::string_view::npos);

}  // namespace glrc
