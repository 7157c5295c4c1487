// The Markdown view of a RunComparison (`glrefcheck compare --markdown FILE`), for CI comments
// on GitLab and GitHub: the text view's sections as tables.
#include <fmt/format.h>

#include "report/comparison_sections.hpp"
#include "report/format.hpp"
#include "report/run_compare.hpp"

namespace glrc::report {
namespace {

using Kind = CaseChange::Kind;
// The section helpers both views share (comparison_sections.hpp).
using namespace sections;

// Markdown table cells: a `|` would end the cell and a newline the row.
std::string md_cell(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '|') {
      out += "\\|";
    } else if (ch == '\n' || ch == '\r') {
      out += ' ';
    } else {
      out += ch;
    }
  }
  return out;
}

}  // namespace

std::string comparison_markdown(const RunComparison& c) {
  std::string md = "## glrefcheck compare\n\n| | base | current |\n|---|---|---|\n";
  const auto row = [&](const char* what, const std::string& base, const std::string& current) {
    md += fmt::format("| {} | {} | {} |\n", what, md_cell(base), md_cell(current));
  };
  row("GL_VERSION", c.base.gl_version, c.current.gl_version);
  row("GL_RENDERER", c.base.gl_renderer, c.current.gl_renderer);
  row("backend", c.base.backend, c.current.backend);
  row("driver", c.base.driver, c.current.driver);
  row("tolerance", c.base.tolerance, c.current.tolerance);
  if (!c.base.mesa_prefix.empty() || !c.current.mesa_prefix.empty())
    row("Mesa prefix", c.base.mesa_prefix, c.current.mesa_prefix);
  if (const auto note = setup_note(c); !note.empty()) md += "\n" + note + "\n";
  for (const std::string& line : c.incomplete)
    md += "\n**Incomplete " + md_cell(line) + "**\n";
  md += "\n**" + counts_line(c) + "**\n\n" + bits_summary(c) + "\n";

  const std::string both_skipped = skipped_in_both_note(c);
  for (const Kind k : kKinds) {
    if (k == Kind::unchanged || c.count(k) == 0) continue;
    md += "\n### " + section_title(c, k) + "\n\n";
    if (k == Kind::skipped && !both_skipped.empty()) md += "(" + both_skipped + ")\n\n";
    if (k == Kind::precision) md += precision_note(c) + "\n\n";
    const auto cases = listed_of(c, k);
    if (cases.empty()) continue;
    if (changes_status(k)) {
      md += "| case | base | current | message |\n|---|---|---|---|\n";
      for (const CaseChange* cc : cases)
        md += fmt::format("| {} | {} | {} | {} |\n", md_cell(cc->name), status_text(cc->base),
                          status_text(cc->current), md_cell(short_message(cc->message)));
      continue;
    }
    md += "| case | channel | max ulp | p99 ulp | allowance used |\n|---|---|---|---|---|\n";
    for (const CaseChange* cc : cases)
      for (const auto& ch : cc->channels)
        if (ch.max_grew || ch.p99_grew)
          md += fmt::format("| {} | {} | {} | {} | {} -> {} |\n", md_cell(cc->name),
                            md_cell(ch.channel),
                            ulps_change(ch.base_max_ulps, ch.current_max_ulps, c.min_ulps),
                            ulps_change(ch.base_p99_ulps, ch.current_p99_ulps, c.min_ulps),
                            ratio_text(ch.base_max_ratio), ratio_text(ch.current_max_ratio));
  }
  if (const auto changed = bits_changed(c); !changed.empty()) {
    md +=
        "\n### Frames with other bits, same outcome, error within the factor\n\n"
        "| case | largest error |\n|---|---|\n";
    for (const CaseChange* cc : changed)
      md += fmt::format("| {} | {} |\n", md_cell(cc->name), worst_change(*cc, c.min_ulps));
  }
  if (no_change(c)) md += "\nNo change.\n";
  return md;
}

}  // namespace glrc::report
