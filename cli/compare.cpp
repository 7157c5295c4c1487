#include "cli/compare.hpp"
#include "cli/validators.hpp"

#include <fmt/core.h>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

#include "cli/output_dir.hpp"
#include "cli/run_support.hpp"
#include "cli/session.hpp"
#include "core/text.hpp"
#include "report/html.hpp"
#include "report/report.hpp"
#include "report/run_compare.hpp"
#include "report/stamp.hpp"

namespace glrc::cli {
namespace {

// Output files may name folders that do not exist yet (CI artifact folders, say).
void make_parent(const std::string& file) {
  const std::filesystem::path p(file);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
}

// Through a temporary file and a rename (report::write_file_atomically): a failed write leaves
// the last one whole.
void write_text(const std::string& file, const std::string& text) {
  make_parent(file);
  report::write_file_atomically(file, text);
}

// The comparison's Markdown under a comment holding its stamp (no Markdown renderer shows it).
std::string stamped_markdown(const std::string& markdown) {
  return report::stamped("<!-- written by glrefcheck compare " + report::stamp_placeholder() +
                         " -->\n" + markdown);
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app, CompareOptions& o) {
  auto* cmd = app.add_subcommand(
      "compare",
      "compare two runs: regressions, fixes, added and removed cases, and errors that grew "
      "(exit 1 on a regression)");
  cmd->add_option("BASE", o.base, "the earlier run: its folder or its results.json")->required();
  cmd->add_option("CURRENT", o.current, "the run to check: its folder or its results.json")
      ->required();
  cmd->add_option("--factor", o.factor,
                  "flag a case whose error grew more than this many times (default 2)")
      ->check(finite_number(1, false));
  cmd->add_option("--min-ulps", o.min_ulps,
                  "errors below this many ULPs are rounding noise: growth is measured from at "
                  "least this (default 1)")
      ->check(finite_number(0, true));
  cmd->add_option("--json", o.json, "also write the comparison as JSON to this file")
      ->type_name("FILE");
  cmd->add_option("--markdown", o.markdown, "also write it as Markdown (for CI comments)")
      ->type_name("FILE");
  cmd->add_option("--html", o.html, "also write an HTML page with both runs' heatmaps")
      ->type_name("FILE");
  cmd->add_flag("--allow-incomplete", o.allow_incomplete,
                "exit 0 though a run was interrupted or holds fewer cases than its suite (its "
                "missing cases are listed as removed or added)");
  return cmd;
}

int cmd_compare(const CompareOptions& o) {
  const report::RunResults base = read_run_results(o.base, "compare");
  const report::RunResults current = read_run_results(o.current, "compare");
  // Two outputs into one file would leave only the last.
  const std::vector<std::pair<const char*, const std::string*>> outputs = {
      {"--json", &o.json}, {"--markdown", &o.markdown}, {"--html", &o.html}};
  for (size_t a = 0; a < outputs.size(); ++a)
    for (size_t b = a + 1; b < outputs.size(); ++b) {
      if (outputs[a].second->empty() || outputs[b].second->empty()) continue;
      std::error_code ec;
      // Absolute first: weakly_canonical leaves "x" relative but resolves "./x".
      const auto resolved = [&](const std::string& f) {
        return std::filesystem::weakly_canonical(std::filesystem::absolute(f, ec), ec);
      };
      if (resolved(*outputs[a].second) == resolved(*outputs[b].second))
        throw InputError(fmt::format("{} and {}: expected two different files, got \"{}\" for both",
                                     outputs[a].first, outputs[b].first,
                                     printable(*outputs[a].second, 200)));
    }
  // Each output replaces only a file glrefcheck wrote and nobody changed since (its stamp).
  if (!o.json.empty()) check_replaceable(o.json, "--json", "compare");
  if (!o.markdown.empty()) check_replaceable(o.markdown, "--markdown", "compare");
  if (!o.html.empty()) check_replaceable(o.html, "--html", "compare");
  const report::RunComparison c = report::compare_runs(base, current, o.factor, o.min_ulps);
  fmt::print("{}", report::comparison_text(c));
  if (!o.json.empty())
    write_text(o.json, report::stamped_json("compare", report::comparison_json(c)));
  if (!o.markdown.empty()) write_text(o.markdown, stamped_markdown(report::comparison_markdown(c)));
  if (!o.html.empty()) {
    make_parent(o.html);
    report::write_comparison_html(o.html, c, report::run_folder(o.base),
                                  report::run_folder(o.current));
  }
  for (const std::string* file : {&o.json, &o.markdown, &o.html})
    if (!file->empty()) fmt::print("wrote {}\n", *file);
  // A gate on the exit code must not pass a run that checked a quarter of the suite.
  if (!c.incomplete.empty() && !o.allow_incomplete) {
    fmt::print("a run is incomplete: exit 1 (--allow-incomplete to compare it anyway)\n");
    return 1;
  }
  return c.has_regression() ? 1 : 0;
}

}  // namespace glrc::cli
