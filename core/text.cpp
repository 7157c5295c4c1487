#include "core/text.hpp"

#include <cstdint>
#include <string>

namespace glrc {

bool is_utf8(std::string_view s) {
  size_t k = 0;
  while (k < s.size()) {
    const auto c = static_cast<unsigned char>(s[k]);
    size_t n = 0;
    uint32_t cp = 0;
    if (c < 0x80) {
      ++k;
      continue;
    } else if (c >= 0xC2 && c <= 0xDF) {
      n = 1, cp = c & 0x1F;
    } else if (c >= 0xE0 && c <= 0xEF) {
      n = 2, cp = c & 0x0F;
    } else if (c >= 0xF0 && c <= 0xF4) {
      n = 3, cp = c & 0x07;
    } else {
      return false;
    }
    for (size_t j = 1; j <= n; ++j) {
      if (k + j >= s.size()) return false;
      const auto d = static_cast<unsigned char>(s[k + j]);
      if ((d & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (d & 0x3F);
    }
    // Overlong forms, UTF-16 surrogates and code points past U+10FFFF are not UTF-8.
    if ((n == 2 && cp < 0x800) || (n == 3 && (cp < 0x10000 || cp > 0x10FFFF)) ||
        (cp >= 0xD800 && cp <= 0xDFFF))
      return false;
    k += n + 1;
  }
  return true;
}

std::string printable(std::string_view s, size_t max) {
  std::string out;
  for (size_t k = 0; k < s.size();) {
    if (k >= max) return out + "... (" + std::to_string(s.size()) + " bytes)";
    const auto c = static_cast<unsigned char>(s[k]);
    // The longest valid UTF-8 sequence starting here, if any, is kept as it is.
    size_t len = c < 0x80 ? 1 : c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : 2;
    if (c >= 0x80 && k + len <= s.size() && is_utf8(s.substr(k, len))) {
      out.append(s.substr(k, len));
      k += len;
      continue;
    }
    static constexpr char kHex[] = "0123456789abcdef";
    if (c < 0x20 || c == 0x7F || c >= 0x80)
      out += {'\\', 'x', kHex[c >> 4], kHex[c & 15]};
    else
      out += char(c);
    ++k;
  }
  return out;
}

std::string wrap_words(std::string_view text, size_t width, std::string_view prefix) {
  std::string out, line;
  auto flush = [&] {
    out.append(prefix).append(line).append("\n");
    line.clear();
  };
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(' ', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view word = text.substr(start, end - start);
    if (!line.empty() && line.size() + 1 + word.size() > width) flush();
    if (!word.empty()) {
      if (!line.empty()) line += ' ';
      line.append(word);
    }
    start = end + 1;
  }
  if (!line.empty()) flush();
  return out;
}

std::string shell_word(std::string_view s) {
  std::string word = s.starts_with("-") ? "./" + std::string(s) : std::string(s);
  const bool plain = !word.empty() && word.find_first_not_of(
                                          "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789._/+-,=:@%") == std::string::npos;
  if (plain) return word;
  std::string q = "'";
  for (char ch : word)
    q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

std::string file_kind(const std::filesystem::file_status& st) {
  namespace fs = std::filesystem;
  switch (st.type()) {
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::not_found:
      return "a broken symbolic link";
    default:
      return "something other than a regular file";
  }
}

std::string file_kind(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, ec))) return "no such file";
  return file_kind(std::filesystem::status(path, ec));
}

}  // namespace glrc
