// Reports written from CaseResults: results.json, junit.xml, terminal tables, and diff images.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/case.hpp"
#include "core/expectation.hpp"
#include "core/result.hpp"
#include "report/stamp.hpp"

namespace glrc::report {

void write_results_json(const std::filesystem::path& file, const RunInfo& run,
                        const std::vector<CaseResult>& results);
// A results.json read back (or a folder holding one). Throws std::runtime_error naming the file
// and the field on anything malformed.
// A file stamped and edited since is refused (its "written_by", report/stamp.hpp); `stamp`
// says whether it held one (none: an older glrefcheck's results, or made by hand).
struct RunResults {
  RunInfo run;
  std::vector<CaseResult> cases;
  JsonStamp stamp = JsonStamp::none;
};
RunResults read_results_json(const std::filesystem::path& file_or_dir);
// The run folder of such an argument (where its cases/<name>/ heatmaps are): the folder itself,
// or the folder of the results.json.
std::filesystem::path run_folder(const std::filesystem::path& file_or_dir);
// The run's description alone, as one line of JSON (results.json's "run"), and back: the run
// journal records it when GL is known, so a resumed run reports the same GL and model.
std::string run_info_json(const RunInfo& run);
RunInfo run_info_from_json(const std::string& text, const std::string& source);
// Writes `text` to `file` so that a reader (or a kill at any moment) sees the old file or the
// new one, never a part: a temporary file in the same folder, flushed to disk, then renamed.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);
// One case as one line of JSON, the same fields as in results.json, and back (how worker
// processes hand results to the runner).
std::string case_result_json(const CaseResult& r);
CaseResult case_result_from_json(const std::string& text, const std::string& source);

// Mesa CI's files (deqp-runner's format): results.csv, one `case,Status,seconds` line per case;
// failures.csv, the same for the cases whose status fails the run.
void write_results_csv(const std::filesystem::path& file, const std::vector<CaseResult>& results);
void write_failures_csv(const std::filesystem::path& file, const std::vector<CaseResult>& results);
// What in a case name would break a line of results.csv or failures.csv (`case,Status,seconds`,
// no quoting: Mesa CI's tools split on commas), or nullptr: an empty name, a comma, a quote, a
// line break or another control character, a space at an end. Such names are refused (by run,
// and by whatever reads a results.json), not quoted: a quoted name would not match the same
// case in a --baseline read by those tools.
const char* csv_breaking(const std::string& name);
// All four files of a run folder: results.json, results.csv, failures.csv, junit.xml.
void write_run_files(const std::filesystem::path& dir, const RunInfo& run,
                     const std::vector<CaseResult>& results);

void write_junit(const std::filesystem::path& file, const RunInfo& run,
                 const std::vector<CaseResult>& results);

// One line for a case in `run`'s listing: "Pass  name  (max 3.1 ulp, 0.012 s)".
std::string case_line(const CaseResult& r);
// The per-channel statistics table for `diff`.
std::string stats_table(const CaseResult& r);
// The n worst pixels over all channels: x, y, channel, reference, GL, error. "" when no
// channel has a worst pixel (nothing compared, e.g. GL drew nothing).
std::string worst_pixels_table(const CaseResult& r, size_t n);
// The failing coverage pixels for `diff`, at most n of those CoverageStats::mismatches keeps
// (compare keeps the first 64 mismatches in row order): x, y, the reference's and GL's
// primitive ("-" for none), the reference's and GL's fragment count (from the frames; "-" where
// a frame has none) and the kind of mismatch, then how many more fail. "" when no coverage pixel
// fails.
std::string coverage_failures_table(const CaseResult& r, const Frame& reference, const Frame& gl,
                                    size_t n);

// Writes, for depth and each component, colour-mapped PNG heatmaps with legends of the error
// (_error.png), of the allowance (_allowed.png) and of their ratio (_ratio.png); EXRs of the
// signed error, the allowance, and the GL and reference values; and coverage.png. Returns the
// files. A frame over 2^20 pixels gets maps only of its failing channels, shrunk by
// map_factor (channel_error.hpp; each pixel the worst of its block), and EXRs of a 256 x 256 tile
// around each one's worst pixel (_error_tile.exr, ...), so that pictures of any frame stay small
// and quick. `before_write`, when given, is told each file before it is created (`diff` records
// its images' names first, so that a diff stopped halfway leaves none unlisted).
using BeforeWrite = std::function<void(const std::filesystem::path&)>;
std::vector<std::filesystem::path> write_diff_images(const std::filesystem::path& dir,
                                                     const Case& c, const Expectation& expected,
                                                     const Frame& gl, const CaseResult& r,
                                                     const BeforeWrite& before_write = {});
// Every file name write_diff_images (and write_streamed_diff_images) may write for case `c`: each
// channel's maps, EXRs and tiles, and coverage.png. A superset, known before anything is
// written (`diff` refuses a folder holding a file of the user's by one of these names).
std::vector<std::string> diff_image_names(const Case& c);
// Rows [y0, y0 + rows) of a case's expectation and GL frame (check's streamed slices).
using SliceSource = std::function<std::pair<Expectation, Frame>(int y0, int rows)>;
// The same files from a case checked slice by slice (check::Checked::streamed), which holds no
// whole frame: the very files write_diff_images writes from the whole frames (a frame of 2^20
// pixels or fewer is stacked whole and given to it), about `slice_rows` rows at a time. The
// slices are read at most twice: once for every map, their worst pixels and coverage.png, once
// more for the rows of the tiles around the worst pixels.
std::vector<std::filesystem::path> write_streamed_diff_images(const std::filesystem::path& dir,
                                                              const Case& c, const CaseResult& r,
                                                              int slice_rows,
                                                              const SliceSource& slice);

}  // namespace glrc::report
