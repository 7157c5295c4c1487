#include "cli/compare.hpp"
#include "cli/validators.hpp"

#include <fmt/core.h>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "cli/output_dir.hpp"
#include "cli/session.hpp"
#include "report/html.hpp"
#include "report/report.hpp"
#include "report/run_compare.hpp"

namespace glrc::cli {
namespace {

// A finite number above `lower` (or at it, when `inclusive`): NaN would compare false
// everywhere and flag nothing, an infinity would flag nothing or everything.
report::RunResults read_run(const std::string& path) {
  try {
    return report::read_results_json(path);
  } catch (const std::runtime_error& e) {
    // One line on stderr, whatever the JSON parser's message holds.
    std::string message = e.what();
    for (char& ch : message)
      if (ch == '\n' || ch == '\r') ch = ' ';
    throw InputError(message);
  }
}

// Output files may name folders that do not exist yet (CI artifact folders, say).
void make_parent(const std::string& file) {
  const std::filesystem::path p(file);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
}

void write_text(const std::string& file, const std::string& text) {
  make_parent(file);
  errno = 0;
  std::ofstream out(file, std::ios::binary);
  out << text;
  // The stream keeps no reason; the open or write under it left one in errno.
  if (!out)
    throw std::runtime_error("cannot write " + file +
                             (errno ? ": " + std::string(std::strerror(errno)) : ""));
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
  return cmd;
}

int cmd_compare(const CompareOptions& o) {
  const report::RunResults base = read_run(o.base);
  const report::RunResults current = read_run(o.current);
  // Each output replaces only a file it wrote before (the top of each format says glrefcheck).
  if (!o.json.empty()) check_replaceable(o.json, "--json", "{\n  \"base\": {");
  if (!o.markdown.empty()) check_replaceable(o.markdown, "--markdown", "## glrefcheck compare");
  if (!o.html.empty()) check_replaceable(o.html, "--html", "<title>glrefcheck compare");
  const report::RunComparison c = report::compare_runs(base, current, o.factor, o.min_ulps);
  fmt::print("{}", report::comparison_text(c));
  if (!o.json.empty()) write_text(o.json, report::comparison_json(c));
  if (!o.markdown.empty()) write_text(o.markdown, report::comparison_markdown(c));
  if (!o.html.empty()) {
    make_parent(o.html);
    report::write_comparison_html(o.html, c, report::run_folder(o.base),
                                  report::run_folder(o.current));
  }
  for (const std::string* file : {&o.json, &o.markdown, &o.html})
    if (!file->empty()) fmt::print("wrote {}\n", *file);
  return c.has_regression() ? 1 : 0;
}

}  // namespace glrc::cli
