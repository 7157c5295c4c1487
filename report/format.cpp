#include "report/format.hpp"

#include <cmath>

#include <fmt/format.h>

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

}  // namespace glrc::report
