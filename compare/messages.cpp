#include "compare/messages.hpp"

#include <cmath>
#include <cstdio>

namespace glrc::compare {

std::string format_ulps(double u) {
  if (std::isinf(u)) return "inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", u);
  return buf;
}

std::string failure_message(const CaseResult& r) {
  std::string msg;
  auto append = [&](const std::string& part) { msg += (msg.empty() ? "" : "; ") + part; };
  int listed = 0, more = 0;
  for (const auto& ch : r.channels) {
    if (ch.pass()) continue;
    if (listed == 3) {
      ++more;
      continue;
    }
    ++listed;
    std::string part = ch.name + ": ";
    if (ch.non_finite > 0) part += std::to_string(ch.non_finite) + " px NaN/Inf, ";
    if (r.tolerance.mode == ToleranceMode::exact)
      part += std::to_string(ch.differing) + " px differ (max " + format_ulps(ch.max_ulps) + " ulp";
    else if (r.tolerance.mode == ToleranceMode::spec)
      part += std::to_string(ch.over_tolerance) + " px over the allowance (max " +
              format_ulps(ch.max_ratio) + "x allowed, " + format_ulps(ch.max_ulps) + " ulp";
    else
      part += std::to_string(ch.over_tolerance) + " px over " + format_ulps(ch.tolerance_ulps) +
              " ulp (max " + format_ulps(ch.max_ulps) + " ulp";
    if (!ch.worst.empty())
      part += " at " + std::to_string(ch.worst[0].x) + "," + std::to_string(ch.worst[0].y);
    append(part + ")");
  }
  if (more > 0) append(std::to_string(more) + (more == 1 ? " more channel" : " more channels"));
  const CoverageStats& cov = r.coverage;
  if (cov.failures > 0) {
    std::string part = "coverage: " + std::to_string(cov.failures) + " px fail (";
    std::string kinds;
    // "1 gap on a shared edge", "2 gaps on shared edges".
    auto kind = [&](uint64_t n, const char* one, const char* many) {
      if (n) kinds += (kinds.empty() ? "" : ", ") + std::to_string(n) + " " + (n == 1 ? one : many);
    };
    kind(cov.fill_rule, "fill-rule error", "fill-rule errors");
    kind(cov.gaps, "gap on a shared edge", "gaps on shared edges");
    kind(cov.double_hits, "double hit on a shared edge", "double hits on shared edges");
    if (!r.tolerance.allow_boundary || r.tolerance.mode == ToleranceMode::exact) {
      kind(cov.exact_tie, "exact tie", "exact ties");
      kind(cov.within_snapping, "within snapping", "within snapping");
    }
    append(part + kinds + ")");
  }
  return msg;
}

std::string undetermined_message(const std::string& channel, const WorstPixel& p) {
  auto number = [](float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", double(v));
    return std::string(buf);
  };
  std::string why;
  if (std::isfinite(p.reference))
    why.append("the triangle reaches within rounding of the eye, where the w_c of a vertex ")
        .append("clipping makes may be 0: its values are unbounded");
  else
    why.append("the exact interpolation there is ")
        .append(number(p.reference))
        .append(": the pixel lies outside the triangle its plane comes from, beyond the plane's ")
        .append("vanishing line");
  return "outside what GL specifies: " + channel + " at " + std::to_string(p.x) + "," +
         std::to_string(p.y) + " has no value the specification determines (" + why +
         "), and GL drew " + number(p.gl) + " there; nothing else fails";
}

}  // namespace glrc::compare
