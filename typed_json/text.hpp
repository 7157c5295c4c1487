// Text for typed_json's messages: one line whatever a file, key or value holds, and the field
// paths messages name ("vertices[3].clip").
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace glrc::typed_json {

// The length of the UTF-8 sequence starting at s[i], or 0 when none starts there (RFC 3629:
// overlong forms, surrogates and code points beyond U+10FFFF are not UTF-8, as nlohmann-json
// also holds). i < s.size().
size_t utf8_length(std::string_view s, size_t i);

// `s` fit for one line of a UTF-8 terminal: control characters as \n, \r, \t or \u00XX (a NUL
// would also end a C string, cutting the message), bytes that are not UTF-8 as \xXX; at most
// `max` bytes of output (never half a character or half an escape), then "...". The bound is on
// the output: 100 DEL bytes are 600 characters escaped. (core/text.hpp's printable escapes
// as \xNN and counts input characters: the two are kept apart because messages of each are
// pinned by tests and read by scripts.)
std::string printable(std::string_view s, size_t max = std::string::npos);

// `s` in double quotes as a message quotes a JSON string: `"` and `\` escaped, at most 60
// characters shown (then "..."), printable() otherwise.
std::string json_quoted(std::string_view s);

// Field paths. path_key("vertices[3]", "clip") is "vertices[3].clip", path_key("", "clip") is
// "clip"; path_index("vertices", 3) is "vertices[3]".
std::string path_key(const std::string& parent, std::string_view key);
std::string path_index(const std::string& parent, size_t i);

// A field path as a message shows it: printable(), and at most the first and last 100 bytes
// (never cutting a character or an escape) joined by "...". A key of 10,000 characters, or a
// value 100,000 arrays deep, would otherwise make the message any length; the start and the end
// (the field itself) stay.
std::string shown_path(const std::string& raw);

// A double for a message, in the C locale with 9 significant digits: "0.100000001", "1e+39".
std::string fmt_double(double d);

}  // namespace glrc::typed_json
