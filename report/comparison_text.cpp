// The terminal view of a RunComparison (`glrefcheck compare`): fixed-width, so that the names
// line up down the whole report and two reports can be diffed.
#include <algorithm>

#include <fmt/format.h>

#include "report/comparison_sections.hpp"
#include "report/format.hpp"
#include "report/run_compare.hpp"

namespace glrc::report {
namespace {

using Kind = CaseChange::Kind;
// The section helpers both views share (comparison_sections.hpp).
using namespace sections;

std::string driver_text(const RunInfo& r) {
  return r.driver.empty() ? r.backend : r.backend + ", " + r.driver;
}

}  // namespace

std::string comparison_text(const RunComparison& c) {
  const auto run_line = [](const char* label, const RunInfo& r) {
    std::string line =
        fmt::format("{:<8} {} | GL {} | {}", label, r.gl_renderer, r.gl_version, driver_text(r));
    if (!r.tolerance.empty()) line += " | tolerance " + r.tolerance;
    if (!r.mesa_prefix.empty()) line += " | Mesa " + r.mesa_prefix;
    return line + "\n";
  };
  std::string text = run_line("base:", c.base) + run_line("current:", c.current);
  for (const std::string& line : c.incomplete)
    text += "incomplete " + line + "\n";
  if (const auto note = setup_note(c); !note.empty()) text += note + "\n";
  text += fmt::format("\n{}\n{}\n", counts_line(c), bits_summary(c));

  // One width for every section, so the names line up down the whole report.
  size_t name_width = 4, status_width = 1;
  for (const auto& cc : c.cases) {
    if (!listed(cc) && cc.same_bits != false) continue;
    name_width = std::max(name_width, cc.name.size());
    status_width =
        std::max({status_width, status_text(cc.base).size(), status_text(cc.current).size()});
  }
  const std::string both_skipped = skipped_in_both_note(c);
  for (const Kind k : kKinds) {
    if (k == Kind::unchanged || c.count(k) == 0) continue;
    text += fmt::format("\n{}:\n", section_title(c, k));
    if (k == Kind::precision) text += "  (" + precision_note(c) + ")\n";
    for (const CaseChange* cc : listed_of(c, k)) {
      if (changes_status(k)) {
        std::string line = fmt::format("  {:>{}} -> {:<{}}  {:<{}}  {}", status_text(cc->base),
                                       status_width, status_text(cc->current), status_width,
                                       cc->name, name_width, short_message(cc->message));
        line.erase(line.find_last_not_of(' ') + 1);
        text += line + "\n";
        continue;
      }
      for (const auto& ch : cc->channels) {
        if (!ch.max_grew && !ch.p99_grew) continue;
        text += fmt::format("  {:<{}}  {:<8}  max {:<24}  p99 {:<24}  allowance used {} -> {}\n",
                            cc->name, name_width, ch.channel,
                            ulps_change(ch.base_max_ulps, ch.current_max_ulps, c.min_ulps),
                            ulps_change(ch.base_p99_ulps, ch.current_p99_ulps, c.min_ulps),
                            ratio_text(ch.base_max_ratio), ratio_text(ch.current_max_ratio));
      }
    }
    if (k == Kind::skipped && !both_skipped.empty()) text += "  (" + both_skipped + ")\n";
  }
  if (const auto changed = bits_changed(c); !changed.empty()) {
    text += "\nframes with other bits, same outcome, error within the factor:\n";
    for (const CaseChange* cc : changed)
      text += fmt::format("  {:<{}}  {}\n", cc->name, name_width, worst_change(*cc, c.min_ulps));
  }
  if (no_change(c)) text += "\nno change\n";
  return text;
}

}  // namespace glrc::report
