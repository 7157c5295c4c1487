// Self-contained HTML reports (one file, styles inline, images as data: URIs), for a run folder
// and for two runs side by side. Knows nothing of GL: it reads results and the run folders'
// heatmaps.
#pragma once

#include <filesystem>

#include "report/report.hpp"
#include "report/run_compare.hpp"

namespace glrc::report {

// The summary (GL strings, counts by status, wall time), a table of every case with its status
// and error statistics, and for each failing case (status or outcome not Pass/Skip) its
// heatmaps: the PNGs that `run` writes into `run_dir/cases/<case name>/`.
void write_run_html(const std::filesystem::path& file, const RunResults& results,
                    const std::filesystem::path& run_dir);

// Two runs side by side: both GL_VERSIONs, the comparison's counts and changed cases, and for
// each regressed or changed case the heatmaps of both runs next to each other.
void write_comparison_html(const std::filesystem::path& file, const RunComparison& comparison,
                           const std::filesystem::path& base_dir,
                           const std::filesystem::path& current_dir);

}  // namespace glrc::report
