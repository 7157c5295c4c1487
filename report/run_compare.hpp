// Two runs side by side (`glrefcheck compare BASE CURRENT`): which cases regressed, which were
// fixed, which were added or removed, and where the error against the reference grew by more
// than a factor even though the case still passes. Knows nothing of GL: it reads results.
//
// One interface, one file per part: the classification (compare_runs, run_compare.cpp) and its
// views, each a pure function of a RunComparison: text (comparison_text.cpp), Markdown
// (comparison_markdown.cpp), JSON (comparison_json.cpp) and HTML (write_comparison_html,
// html.hpp). The text and Markdown views share their sections (comparison_sections.hpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "report/report.hpp"

namespace glrc::report {

// One channel (depth, color.x, ...) present in both runs with compared pixels in both.
struct ChannelChange {
  std::string channel;
  // The error against the reference in ULPs of the attribute's scale (ChannelStats::max_ulps,
  // p99_ulps), and the share of the allowance used (max_ratio), in each run.
  double base_max_ulps = 0, current_max_ulps = 0;
  double base_p99_ulps = 0, current_p99_ulps = 0;
  double base_max_ratio = 0, current_max_ratio = 0;
  // current > factor * max(base, min_ulps): grown beyond the factor (NaN counts as grown).
  bool max_grew = false, p99_grew = false;
};

struct CaseChange {
  enum class Kind {
    regression,  // passed in base, fails now (Fail, Crash, Timeout, Error); or failed and now
                 // crashes or times out (the case is no longer checked at all)
    fix,         // failed in base, passes now
    changed,     // failed in both, in different ways (e.g. Crash -> Fail)
    added,       // only in current
    removed,     // only in base
    skipped,     // skipped in one run or both
    precision,   // same outcome, but the error grew beyond the factor on some channel
    unchanged,
  };
  std::string name;
  Kind kind = Kind::unchanged;
  // Outcomes (CaseResult::outcome: what the case did, whatever each run's baseline expected);
  // nullopt where the case is absent from that run.
  std::optional<Status> base, current;
  std::string message;  // current's message (base's for removed cases)
  // Whether GL drew the very same bits in both runs (CaseResult::gl_digest); nullopt when a
  // run has no frame digest for it (a crash, or a results.json from before digests).
  std::optional<bool> same_bits;
  std::vector<ChannelChange> channels;  // every channel compared in both runs
};
const char* to_string(CaseChange::Kind k);  // "regression", "fix", ...

struct RunComparison {
  RunInfo base, current;
  double factor = 2;    // precision growth that is flagged
  double min_ulps = 1;  // errors below this many ULPs are rounding noise, not a base to grow from
  // Every case of either run: current's order, then the cases only base has.
  std::vector<CaseChange> cases;
  size_t count(CaseChange::Kind k) const;
  // Cases whose frames were compared bit for bit, and of those, the ones with identical bits.
  size_t bits_compared() const;
  size_t bits_identical() const;
  bool has_regression() const { return count(CaseChange::Kind::regression) > 0; }
  // A side that did not check its whole suite (or shard of it), one line each ("current:
  // interrupted after 79 of 320 cases"): its missing cases show as removed or added, which no
  // driver change explains. Empty when both are complete, or say nothing of their size.
  std::vector<std::string> incomplete;
};

RunComparison compare_runs(const RunResults& base, const RunResults& current, double factor = 2,
                           double min_ulps = 1);

// "GL frames: all 45 bit-identical to base", or how many differ in their bits; one line, no
// newline, that every view prints.
std::string bits_summary(const RunComparison& c);

// The terminal text (comparison_text.cpp): both GL_VERSIONs, counts, then the regressions,
// fixes, changes, added/removed cases and precision changes in a table (unchanged cases are
// counted only). Lines end in '\n'.
std::string comparison_text(const RunComparison& c);
// The same for CI comments (GitLab/GitHub Markdown; comparison_markdown.cpp): `|` in cells
// escaped, line breaks in cells replaced by spaces.
std::string comparison_markdown(const RunComparison& c);
// Everything, for scripts (comparison_json.cpp): {"base": run, "current": run, "factor",
// "min_ulps", "summary": counts by kind, "regressions", "bits_compared", "bits_identical",
// "cases": [...]} (non-finite numbers as "nan"/"inf" strings, as in results.json; bad UTF-8 in
// names and messages replaced, never thrown).
std::string comparison_json(const RunComparison& c);

}  // namespace glrc::report
