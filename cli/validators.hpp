// Option checks the subcommands share.
#pragma once

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/names.hpp"

namespace glrc::cli {

// An option taking one of enum E's names (core/names.hpp; or of `allowed` among them), stored
// in `value` as the enum. CLI11 checks the name first, so an unknown one is its usual message.
template <class E>
CLI::Option* add_enum_option(CLI::App& app, const std::string& name, E& value,
                             const std::string& help,
                             const std::vector<std::string>& allowed = names_of<E>()) {
  return app
      .add_option_function<std::string>(
          name, [&value](const std::string& s) { value = *from_name<E>(s); }, help)
      ->check(CLI::IsMember(allowed));
}

// The whole of `s` as a number (std::stod's syntax, so "nan" and "inf" too), or nothing.
inline std::optional<double> parsed_number(const std::string& s) {
  try {
    size_t used = 0;
    const double v = std::stod(s, &used);
    if (used == s.size()) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

// A finite number above `lower` (or at it, when `inclusive`): NaN would compare false everywhere
// and an infinite tolerance or factor would say nothing.
inline CLI::Validator finite_number(double lower, bool inclusive) {
  const std::string bound = fmt::format("{} {:g}", inclusive ? ">=" : ">", lower);
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        const std::optional<double> n = parsed_number(s);
        if (!n) return "expected a number, got \"" + s + "\"";
        const double v = *n;
        const bool ok = std::isfinite(v) && (inclusive ? v >= lower : v > lower);
        return ok ? "" : "expected a finite number " + bound + ", got " + s;
      },
      "NUMBER " + bound);
}

// A finite number in [lower, upper], said plainly: "expected seconds > 0, a finite number from
// 0.001 to 1000000, got nan" rather than CLI11's range message.
inline CLI::Validator finite_range(double lower, double upper) {
  const std::string range = fmt::format("from {:.10g} to {:.10g}", lower, upper);
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        const std::optional<double> n = parsed_number(s);
        if (!n) return "expected a number " + range + ", got \"" + s + "\"";
        const double v = *n;
        if (std::isfinite(v) && v >= lower && v <= upper) return "";
        return "expected a finite number " + range + ", got " + s;
      },
      "NUMBER " + range);
}

// A whole number from `lower` to 2^64 - 1, in plain digits: CLI11 reads "-1" into a uint64_t as
// 18446744073709551615 and clamps 18446744073709551616 to the largest, both silently.
inline CLI::Validator whole_u64(uint64_t lower = 0) {
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        const std::string expected =
            fmt::format("expected a whole number from {} to 18446744073709551615", lower);
        uint64_t v = 0;
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (s.empty() || ec != std::errc() || end != s.data() + s.size() || v < lower)
          return expected + ", got \"" + s + "\"";
        return "";
      },
      fmt::format("INTEGER >= {}", lower));
}

// A whole number >= lower that fits an int: CLI11's PositiveNumber says "Value 0 not in range
// 2.22507e-308 to 1.79769e+308", in as many digits as it likes.
inline CLI::Validator whole_number(int lower) {
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        const std::string expected = fmt::format("expected a whole number >= {}", lower);
        long long v = 0;
        try {
          size_t used = 0;
          v = std::stoll(s, &used);
          if (used != s.size()) return expected + ", got \"" + s + "\"";
        } catch (const std::out_of_range&) {
          return expected + " (at most " + std::to_string(INT_MAX) + "), got " + s;
        } catch (const std::exception&) {
          return expected + ", got \"" + s + "\"";
        }
        if (v < lower) return expected + ", got " + s;
        if (v > INT_MAX) return expected + " (at most " + std::to_string(INT_MAX) + "), got " + s;
        return "";
      },
      fmt::format("INT >= {}", lower));
}

}  // namespace glrc::cli
