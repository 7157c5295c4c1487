// A shader_test's text: numbers written so that shader_runner and Mesa's GLSL lexer read back the
// same float32 (shader_test.hpp says why), and comments in the characters each part allows.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "core/case.hpp"

namespace glrc::reproducer {

// Text assembled by appending (GCC 12 at -O3 reports a false -Wrestrict in operator+ on a
// string literal and a std::string).
template <typename... Parts>
std::string cat(const Parts&... parts) {
  std::string s;
  (s.append(std::string_view(parts)), ...);
  return s;
}

// A decimal that shader_runner's parsers give back as `v` exactly: they call strtod and cast to
// float (strtof_hex for vertex data and probes), a double rounding that the shortest decimal can
// miss when it lies within 2^-53 of a midpoint between floats; each candidate is read back the
// same way, and "%.17g" of the float's double, which strtod reads exactly, always works. NaN and
// Inf as "nan", "inf", "-inf".
std::string decimal(float v);

// A GLSL float literal of the finite float `v`: the shortest decimal strtof gives back (Mesa's
// GLSL lexer reads float literals with strtof), with a '.' or an exponent so that it is a float
// ("1.0", "-0.0", not the int literals "1" and "-0").
std::string glsl_float(float v);

// The GLSL type of a varying of `size` components: float, vec2, vec3, vec4.
const char* glsl_type(int size);

// A case file's qualifier names are GLSL's (core/case.hpp's Names<Interpolation>).
std::string_view glsl_qualifier(Interpolation i);

// `text` on one line: control characters as spaces.
std::string one_line(std::string_view text);

// `text` as "# " comment lines of at most `width` characters, broken at spaces; control
// characters become spaces.
std::string comment_lines(std::string_view text, size_t width = 96);

// `text` for a GLSL comment: printable ASCII only (GLSL's character set), others as '?'.
std::string glsl_comment(std::string_view text);

// n with a comma every three digits: 262,144.
std::string with_commas(size_t n);

}  // namespace glrc::reproducer
