// glrefcheck compare BASE CURRENT: two runs' results side by side, for CI (exit 1 on a
// regression) and for people (text, Markdown, JSON, HTML).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace glrc::cli {

struct CompareOptions {
  std::string base, current;  // run folders or results.json files
  std::string json, markdown, html;
  double factor = 2;              // precision growth that is flagged
  double min_ulps = 1;            // errors below this are rounding noise, not a base to grow from
  bool allow_incomplete = false;  // an interrupted or partial side is no failure of the gate
};

// Adds the subcommand "compare" with its positionals and options; returns it.
CLI::App* add_compare_command(CLI::App& app, CompareOptions& o);
// Prints the comparison, writes the files asked for; 1 when a case regressed, or when a side
// is incomplete (RunComparison::incomplete) without allow_incomplete, else 0.
// InputError for a results.json that cannot be read.
int cmd_compare(const CompareOptions& o);

}  // namespace glrc::cli
