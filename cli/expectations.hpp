// Expected results, in Mesa CI's format: a *-fails.txt file of `case,Status` lines, `#`
// comments and blank lines ignored (the evidence for each entry goes in the comment above it).
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "core/result.hpp"

namespace glrc::cli {

struct Baseline {
  std::map<std::string, std::string> expected;  // case name -> status as written ("Fail")
};

// Throws std::runtime_error with "<file>:<line>: expected `case,Status`, got ..." on bad input
// (statuses: Fail, Crash, Timeout, Error).
Baseline read_baseline(const std::filesystem::path& file);

// Applies the baseline to a result: a listed case with the listed status becomes ExpectedFail, a
// listed case that passes UnexpectedPass (the list needs updating, as in Mesa CI); one that fails
// with another status keeps it, with the expectation in its message.
void apply(const Baseline& b, CaseResult& r);

// Whether a status fails the run.
bool fails_run(Status s);

}  // namespace glrc::cli
