// Two runs side by side: the classification, and the text, Markdown and JSON reports of it.
#include "report/run_compare.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "report/format.hpp"

namespace glrc::report {
namespace {

using Kind = CaseChange::Kind;

// The order of the counts and the reports' sections: what needs attention first.
constexpr Kind kKinds[] = {Kind::regression, Kind::fix,     Kind::changed,   Kind::added,
                           Kind::removed,    Kind::skipped, Kind::precision, Kind::unchanged};

// Outcomes are pass, fail, crash, timeout, error or skip. The expectation statuses fold into
// them, so that results written by anything that filled `outcome` from `status` still compare
// (deqp-runner's Flake is a case that passed on a retry).
Status outcome_of(Status s) {
  switch (s) {
    case Status::expected_fail:
      return Status::fail;
    case Status::unexpected_pass:
    case Status::flake:
      return Status::pass;
    default:
      return s;
  }
}

bool passes(Status s) {
  return s == Status::pass;
}

// A crash or a timeout checks nothing at all, so reaching one from a failure that still
// compared pixels (or stopped at a GL error) loses information even though both runs fail.
bool unchecked(Status s) {
  return s == Status::crash || s == Status::timeout;
}

Kind classify(Status base, Status current) {
  base = outcome_of(base), current = outcome_of(current);
  if (base == Status::skip || current == Status::skip) return Kind::skipped;
  if (passes(base) != passes(current)) return passes(base) ? Kind::regression : Kind::fix;
  if (base == current) return Kind::unchanged;  // precision is decided from the channels
  return unchecked(current) && !unchecked(base) ? Kind::regression : Kind::changed;
}

// current > factor * max(base, min_ulps). A NaN current is never within any bound; a NaN base
// is no bound at all, so only a NaN current counts.
bool grew(double base, double current, double factor, double min_ulps) {
  if (std::isnan(current)) return true;
  return current > factor * std::max(base, min_ulps);
}

std::vector<ChannelChange> channel_changes(const CaseResult& base, const CaseResult& current,
                                           double factor, double min_ulps) {
  std::vector<ChannelChange> out;
  for (const auto& now : current.channels) {
    if (now.compared == 0) continue;
    const auto before = std::find_if(base.channels.begin(), base.channels.end(),
                                     [&](const ChannelStats& ch) { return ch.name == now.name; });
    if (before == base.channels.end() || before->compared == 0) continue;
    ChannelChange ch;
    ch.channel = now.name;
    ch.base_max_ulps = before->max_ulps, ch.current_max_ulps = now.max_ulps;
    ch.base_p99_ulps = before->p99_ulps, ch.current_p99_ulps = now.p99_ulps;
    ch.base_max_ratio = before->max_ratio, ch.current_max_ratio = now.max_ratio;
    ch.max_grew = grew(ch.base_max_ulps, ch.current_max_ulps, factor, min_ulps);
    ch.p99_grew = grew(ch.base_p99_ulps, ch.current_p99_ulps, factor, min_ulps);
    out.push_back(std::move(ch));
  }
  return out;
}

bool any_grew(const CaseChange& c) {
  return std::any_of(c.channels.begin(), c.channels.end(),
                     [](const ChannelChange& ch) { return ch.max_grew || ch.p99_grew; });
}

std::string status_text(const std::optional<Status>& s) {
  return s ? to_string(*s) : "-";
}

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

std::string counts_line(const RunComparison& c) {
  std::string line = count_text(c.cases.size(), "case", "cases") + ": ";
  for (size_t k = 0; k < std::size(kKinds); ++k)
    line += (k ? ", " : "") + counted(c.count(kKinds[k]), kKinds[k]);
  return line;
}

// How far the error grew, against the base the factor is applied to: "x6", "x2.5", "xinf".
std::string growth_text(double base, double current, double min_ulps) {
  // fmt, not "x" + string: GCC 12 at -O3 reports a false -Wrestrict inside operator+.
  return fmt::format("x{}", ratio_text(current / std::max(base, min_ulps)));
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

std::string driver_text(const RunInfo& r) {
  return r.driver.empty() ? r.backend : r.backend + ", " + r.driver;
}

bool changes_status(Kind k) {
  return k != Kind::precision && k != Kind::unchanged;
}

// A case skipped in both runs says nothing about either: it is counted, not listed, and is no
// change.
bool skipped_in_both(const CaseChange& c) {
  return c.kind == Kind::skipped && c.base == Status::skip && c.current == Status::skip;
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

nlohmann::json run_json(const RunInfo& r) {
  return {{"backend", r.backend},
          {"driver", r.driver},
          {"gl_renderer", r.gl_renderer},
          {"gl_version", r.gl_version},
          {"gl_vendor", r.gl_vendor},
          {"mesa_prefix", r.mesa_prefix},
          {"model", r.model},
          {"model_source", r.model_source},
          {"tolerance", r.tolerance}};
}

nlohmann::json optional_status(const std::optional<Status>& s) {
  return s ? nlohmann::json(to_string(*s)) : nlohmann::json(nullptr);
}

}  // namespace

const char* to_string(CaseChange::Kind k) {
  switch (k) {
    case Kind::regression:
      return "regression";
    case Kind::fix:
      return "fix";
    case Kind::changed:
      return "changed";
    case Kind::added:
      return "added";
    case Kind::removed:
      return "removed";
    case Kind::skipped:
      return "skipped";
    case Kind::precision:
      return "precision";
    case Kind::unchanged:
      return "unchanged";
  }
  return "unchanged";
}

size_t RunComparison::count(CaseChange::Kind k) const {
  return size_t(
      std::count_if(cases.begin(), cases.end(), [&](const CaseChange& c) { return c.kind == k; }));
}

// Identical statistics do not mean identical pixels: the frame digests say whether a Mesa change
// touched the rasterizer's output at all.
std::string bits_summary(const RunComparison& c) {
  const size_t n = c.bits_compared(), same = c.bits_identical();
  if (n == 0) return "GL frames: no digests to compare bit for bit";
  if (same == n) return fmt::format("GL frames: all {} bit-identical to base", n);
  return fmt::format("GL frames: {} of {} bit-identical to base, {} with other bits", same, n,
                     n - same);
}

size_t RunComparison::bits_compared() const {
  return size_t(std::count_if(cases.begin(), cases.end(),
                              [](const CaseChange& c) { return c.same_bits.has_value(); }));
}

size_t RunComparison::bits_identical() const {
  return size_t(std::count_if(cases.begin(), cases.end(),
                              [](const CaseChange& c) { return c.same_bits.value_or(false); }));
}

RunComparison compare_runs(const RunResults& base, const RunResults& current, double factor,
                           double min_ulps) {
  RunComparison out;
  out.base = base.run, out.current = current.run;
  out.factor = factor, out.min_ulps = min_ulps;

  std::unordered_map<std::string, const CaseResult*> in_base, in_current;
  for (const auto& r : base.cases)
    in_base.emplace(r.name, &r);
  for (const auto& r : current.cases)
    in_current.emplace(r.name, &r);

  for (const auto& now : current.cases) {
    CaseChange c;
    c.name = now.name;
    c.current = now.outcome;
    c.message = now.message;
    const auto found = in_base.find(now.name);
    if (found == in_base.end()) {
      c.kind = Kind::added;
    } else {
      const CaseResult& before = *found->second;
      c.base = before.outcome;
      c.kind = classify(before.outcome, now.outcome);
      c.channels = channel_changes(before, now, factor, min_ulps);
      if (!before.gl_digest.empty() && !now.gl_digest.empty())
        c.same_bits = before.gl_digest == now.gl_digest;
      if (c.kind == Kind::unchanged && any_grew(c)) c.kind = Kind::precision;
    }
    out.cases.push_back(std::move(c));
  }
  for (const auto& before : base.cases) {
    if (in_current.count(before.name)) continue;
    CaseChange c;
    c.name = before.name;
    c.kind = Kind::removed;
    c.base = before.outcome;
    c.message = before.message;
    out.cases.push_back(std::move(c));
  }
  return out;
}

namespace {

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

std::string comparison_json(const RunComparison& c) {
  nlohmann::json summary = nlohmann::json::object();
  for (const Kind k : kKinds)
    summary[to_string(k)] = c.count(k);
  nlohmann::json cases = nlohmann::json::array();
  for (const auto& cc : c.cases) {
    nlohmann::json channels = nlohmann::json::array();
    for (const auto& ch : cc.channels)
      channels.push_back({{"channel", ch.channel},
                          {"base_max_ulps", json_number(ch.base_max_ulps)},
                          {"current_max_ulps", json_number(ch.current_max_ulps)},
                          {"base_p99_ulps", json_number(ch.base_p99_ulps)},
                          {"current_p99_ulps", json_number(ch.current_p99_ulps)},
                          {"base_max_ratio", json_number(ch.base_max_ratio)},
                          {"current_max_ratio", json_number(ch.current_max_ratio)},
                          {"max_grew", ch.max_grew},
                          {"p99_grew", ch.p99_grew}});
    cases.push_back({{"name", cc.name},
                     {"kind", to_string(cc.kind)},
                     {"base", optional_status(cc.base)},
                     {"current", optional_status(cc.current)},
                     {"message", cc.message},
                     {"same_bits", cc.same_bits ? nlohmann::json(*cc.same_bits) : nullptr},
                     {"channels", std::move(channels)}});
  }
  const nlohmann::json doc = {
      {"base", run_json(c.base)},           {"current", run_json(c.current)},
      {"factor", json_number(c.factor)},    {"min_ulps", json_number(c.min_ulps)},
      {"summary", std::move(summary)},      {"regressions", c.has_regression()},
      {"bits_compared", c.bits_compared()}, {"bits_identical", c.bits_identical()},
      {"cases", std::move(cases)}};
  // Case names and messages come from files and drivers; replace bad UTF-8 rather than throw.
  return doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace glrc::report
