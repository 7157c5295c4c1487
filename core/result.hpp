// CaseResult: the comparator's findings for one case, and what the reports are written from.
// Knows nothing of GL: the GL strings live in RunInfo, filled by whoever ran the GL side.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/case.hpp"

namespace glrc {

enum class Status { pass, fail, expected_fail, unexpected_pass, skip, error };
const char* to_string(Status s);

struct WorstPixel {
  int x = 0, y = 0;
  float reference = 0, gl = 0;
  double abs_error = 0;  // |gl - reference|; +inf for NaN/Inf in GL output
  double ulps = 0;       // abs_error in ULPs of the attribute's scale
};

struct ChannelStats {
  std::string name;             // "depth" or "color.x"
  uint64_t compared = 0;        // pixels covered by the same primitive in both frames
  uint64_t over_tolerance = 0;  // of which over the tolerance (NaN/Inf included)
  uint64_t non_finite = 0;      // GL gave NaN or Inf where the reference is finite
  double max_abs = 0, max_ulps = 0, mean_ulps = 0, rms_ulps = 0, p99_ulps = 0;
  double tolerance_ulps = 0;
  std::vector<WorstPixel> worst;  // largest errors first
  // NaN or Inf never passes, whatever the tolerance (even an infinite one).
  bool pass() const { return over_tolerance == 0 && non_finite == 0; }
};

struct CoverageStats {
  uint64_t both = 0;             // covered by the same primitive in both
  uint64_t neither = 0;          // covered by none in both
  uint64_t reference_only = 0;   // reference covers, GL does not
  uint64_t gl_only = 0;          // GL covers, reference does not
  uint64_t other_primitive = 0;  // both cover, with different primitives
  uint64_t boundary = 0;         // mismatches whose centre is within a subpixel step of an edge
  uint64_t failures = 0;         // mismatches that count against the verdict
  struct Pixel {
    int x = 0, y = 0;
    int32_t reference = -1, gl = -1;
    bool boundary = false;
  };
  std::vector<Pixel> mismatches;  // first few, for the report
};

struct CaseResult {
  std::string name;
  std::string description;
  Status status = Status::error;
  std::string message;  // why it failed / was skipped; empty on pass
  Tolerance tolerance;
  CoverageStats coverage;
  std::vector<ChannelStats> channels;  // depth first, then each varying component
  double seconds = 0;                  // reference + GL + compare
};

// Run-wide facts for the reports.
struct RunInfo {
  std::string backend, driver, model;
  std::string gl_vendor, gl_renderer, gl_version;
  double seconds = 0;
};

}  // namespace glrc
