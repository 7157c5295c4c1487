// Number formatting shared by the text and file reports, so a value reads the same everywhere.
#pragma once

#include <string>

namespace glrc::report {

// An error in ULPs: "3.1", "64", "0.012", "1.23e+05", "NaN", "inf".
std::string ulps_text(double ulps);
// A share of the allowance (error / allowed): "0.012", "0.31", "2.5", "1.2e+03", "inf".
std::string ratio_text(double ratio);
// A float value exactly enough to reproduce it (%.9g): "0.333333343", "nan", "-inf".
std::string float_text(double value);
// A duration: "0.012 s".
std::string seconds_text(double seconds);

}  // namespace glrc::report
