// CaseResult: the comparator's findings for one case, and what the reports are written from.
// Knows nothing of GL: the GL strings live in RunInfo, filled by whoever ran the GL side.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/case.hpp"

namespace glrc {

// The statuses of Mesa CI's result files (deqp-runner's names). pass, fail, crash, timeout,
// error and skip are what a case did; expected_fail, unexpected_pass and flake are what that
// means against the expectations (--baseline, --flakes).
enum class Status {
  pass,
  fail,
  expected_fail,
  unexpected_pass,
  skip,
  error,
  crash,
  timeout,
  flake
};
template <>
struct Names<Status> {
  static constexpr std::array<std::pair<Status, std::string_view>, 9> table{{
      {Status::pass, "Pass"},
      {Status::fail, "Fail"},
      {Status::expected_fail, "ExpectedFail"},
      {Status::unexpected_pass, "UnexpectedPass"},
      {Status::skip, "Skip"},
      {Status::error, "Error"},
      {Status::crash, "Crash"},
      {Status::timeout, "Timeout"},
      {Status::flake, "Flake"},
  }};
};
// "Pass", "Fail", "ExpectedFail", ..., "Crash", "Timeout", "Flake"
const char* to_string(Status s);
// The inverse of to_string; nullopt for anything else.
std::optional<Status> status_from_string(std::string_view s);
// Whether a status fails the run (and goes to failures.csv): Fail, Crash, Timeout, Error, and
// UnexpectedPass (the expectations need updating, as in Mesa CI).
inline bool fails_run(Status s) {
  return s == Status::fail || s == Status::crash || s == Status::timeout || s == Status::error ||
         s == Status::unexpected_pass;
}
const char* to_string(ToleranceMode m);  // "spec", "ulps", "exact"

struct WorstPixel {
  int x = 0, y = 0;
  float reference = 0, gl = 0;
  double abs_error = 0;  // |gl - reference|; +inf for NaN/Inf in GL output
  double ulps = 0;       // abs_error in ULPs of the attribute's scale
  double allowed = 0;    // the largest legal abs_error at this pixel
  double ratio = 0;      // abs_error / allowed: over 1 fails (0/0 is 0, x/0 is inf)
};

struct ChannelStats {
  std::string name;             // "depth" or "color.x"
  uint64_t compared = 0;        // pixels covered by the same primitive in both frames
  uint64_t over_tolerance = 0;  // of which over the tolerance (NaN/Inf included)
  uint64_t non_finite = 0;      // GL gave NaN or Inf where the reference is finite
  // Pixels covered by the same primitive in both whose expected value is itself NaN or Inf
  // (spec and ulps modes): the specification determines no value there, so they are not
  // judged (compare::value_determined); not counted in `compared`.
  uint64_t undetermined = 0;
  uint64_t differing = 0;  // pixels whose bits differ from the reference at all
  double max_abs = 0, max_ulps = 0, mean_ulps = 0, rms_ulps = 0, p99_ulps = 0;
  // How much of the allowance was used: abs_error / allowed, over the compared pixels.
  double max_ratio = 0, p99_ratio = 0;
  double tolerance_ulps = 0;  // ulps mode: the threshold; spec mode: the largest allowance in ULPs
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
  // Every mismatch gets one label: exact tie (the centre lies on an edge), within snapping
  // (within the band the position freedom allows), or fill-rule error (everything else).
  uint64_t exact_tie = 0, within_snapping = 0, fill_rule = 0;
  uint64_t boundary = 0;  // exact_tie + within_snapping
  // Watertightness where triangles share an edge: pixels no fragment reached although one had
  // to (gaps) and pixels reached twice (double hits). Always failures.
  uint64_t gaps = 0, double_hits = 0;
  bool fragments_checked = false;  // whether GL reported fragment counts
  // Pixels whose count differed where the edge bits excuse it (compare::count_excused): judged
  // by which triangles GL's fragments came from (core/fragment_trace.hpp), or left excused (no
  // trace from GL, too many choices, or beyond compare::kMostTracedPixels).
  uint64_t counts_traced = 0, counts_untraced = 0;
  uint64_t failures = 0;  // mismatches that count against the verdict
  enum class Label { exact_tie, within_snapping, fill_rule, gap, double_hit };
  struct Pixel {
    int x = 0, y = 0;
    int32_t reference = -1, gl = -1;
    bool boundary = false;
    Label label = Label::fill_rule;
  };
  std::vector<Pixel> mismatches;  // first few, for the report
  // Every pixel the traces failed (at most compare::kMostTracedPixels), with its label: the
  // label compare::coverage_label gives there is the excused one (the coverage picture paints
  // these instead).
  std::vector<Pixel> traced_failures;
};

template <>
struct Names<CoverageStats::Label> {
  static constexpr std::array<std::pair<CoverageStats::Label, std::string_view>, 5> table{{
      {CoverageStats::Label::exact_tie, "exact_tie"},
      {CoverageStats::Label::within_snapping, "within_snapping"},
      {CoverageStats::Label::fill_rule, "fill_rule"},
      {CoverageStats::Label::gap, "gap"},
      {CoverageStats::Label::double_hit, "double_hit"},
  }};
};

struct CaseResult {
  std::string name;
  std::string description;
  Status status = Status::error;
  // What the case did before expectations were applied: pass, fail, crash, timeout, error or
  // skip. Comparing two runs compares outcomes, whatever each run's baseline said.
  Status outcome = Status::error;
  std::string message;  // why it failed / was skipped; empty on pass
  Tolerance tolerance;
  CoverageStats coverage;
  std::vector<ChannelStats> channels;  // depth first, then each varying component
  // SHA-256 of the GL frame's bits (ref::digest): two runs with the same digest drew the very
  // same pixels, however the statistics read. Empty when GL gave no frame.
  std::string gl_digest;
  double seconds = 0;  // reference + GL + compare
};

// Run-wide facts for the reports.
struct RunInfo {
  std::string backend, driver, model;
  // Where `model` came from: "identify", "identify (cached)", "command line", "default"
  // (cli's ModelChoice); empty in results written before it was recorded.
  std::string model_source;
  std::string tolerance;  // "spec (subpixel bits 8)", "ulps" or "exact"
  int subpixel_bits = 0;  // GL_SUBPIXEL_BITS as reported
  std::string gl_vendor, gl_renderer, gl_version;
  // The Mesa install tree given with --mesa (empty: the system's), and the driver library GL
  // actually came from (libOSMesa, libEGL_mesa, ...), so nobody can mistake which Mesa ran.
  std::string mesa_prefix, gl_library;
  // What the implementation got wrong while the GL side set up (gl::GlInfo::warnings, e.g. a
  // wrong first draw), one line each. The run went on regardless.
  std::vector<std::string> gl_warnings;
  // gl_PrimitiveID came from a pass-through geometry shader (gl::GlInfo's field of that name):
  // without one the driver drew nothing when the fragment shader read it.
  bool gl_primitive_id_from_geometry_shader = false;
  int jobs = 1;
  // Sharding: this run holds every `fraction`-th case starting at `fraction_start` (1-based) of
  // `total_cases`; fraction 1 is the whole suite.
  int fraction = 1, fraction_start = 1;
  size_t total_cases = 0;
  double seconds = 0;
  // Stopped by SIGINT or SIGTERM before every case was checked: the results hold the cases that
  // finished, and `glrefcheck run --resume` completes the run.
  bool interrupted = false;
  // Everything besides GL, the model and the tolerance that changes a verdict, by name (cli's
  // verdict_inputs: "strict_coverage", "varying_ulps", "depth_ulps", "case_files" (run: the
  // SHA-256 of the suite's case names and contents), "timeout" (--timeout), and "baseline",
  // "flakes", "skips" as the SHA-256 of the file read, "" where not given): shards that differ in
  // one judged alike would merge into results no single run gives. Empty in results before it.
  std::map<std::string, std::string> verdict_inputs;
};

}  // namespace glrc
