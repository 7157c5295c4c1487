// glrefcheck run (the suite, in worker processes, with Mesa CI's expectations and sharding),
// merge (shards into one run) and report (a run's HTML page).
#pragma once

#include <string>
#include <vector>

#include "cli/session.hpp"

namespace glrc::cli {

int cmd_run(const Options& o);

// Joins the results of the shards of one run (--fraction N, --fraction-start 1..N, each shard
// once) into `out`, in the order an unsharded run has, with the failing cases' heatmaps.
int cmd_merge(const std::vector<std::string>& dirs, const std::string& out, bool html);

// Writes <dir>/report.html (or `file`) from a run folder.
int cmd_report(const std::string& dir, const std::string& file);

}  // namespace glrc::cli
