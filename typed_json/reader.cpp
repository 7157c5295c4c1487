#include "typed_json/reader.hpp"

#include <locale.h>
#include <cctype>
#include <cerrno>
#include <cstdlib>

namespace glrc::typed_json {
namespace {

// Strings holding numbers are parsed in the C locale, whatever the process's locale is.
float parse_float_c_locale(const char* s, char** end) {
  static const locale_t c_locale = newlocale(LC_ALL_MASK, "C", locale_t(0));
  return strtof_l(s, end, c_locale);
}

}  // namespace

void Reader::fail(const std::string& path, const std::string& expected,
                  const std::string& got) const {
  std::string msg = source_;
  if (!msg.empty()) msg += ": ";
  if (!path.empty()) msg += shown_path(path) + ": ";
  msg += "expected " + expected;
  if (!got.empty()) msg += ", got " + got;
  // One line, always, whatever a file name or a key holds.
  raise_(printable(msg));
  // `raise` must throw; should one return, this still never goes on with a bad value.
  throw Error(printable(msg));
}

float Reader::float32_from_text(const std::string& s, const std::string& path) const {
  const char* begin = s.c_str();
  char* end = nullptr;
  if (s.empty() || std::isspace(static_cast<unsigned char>(s[0])))
    fail(path, "a number or a string holding a C99 hex float or decimal", json_quoted(s));
  errno = 0;
  const float f = parse_float_c_locale(begin, &end);
  if (end != begin + s.size())
    fail(path, "a number or a string holding a C99 hex float or decimal", json_quoted(s));
  // ERANGE also flags an underflow to a subnormal or zero, which is the float it should be.
  if (!std::isfinite(f)) fail(path, "a finite float32 value", json_quoted(s));
  return f;
}

}  // namespace glrc::typed_json
