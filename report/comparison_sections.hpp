// Internal to report: the pieces the text and Markdown views of a RunComparison share (and the
// JSON view's order of kinds), so that both list the same cases under the same headings with
// the same numbers. Each returns plain text; the views add their own markup around it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "report/run_compare.hpp"

namespace glrc::report::sections {

// The order of the counts and of the reports' sections: what needs attention first.
inline constexpr CaseChange::Kind kKinds[] = {
    CaseChange::Kind::regression, CaseChange::Kind::fix,      CaseChange::Kind::changed,
    CaseChange::Kind::added,      CaseChange::Kind::removed,  CaseChange::Kind::skipped,
    CaseChange::Kind::precision,  CaseChange::Kind::unchanged};

// A status's name ("Pass", "Crash"), or "-" where the case is absent from that run.
std::string status_text(const std::optional<Status>& s);

// "12 cases: 1 regression, 0 fixes, 0 changed, ...": every kind of kKinds, in that order.
std::string counts_line(const RunComparison& c);

// A section's heading: its count, and what the kind means where the name alone does not say,
// e.g. "2 added (only in current)".
std::string section_title(const RunComparison& c, CaseChange::Kind k);

// What a precision change is, under that section's title (the comparison's factor and
// min_ulps).
std::string precision_note(const RunComparison& c);

// "" when both runs used the same tolerance and model; else one line warning that statuses may
// differ for that reason alone.
std::string setup_note(const RunComparison& c);

// "1.5 -> 6 ulp (x4)": an error in ULPs in each run and its growth against max(base, min_ulps).
std::string ulps_change(double base, double current, double min_ulps);

// Whether a case of kind k is listed with its two statuses (regression ... skipped) rather than
// with its grown channels (precision); unchanged cases are not listed at all.
bool changes_status(CaseChange::Kind k);

// Whether the views list a case: any kind but unchanged, except a case skipped in both runs,
// which says nothing about either and is only counted.
bool listed(const CaseChange& c);

// The listed cases of kind k, in the comparison's order (pointers into c.cases).
std::vector<const CaseChange*> listed_of(const RunComparison& c, CaseChange::Kind k);

// "3 skipped in both runs", or "" when there is none.
std::string skipped_in_both_note(const RunComparison& c);

// No case is listed: the views then say "no change".
bool no_change(const RunComparison& c);

// Unchanged cases whose frames differ in their bits (same_bits == false): not a finding by the
// factor, but worth a look. Pointers into c.cases.
std::vector<const CaseChange*> bits_changed(const RunComparison& c);

// The channel whose max error changed most: "color.x max 1.5 -> 2 ulp (x1.3)", or
// "coverage only" for a case with no channel compared in both runs.
std::string worst_change(const CaseChange& cc, double min_ulps);

}  // namespace glrc::report::sections
