// The commands on cases named on the command line: diff (one case against GL, with its tables
// and heatmaps), digest (the reference's digest of each case) and list.
#pragma once

#include "cli/session.hpp"

namespace glrc::cli {

int cmd_diff(const Options& o);
int cmd_digest(const Options& o);
int cmd_list(const Options& o);

}  // namespace glrc::cli
