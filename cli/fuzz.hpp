// glrefcheck fuzz: random campaigns (campaign/) on worker processes, each distinct failure
// shrunk to a minimal case written into <out>/failures/, and --replay S:I --emit FILE to make
// one generated case again as a case file.
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/session.hpp"

namespace glrc::cli {

struct FuzzOptions {
  std::optional<uint64_t> seed;  // default: a fresh one, printed and recorded
  std::optional<uint64_t> count;
  std::optional<double> seconds;
  std::vector<std::string> generators;  // default: every one
  std::optional<std::string> replay;    // given, even empty: refused then, not a random campaign
  std::string emit;
  // Known campaign failures, `<failure>,Fail` lines (Mesa CI's format; <failure> is the name of
  // the minimal case, "non_finite_noperspective"): reported as known, they do not fail it.
  std::string baseline;
  bool out_given = false;  // --out given (with --emit, which writes one file, it is refused)
  double shrink_seconds = 60;
  bool no_shrink = false;
};

// Adds the `fuzz` subcommand's own options (the GL, model and worker options are the caller's).
CLI::App* add_fuzz_command(CLI::App& app, FuzzOptions& f);
// Exit 0: no failure the baseline does not list; 1: a new failure; 2: bad input; 130/143:
// interrupted.
int cmd_fuzz(const Options& o, const FuzzOptions& f);

// A campaign's results.json (campaign::campaign_json, each failure with its minimal case's
// "result") and results.csv (`<failure>,Fail|ExpectedFail,seconds`) in `out`.
void write_campaign_files(const std::filesystem::path& out, const nlohmann::json& doc);
// The minimal cases (file names in failures/) the campaign results in `out` list, and those a
// campaign still running, or killed outright, wrote before its results (kFailuresWritten); none
// when there are none, or they are not a campaign's.
std::set<std::string> listed_failure_files(const std::filesystem::path& out);
// In a campaign's folder while it runs: the name of each minimal case it writes into failures/,
// a line each, added before the case is written. A campaign killed outright (SIGKILL, a machine
// that went down) has no results.json listing them; this file names them as its own, so that the
// next campaign there replaces them instead of taking them for a person's. Written over by the
// next campaign's first minimal case, removed once results.json lists them (write_campaign_files).
inline constexpr const char* kFailuresWritten = ".glrefcheck-failures";

// `merge` of campaign shards (`fuzz --fraction`): campaign::merge_campaigns, each failure's
// minimal case and heatmaps copied from the shard it came from, report.html. Exit 0 when no
// failure is new, 1 otherwise.
int cmd_merge_campaign(const std::vector<std::string>& dirs, const std::string& out_dir);

}  // namespace glrc::cli
