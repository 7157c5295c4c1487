// The comparator's one-line messages (internal to compare/): why a case failed, and why one
// whose only trouble lies where the specification determines no value is skipped.
#pragma once

#include <string>

#include "core/result.hpp"

namespace glrc::compare {

// A number of ULPs as the messages print it (3 significant digits, "inf").
std::string format_ulps(double u);
// Why a case failed, in one line: the first failing channels and the coverage failures.
std::string failure_message(const CaseResult& r);
// Why a case whose only trouble is a NaN or Inf where no value is determined is skipped.
std::string undetermined_message(const std::string& channel, const WorstPixel& p);

}  // namespace glrc::compare
