#include "typed_json/document.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace glrc::typed_json {
namespace {

// Where byte `offset` of `text` is, as JSON parsers say it: "line L, column C" (1-based).
std::string line_and_column(std::string_view text, size_t offset) {
  const std::string_view before = text.substr(0, offset);
  const size_t line = size_t(std::count(before.begin(), before.end(), '\n')) + 1;
  const size_t start = before.rfind('\n');
  const size_t column = offset - (start == std::string_view::npos ? 0 : start + 1) + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

}  // namespace

// Bytes no JSON text may hold, found before parsing so that the message says what and where:
// nlohmann-json takes a NUL for the end of the input (silently ignoring what follows), and its
// message for a byte that is not UTF-8 gives no offset.
void check_bytes(const Reader& r, std::string_view text) {
  for (size_t i = 0; i < text.size();) {
    // Eight ASCII bytes without a NUL at a time: a 50 MB case is mostly that.
    if (i + 8 <= text.size()) {
      uint64_t w;
      std::memcpy(&w, text.data() + i, 8);
      constexpr uint64_t kHigh = 0x8080808080808080ull, kLow = 0x0101010101010101ull;
      if ((w & kHigh) == 0 && ((w - kLow) & ~w & kHigh) == 0) {
        i += 8;
        continue;
      }
    }
    if (text[i] == '\0')
      r.fail(line_and_column(text, i), "a JSON text without NUL bytes",
             "a NUL byte at offset " + std::to_string(i));
    if (static_cast<unsigned char>(text[i]) < 0x80) {
      ++i;
      continue;
    }
    const size_t n = utf8_length(text, i);
    if (n == 0) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[i]));
      r.fail(
          line_and_column(text, i), "UTF-8 text",
          std::string("the byte ") + byte + ", which is not UTF-8, at offset " + std::to_string(i));
    }
    i += n;
  }
}

void fail_parse(const Reader& r, const ParseError& e, const NumberExpectation& expected_number) {
  if (e.id == 406) {
    // "number overflow parsing '1e400'": a number beyond double range, in the field the
    // builder's path names.
    r.fail(e.path,
           expected_number ? expected_number(e.path) : "a number within the range of a double",
           printable(e.last_token, 80) + " (beyond the range of a double)");
  }
  // nlohmann-json's message, without its "[json.exception...] parse error at line L, column C: "
  // prefix (the line and column become the field) and with the text it quotes cut short: a
  // malformed 50 MB line would otherwise be quoted whole.
  std::string msg = e.message;
  std::string where;
  const size_t at = msg.find("at line ");
  if (at != std::string::npos) {
    const size_t colon = msg.find(": ", at);
    where = msg.substr(at + 3, colon == std::string::npos ? std::string::npos : colon - at - 3);
    msg = colon == std::string::npos ? "" : msg.substr(colon + 2);
  } else if (const size_t close = msg.find("] "); close != std::string::npos) {
    msg = msg.substr(close + 2);
  }
  constexpr size_t kQuoted = 80;
  if (e.last_token.size() > kQuoted) {
    const std::string quoted = "'" + e.last_token + "'";
    if (const size_t q = msg.find(quoted); q != std::string::npos)
      msg.replace(q, quoted.size(), "'" + printable(e.last_token, kQuoted) + "'");
  }
  r.fail(where, "valid JSON", msg);
}

}  // namespace glrc::typed_json
