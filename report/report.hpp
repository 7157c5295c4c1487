// Reports written from CaseResults: results.json, junit.xml, terminal tables, and diff images.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "core/frame.hpp"
#include "core/result.hpp"

namespace glrc::report {

void write_results_json(const std::filesystem::path& file, const RunInfo& run,
                        const std::vector<CaseResult>& results);
void write_junit(const std::filesystem::path& file, const RunInfo& run,
                 const std::vector<CaseResult>& results);

// One line for a case in `run`'s listing: "Pass  name  (max 3.1 ulp, 0.012 s)".
std::string case_line(const CaseResult& r);
// The per-channel statistics table for `diff`.
std::string stats_table(const CaseResult& r);
// The n worst pixels over all channels: x, y, channel, reference, GL, error.
std::string worst_pixels_table(const CaseResult& r, size_t n);

// Writes, for depth and each component, colour-mapped PNG heatmaps with legends of the error
// (_error.png), of the allowance (_allowed.png) and of their ratio (_ratio.png); EXRs of the
// signed error, the allowance, and the GL and reference values; and coverage.png. Returns the
// files.
std::vector<std::filesystem::path> write_diff_images(const std::filesystem::path& dir,
                                                     const Case& c, const Expectation& expected,
                                                     const Frame& gl, const CaseResult& r);

}  // namespace glrc::report
