// Option checks the subcommands share.
#pragma once

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace glrc::cli {

// A finite number above `lower` (or at it, when `inclusive`): NaN would compare false everywhere
// and an infinite tolerance or factor would say nothing.
inline CLI::Validator finite_number(double lower, bool inclusive) {
  const std::string bound = fmt::format("{} {:g}", inclusive ? ">=" : ">", lower);
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        double v = 0;
        try {
          size_t used = 0;
          v = std::stod(s, &used);
          if (used != s.size()) return "expected a number, got \"" + s + "\"";
        } catch (const std::exception&) {
          return "expected a number, got \"" + s + "\"";
        }
        const bool ok = std::isfinite(v) && (inclusive ? v >= lower : v > lower);
        return ok ? "" : "expected a finite number " + bound + ", got " + s;
      },
      "NUMBER " + bound);
}

}  // namespace glrc::cli
