#include "typed_json/text.hpp"

#include <algorithm>
#include <cstdio>
#include <locale>
#include <sstream>

namespace glrc::typed_json {

size_t utf8_length(std::string_view s, size_t i) {
  const auto at = [&](size_t k) { return k < s.size() ? static_cast<unsigned char>(s[k]) : 0; };
  const unsigned char c = at(i);
  const auto cont = [&](size_t k, unsigned char lo = 0x80, unsigned char hi = 0xBF) {
    return at(k) >= lo && at(k) <= hi;
  };
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return cont(i + 1) ? 2 : 0;
  if (c >= 0xE0 && c <= 0xEF) {
    const unsigned char lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    return cont(i + 1, lo, hi) && cont(i + 2) ? 3 : 0;
  }
  if (c >= 0xF0 && c <= 0xF4) {
    const unsigned char lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    return cont(i + 1, lo, hi) && cont(i + 2) && cont(i + 3) ? 4 : 0;
  }
  return 0;
}

std::string printable(std::string_view s, size_t max) {
  std::string out;
  size_t i = 0;
  while (i < s.size()) {
    const size_t n = utf8_length(s, i);
    const auto c = static_cast<unsigned char>(s[i]);
    char buf[8];
    std::string_view piece;
    if (n == 0) {
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      piece = buf;
    } else if (c == '\n') {
      piece = "\\n";
    } else if (c == '\r') {
      piece = "\\r";
    } else if (c == '\t') {
      piece = "\\t";
    } else if (c < 0x20 || c == 0x7F) {
      std::snprintf(buf, sizeof buf, "\\u%04X", c);
      piece = buf;
    } else {
      piece = s.substr(i, n);
    }
    if (out.size() + piece.size() > max) break;
    out.append(piece);
    i += std::max<size_t>(n, 1);
  }
  if (i < s.size()) out += "...";
  return out;
}

std::string json_quoted(std::string_view s) {
  constexpr size_t kMax = 60;  // keep messages one readable line
  std::string escaped;
  for (const char ch : s.substr(0, 4 * kMax)) {  // enough for kMax characters shown
    if (ch == '"' || ch == '\\') escaped += '\\';
    escaped += ch;
  }
  std::string shown = printable(escaped, kMax);
  if (s.size() > 4 * kMax && !shown.ends_with("...")) shown += "...";
  return "\"" + shown + "\"";
}

std::string path_key(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

std::string path_index(const std::string& parent, size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

std::string shown_path(const std::string& raw) {
  constexpr size_t kKeep = 100;
  // Cut as shown, escapes and all: a key of DEL bytes is six times as long on screen.
  const std::string path = printable(raw);
  if (path.size() <= 2 * kKeep) return path;
  size_t head = kKeep, tail = path.size() - kKeep;
  const auto inside_character = [&](size_t i) {
    return (static_cast<unsigned char>(path[i]) & 0xC0) == 0x80;
  };
  while (head > 0 && inside_character(head))
    --head;
  while (tail < path.size() && inside_character(tail))
    ++tail;
  // Nor half an escape (\u007F, \xFF, \n): a backslash close before a cut starts one.
  if (const size_t b = path.rfind('\\', head); b != std::string::npos && head - b < 6) head = b;
  if (const size_t b = path.rfind('\\', tail); b != std::string::npos && tail - b < 6 && b > head)
    tail = b;
  return path.substr(0, head) + "..." + path.substr(tail);
}

std::string fmt_double(double d) {
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os.precision(9);
  os << d;
  return os.str();
}

}  // namespace glrc::typed_json
