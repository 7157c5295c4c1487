#include "report/format.hpp"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace glrc::report {

std::string ulps_text(double ulps) {
  if (std::isnan(ulps)) return "NaN";
  if (std::isinf(ulps)) return ulps > 0 ? "inf" : "-inf";
  // One decimal reads well near the tolerances (tens of ulps); far beyond them only the
  // magnitude matters. Whole numbers (tolerances, small integer errors) print without one.
  const double magnitude = std::fabs(ulps);
  if (magnitude >= 1e5) return fmt::format("{:.3g}", ulps);
  if (magnitude >= 100 || ulps == std::floor(ulps)) return fmt::format("{:.0f}", ulps);
  if (magnitude < 0.1) return fmt::format("{:.2g}", ulps);
  return fmt::format("{:.1f}", ulps);
}

std::string ratio_text(double ratio) {
  if (std::isnan(ratio)) return "NaN";
  if (std::isinf(ratio)) return "inf";
  if (ratio == 0) return "0";
  return fmt::format("{:.2g}", ratio);
}

std::string float_text(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  // Nine significant digits identify every float32 uniquely.
  return fmt::format("{:.9g}", value);
}

std::string seconds_text(double seconds) {
  return fmt::format("{:.3f} s", seconds);
}

std::string count_text(uint64_t n, std::string_view one, std::string_view many) {
  return std::to_string(n) + " " + std::string(n == 1 ? one : many);
}

std::string short_message(const std::string& message, size_t max_chars) {
  std::string line = message.substr(0, message.find('\n'));
  if (line.size() > max_chars) line = line.substr(0, max_chars - 3) + "...";
  return line;
}

nlohmann::json json_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

// Escapes text for XML 1.0 content and attribute values. Control characters other than tab,
// newline and carriage return are not allowed in XML 1.0 at all, even as references, so they
// become '?'. Newlines are written as references so that attribute values keep them.
std::string xml_escaped(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char ch : s) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      case '\n':
        out += "&#10;";
        break;
      case '\r':
        out += "&#13;";
        break;
      case '\t':
        out += "&#9;";
        break;
      default:
        out += (static_cast<unsigned char>(ch) < 0x20) ? '?' : ch;
    }
  }
  return out;
}

}  // namespace glrc::report
