// Shrinking a failing case to a small one that fails the same way: fewer triangles, varyings
// and components, a smaller framebuffer and viewport, simpler float32 numbers, each step kept
// only if a check of the smaller case still shows the same failure (class and signature,
// failure.hpp) on the same implementation. Greedy, deterministic and bounded: every kept step
// makes the case strictly smaller or simpler (so it ends), and it stops at a time or check
// budget with the smallest case found so far.
#pragma once

#include <functional>
#include <vector>

#include "campaign/failure.hpp"
#include "core/case.hpp"
#include "core/result.hpp"

namespace glrc::campaign {

// Checks candidates and returns one result per candidate, in order. It may check them in
// parallel (a campaign's workers do); a candidate it could not check should come back as a
// result that shows no failure (a pass), never as the target failure.
using Judge = std::function<std::vector<CaseResult>(const std::vector<Case>& candidates)>;

struct ShrinkOptions {
  double seconds = 60;  // wall-clock budget, checked between batches
  int max_checks = 5000;
  // Candidates handed to the judge at once (about twice its parallelism): the first of them,
  // in order, that still fails is taken, so the outcome does not depend on this number's
  // effect on timing, only on which candidates are tried.
  size_t batch = 4;
  // Stop now (an interrupt), with the smallest case so far; checked between batches.
  std::function<bool()> stop;
};

struct Shrunk {
  Case minimal;       // the smallest failing case found (the input when nothing smaller failed)
  CaseResult result;  // its check
  int steps = 0;      // smaller cases kept
  int checks = 0;     // candidates checked
  double seconds = 0;
  bool complete = false;  // no candidate left that could shrink it further (not out of budget)
};

// Shrinks `failing`, which the judge saw fail with `target` (one of failures_of(failing, r)),
// starting from its result `failing_result`. The order of the passes: triangles (halves,
// quarters, ..., one at a time), vertices no triangle uses (dropped without a check),
// varyings, components, GL's default for each state (cull, front face, provoking vertex, depth
// function, depth range), the framebuffer and viewport, then numbers (every clip coordinate and
// value towards 0, integers, pixel centres and fewer mantissa bits), repeated until none makes
// progress.
Shrunk shrink(const Case& failing, const CaseResult& failing_result, const Failure& target,
              const Judge& judge, const ShrinkOptions& options = {});

// Whether `r` of case `c` still shows `target`.
bool shows(const Case& c, const CaseResult& r, const Failure& target);

// How complicated a float32 is to read: 0 for 0, then integers before fractions, fewer
// significant mantissa bits and smaller exponents first. Shrinking replaces a number only by one
// of strictly smaller complexity.
int complexity(float x);

}  // namespace glrc::campaign
