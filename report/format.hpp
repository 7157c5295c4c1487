// Number and message formatting shared by the text and file reports, so a value reads the same
// everywhere.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace glrc::report {

// An error in ULPs: "3.1", "64", "0.012", "1.23e+05", "NaN", "inf".
std::string ulps_text(double ulps);
// A share of the allowance (error / allowed): "0.012", "0.31", "2.5", "1.2e+03", "inf".
std::string ratio_text(double ratio);
// A float value exactly enough to reproduce it (%.9g): "0.333333343", "nan", "-inf".
std::string float_text(double value);
// A duration: "0.012 s".
std::string seconds_text(double seconds);

// A count with its noun in the right number: count_text(1, "case", "cases") is "1 case",
// count_text(2, ...) "2 cases", count_text(0, ...) "0 cases".
std::string count_text(uint64_t n, std::string_view one, std::string_view many);

// A message in a listing: its first line, cut to `max_chars` with "..." (the whole message is in
// results.json).
std::string short_message(const std::string& message, size_t max_chars = 100);

// A number in a JSON report. JSON has no NaN or infinity, and nlohmann would write them as null,
// which reads back as "missing" rather than as the very finding (GL gave NaN) the report is
// about. So a non-finite number is the string "nan", "inf" or "-inf"; every finite one stays a
// number, and a reader must accept either in any numeric field. Frame values are float32:
// widening to double is exact and nlohmann prints doubles with round-trip precision, so floats
// read back bit for bit.
nlohmann::json json_number(double v);

// Text for XML and HTML content and attribute values: markup characters as references,
// newlines as &#10; (so attribute values keep them), other control characters as '?'. Case
// names, messages and GL strings come from files and drivers: any of them may hold markup.
std::string xml_escaped(std::string_view s);

}  // namespace glrc::report
