#include "export/shader_test_text.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "core/text.hpp"

namespace glrc::reproducer {
namespace {

bool same_bits(float a, float b) {
  return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

}  // namespace

std::string decimal(float v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v < 0 ? "-inf" : "inf";
  char text[64];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  if (ec == std::errc()) {
    std::string s(text, end);
    if (same_bits(float(std::strtod(s.c_str(), nullptr)), v)) return s;
  }
  std::snprintf(text, sizeof text, "%.9g", double(v));
  if (same_bits(float(std::strtod(text, nullptr)), v)) return text;
  std::snprintf(text, sizeof text, "%.17g", double(v));
  return text;
}

std::string glsl_float(float v) {
  char text[64];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  if (ec != std::errc()) throw std::logic_error("glsl_float: to_chars failed");
  std::string s(text, end);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

const char* glsl_type(int size) {
  static const char* const kTypes[] = {"float", "vec2", "vec3", "vec4"};
  return kTypes[std::clamp(size, 1, 4) - 1];
}

std::string_view glsl_qualifier(Interpolation i) {
  return name_of(i);
}

std::string one_line(std::string_view text) {
  std::string t;
  for (const char ch : text)
    t += static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f ? ' ' : ch;
  return t;
}

std::string comment_lines(std::string_view text, size_t width) {
  return wrap_words(one_line(text), width, "# ");
}

std::string glsl_comment(std::string_view text) {
  std::string t;
  for (const char ch : text)
    t += ch >= 0x20 && ch < 0x7f ? ch : '?';
  return t;
}

std::string with_commas(size_t n) {
  const std::string digits = std::to_string(n);
  std::string s;
  for (size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) s += ',';
    s += digits[k];
  }
  return s;
}

}  // namespace glrc::reproducer
