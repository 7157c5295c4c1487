// The selftest loop: every case is checked without a fault (it must pass, or fail only as the
// baseline expects), then each fault of faults.hpp is planted on the GL side of every case that
// passed clean, and the check must fail it. A fault that changes no bit of a case cannot be
// caught there and is counted as not applicable, not as missed.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "check/check.hpp"
#include "core/case.hpp"
#include "core/result.hpp"
#include "gl_harness/gl_harness.hpp"
#include "report/expectations.hpp"

namespace glrc::selftest {

struct FaultRow {
  std::string name, description;
  int changed = 0;      // cases whose GL bits the fault changed
  int caught = 0;       // of those, the cases that fail
  int errors = 0;       // cases GL could not draw with the fault planted
  std::string example;  // the first catching case and why
};

struct SelftestResult {
  size_t cases = 0;
  size_t passed_clean = 0;    // cases that pass without a fault: the ones faults are tried on
  int expected_failures = 0;  // clean failures the baseline lists
  // Cases GL cannot draw for a feature it lacks (gl::FeatureMissing: `run` skips them too).
  size_t skipped = 0;
  std::vector<CaseResult> clean_failures;  // the others, which make the selftest fail
  std::vector<FaultRow> faults;            // in faults()'s order
  int missed() const;                      // faults no case caught
  bool ok() const { return missed() == 0 && clean_failures.empty(); }
};

// What the loop reports as it goes: `step(k, n, what)` before each check (for a progress line),
// `clean_failure(r)` as each unexpected clean failure is found. Either may be empty.
struct SelftestProgress {
  std::function<void(size_t k, size_t n, const std::string& what)> step;
  std::function<void(const CaseResult& r)> clean_failure;
};

// Runs the loop on `renderer`, every case judged by `o` (one model for clean and faulted runs).
SelftestResult run_selftest(const std::vector<Case>& cases, gl::Renderer& renderer,
                            const check::CheckOptions& o, const report::Baseline& baseline,
                            const SelftestProgress& progress = {});

}  // namespace glrc::selftest
