// The pieces the text and Markdown views of a RunComparison share (comparison_sections.hpp).
#include "report/comparison_sections.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report/format.hpp"

namespace glrc::report::sections {
namespace {

using Kind = CaseChange::Kind;

// A count with its noun, singular or plural: "1 regression", "3 fixes", "0 changed".
std::string counted(size_t n, Kind k) {
  switch (k) {
    case Kind::regression:
      return fmt::format("{} regression{}", n, n == 1 ? "" : "s");
    case Kind::fix:
      return fmt::format("{} fix{}", n, n == 1 ? "" : "es");
    case Kind::precision:
      return fmt::format("{} precision change{}", n, n == 1 ? "" : "s");
    default:
      return fmt::format("{} {}", n, to_string(k));
  }
}

// How far the error grew, against the base the factor is applied to: "x6", "x2.5", "xinf".
std::string growth_text(double base, double current, double min_ulps) {
  // fmt, not "x" + string: GCC 12 at -O3 reports a false -Wrestrict inside operator+.
  return fmt::format("x{}", ratio_text(current / std::max(base, min_ulps)));
}

// A case skipped in both runs says nothing about either: it is counted, not listed, and is no
// change.
bool skipped_in_both(const CaseChange& c) {
  return c.kind == Kind::skipped && c.base == Status::skip && c.current == Status::skip;
}

}  // namespace

std::string status_text(const std::optional<Status>& s) {
  return s ? to_string(*s) : "-";
}

std::string counts_line(const RunComparison& c) {
  std::string line = count_text(c.cases.size(), "case", "cases") + ": ";
  for (size_t k = 0; k < std::size(kKinds); ++k)
    line += (k ? ", " : "") + counted(c.count(kKinds[k]), kKinds[k]);
  return line;
}

std::string ulps_change(double base, double current, double min_ulps) {
  return fmt::format("{} -> {} ulp ({})", ulps_text(base), ulps_text(current),
                     growth_text(base, current, min_ulps));
}

// What a precision change is, under the section's title.
std::string precision_note(const RunComparison& c) {
  return fmt::format(
      "max or p99 error now over x{} of max(base, {} ulp); allowance used: max error / allowed",
      ratio_text(c.factor), ulps_text(c.min_ulps));
}

// Statuses from different tolerances (or expectation models) differ for that reason alone.
std::string setup_note(const RunComparison& c) {
  if (c.base.tolerance == c.current.tolerance && c.base.model == c.current.model) return "";
  return "note: the runs used different tolerances or models; a status may change for that alone";
}

bool changes_status(Kind k) {
  return k != Kind::precision && k != Kind::unchanged;
}

bool listed(const CaseChange& c) {
  return c.kind != Kind::unchanged && !skipped_in_both(c);
}

bool no_change(const RunComparison& c) {
  return std::none_of(c.cases.begin(), c.cases.end(), listed);
}

std::vector<const CaseChange*> listed_of(const RunComparison& c, Kind k) {
  std::vector<const CaseChange*> out;
  for (const auto& cc : c.cases)
    if (cc.kind == k && listed(cc)) out.push_back(&cc);
  return out;
}

std::string skipped_in_both_note(const RunComparison& c) {
  const auto n = std::count_if(c.cases.begin(), c.cases.end(), skipped_in_both);
  return n ? fmt::format("{} skipped in both runs", n) : "";
}

// A section's heading: its count, and what the kind means where the name alone does not say.
std::string section_title(const RunComparison& c, Kind k) {
  const std::string title = counted(c.count(k), k);
  switch (k) {
    case Kind::changed:
      return title + " (failing in both, differently)";
    case Kind::added:
      return title + " (only in current)";
    case Kind::removed:
      return title + " (only in base)";
    case Kind::skipped:
      return title + " (in one run or both)";
    default:
      return title;
  }
}

// Unchanged cases whose frames differ: not a finding by the factor, but worth a look.
std::vector<const CaseChange*> bits_changed(const RunComparison& c) {
  std::vector<const CaseChange*> out;
  for (const auto& cc : c.cases)
    if (cc.kind == Kind::unchanged && cc.same_bits == false) out.push_back(&cc);
  return out;
}

// The channel whose max error changed most: "color.x max 1.5 -> 2 ulp (x1.3)".
std::string worst_change(const CaseChange& cc, double min_ulps) {
  const ChannelChange* worst = nullptr;
  for (const auto& ch : cc.channels)
    if (!worst || std::abs(ch.current_max_ulps - ch.base_max_ulps) >
                      std::abs(worst->current_max_ulps - worst->base_max_ulps))
      worst = &ch;
  if (!worst) return "coverage only";
  return worst->channel + " max " +
         ulps_change(worst->base_max_ulps, worst->current_max_ulps, min_ulps);
}

}  // namespace glrc::report::sections
