// glrefcheck merge (shards into one run, by report/merge) and report (a run's HTML page).
#include <fmt/core.h>

#include <filesystem>
#include <stdexcept>

#include "cli/journal.hpp"
#include "cli/output_dir.hpp"
#include "cli/run.hpp"
#include "cli/run_support.hpp"
#include "report/html.hpp"
#include "report/merge.hpp"
#include "report/report.hpp"

namespace glrc::cli {

int cmd_merge(const std::vector<std::string>& dirs, const std::string& out_dir, bool html) {
  std::vector<report::RunResults> shards;
  for (const auto& d : dirs) {
    try {
      shards.push_back(report::read_results_json(d));
    } catch (const std::runtime_error& e) {
      throw InputError(std::string("merge: ") + e.what());
    }
  }
  report::RunResults merged;
  try {
    merged = report::merge_shards(shards, dirs);
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  const RunInfo& info = merged.run;
  const std::vector<CaseResult>& list = merged.cases;
  // The merge replaces its folder's run files: never a shard's own.
  for (const auto& d : dirs) {
    bool clash = inside(out_dir, report::run_folder(d)) && inside(report::run_folder(d), out_dir);
    for (const std::string& name : run_output_names())
      clash = clash || inside(report::run_folder(d), std::filesystem::path(out_dir) / name);
    if (clash)
      throw InputError("merge --out " + out_dir + ": expected a folder apart from the shards, " +
                       "got the shard " + d + " or a folder whose run files hold it");
  }
  const std::filesystem::path out = output_folder(out_dir);
  // Heatmaps and files of an earlier run or merge here would be taken for this merge's.
  clear_run_outputs(out);
  for (size_t k = 0; k < shards.size(); ++k) {
    const auto images = report::run_folder(dirs[k]) / "cases";
    std::error_code ec;
    if (std::filesystem::is_directory(images, ec))
      std::filesystem::copy(images, out / "cases",
                            std::filesystem::copy_options::recursive |
                                std::filesystem::copy_options::overwrite_existing);
  }
  fmt::print("merged {} shards: {}\n", shards.size(), report::run_summary(list, info.seconds));
  write_outputs(out, info, list, html);
  return report::any_fails_run(list) ? 1 : 0;
}

int cmd_report(const std::string& dir, const std::string& file) {
  report::RunResults results;
  std::error_code ec;
  if (std::filesystem::is_directory(dir, ec) &&
      !std::filesystem::exists(std::filesystem::path(dir) / "results.json", ec) &&
      std::filesystem::exists(std::filesystem::path(dir) / kJournalFile, ec))
    throw InputError("report: " + dir + " holds no results.json but a " + kJournalFile +
                     ": the run was killed; `glrefcheck run --resume " + dir + "` finishes it");
  try {
    results = report::read_results_json(dir);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string("report: ") + e.what());
  }
  const std::filesystem::path run_dir = report::run_folder(dir);
  const std::filesystem::path html =
      file.empty() ? run_dir / "report.html" : std::filesystem::path(file);
  check_replaceable(html, file.empty() ? "report" : "--out", "<title>glrefcheck");
  report::write_run_html(html, results, run_dir);
  fmt::print("wrote {}\n", html.string());
  return 0;
}

}  // namespace glrc::cli
