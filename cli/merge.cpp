// glrefcheck merge (shards into one run, by report/merge) and report (a run's HTML page).
#include <fmt/core.h>

#include <filesystem>
#include <optional>
#include <stdexcept>

#include <fstream>
#include <nlohmann/json.hpp>

#include "campaign/campaign.hpp"
#include "cli/fuzz.hpp"
#include "cli/interrupts.hpp"
#include "cli/journal.hpp"
#include "cli/output_dir.hpp"
#include "cli/run.hpp"
#include "cli/run_support.hpp"
#include "core/text.hpp"
#include "report/format.hpp"
#include "report/html.hpp"
#include "report/merge.hpp"
#include "report/report.hpp"
#include "report/stamp.hpp"

namespace glrc::cli {

namespace {

// The results.json of a shard folder (or the file itself), parsed, with its stamp; nullopt when
// it cannot be read as JSON (read_results_json then says why in its words).
struct RawResults {
  nlohmann::json doc;
  report::JsonStamp stamp;
};
std::optional<RawResults> raw_results(const std::string& dir) {
  const std::filesystem::path file = report::run_folder(dir) / "results.json";
  // Opened only when a regular file: a FIFO there would block the merge for good.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  try {
    nlohmann::json doc = nlohmann::json::parse(text);
    const report::JsonStamp stamp = report::json_stamp(doc.contains("written_by"), text);
    return RawResults{std::move(doc), stamp};
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

// The merge replaces its folder's run files: never a shard's own, and nothing inside a shard's
// folder either (its failures/ or cases/: a later run or campaign there would find a folder of
// files it did not write).
void check_apart(const std::vector<std::string>& dirs, const std::string& out_dir) {
  for (const auto& d : dirs) {
    bool clash = inside(out_dir, report::run_folder(d));
    for (const std::string& name : run_output_names())
      clash = clash || inside(report::run_folder(d), std::filesystem::path(out_dir) / name);
    if (clash)
      throw InputError("merge --out " + out_dir + ": expected a folder apart from the shards, " +
                       "got the shard " + d +
                       ", a folder inside it, or a folder whose run "
                       "files hold it");
  }
}

// A shard's heatmap folder (where it has one) holds only what a merge can copy, checked before
// the merge clears anything: a FIFO or a socket there failed the copy halfway, in words that
// named no file.
void check_copyable(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return;
  for (std::filesystem::recursive_directory_iterator it(dir, ec), end; !ec && it != end;
       it.increment(ec)) {
    const auto st = it->symlink_status(ec);
    if (!std::filesystem::is_regular_file(st) && !std::filesystem::is_directory(st))
      throw InputError("merge: " + it->path().string() +
                       ": expected the shard's heatmaps (files and folders), got something else");
  }
  if (ec) throw InputError("merge: cannot read " + dir.string() + " (" + ec.message() + ")");
}

}  // namespace

namespace {

// The campaign shards' results joined (campaign::merge_campaigns); `from[i]`: the shard of the
// i-th failure. Each field checked, then each shard's stamp.
nlohmann::json merged_campaign(const std::vector<std::string>& dirs, std::vector<size_t>& from) {
  std::vector<nlohmann::json> shards;
  std::vector<report::JsonStamp> stamps;
  for (const auto& d : dirs) {
    check_settled(d, "merge");
    auto j = raw_results(d);
    if (!j || !campaign::is_campaign_json(j->doc))
      throw InputError("merge: " + d + ": expected the results of a fuzz campaign shard, as the " +
                       "first shard holds, got " +
                       (j ? "a run's results" : "no readable results.json"));
    shards.push_back(std::move(j->doc));
    stamps.push_back(j->stamp);
  }
  nlohmann::json merged;
  try {
    merged = campaign::merge_campaigns(shards, dirs, from);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string("merge: ") + e.what());
  }
  // After each field's own check, as read_results_json does: a shard stamped and edited since
  // (a failure taken out) is no campaign's results.
  for (size_t k = 0; k < dirs.size(); ++k)
    if (stamps[k] == report::JsonStamp::edited)
      throw InputError("merge: " + report::edited_stamp_message(
                                       (report::run_folder(dirs[k]) / "results.json").string()));
  // As read_run_results says it of a run's.
  for (size_t k = 0; k < dirs.size(); ++k)
    if (stamps[k] == report::JsonStamp::none) note_unstamped(dirs[k]);
  return merged;
}

// InputError when a shard's minimal case is not as its campaign wrote it (its stamp, fuzz's, no
// longer matches: edited since), which merge would give as the merged campaign's own; a note
// when it holds no stamp (an older glrefcheck's), read as it stands.
void check_minimal_case(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  if (!in.good() && !in.eof())
    throw InputError("merge: cannot read " + printable(file.string(), 200));
  if (text.find(report::kStampPrefix) == std::string::npos) {
    fmt::print(stderr,
               "note: {}: the minimal case holds no stamp (an older glrefcheck's, or made by "
               "hand): merged as it stands\n",
               printable(file.string(), 200));
    return;
  }
  if (!report::stamp_intact(text) || report::stamp_writer(text) != "fuzz")
    throw InputError("merge: " + printable(file.string(), 200) +
                     ": expected the failure's minimal case as the shard's campaign wrote it, got "
                     "one changed since (its stamp no longer matches): merge gives it as the "
                     "campaign's own; run the shard again, or put its file back");
}

}  // namespace

int cmd_merge_campaign(const std::vector<std::string>& dirs, const std::string& out_dir) {
  std::vector<size_t> from;
  const nlohmann::json merged = merged_campaign(dirs, from);
  check_apart(dirs, out_dir);
  // Everything to copy is checked before the folder's earlier merge is cleared: a failure moved
  // out of its shard must not cost the last good merge.
  for (size_t i = 0; i < merged["failures"].size(); ++i) {
    const std::filesystem::path shard = report::run_folder(dirs[from[i]]);
    const std::filesystem::path file = merged["failures"][i].value("file", "");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(shard / file, ec))
      throw InputError("merge: " + (shard / file).string() +
                       ": expected the failure's minimal case, as the shard's results.json names "
                       "it (moved or deleted?)");
    check_minimal_case(shard / file);
    check_copyable(shard / "cases" / file.stem());
  }
  const OutputFolder folder = output_folder(out_dir);
  const std::filesystem::path& out = folder.path;
  // The folder's earlier merge comes back if this one fails halfway (its minimal cases as
  // set_aside_outputs checks them: none a person changed or added).
  EarlierOutputs earlier = set_aside_outputs(out, {"failures"});
  std::filesystem::create_directories(out / "failures");
  // Each failure's minimal case and heatmaps, from the shard it was taken from.
  std::vector<CaseResult> minimal;
  size_t new_failures = 0;
  for (size_t i = 0; i < merged["failures"].size(); ++i) {
    const nlohmann::json& f = merged["failures"][i];
    const std::filesystem::path shard = report::run_folder(dirs[from[i]]);
    const std::filesystem::path file = f.value("file", "");
    const std::string name = file.stem().string();
    std::error_code ec;
    std::filesystem::copy_file(shard / file, out / file,
                               std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) throw InputError("merge: cannot copy " + (shard / file).string() + ": " + ec.message());
    if (std::filesystem::is_directory(shard / "cases" / name, ec)) {
      std::filesystem::create_directories(out / "cases" / name);
      std::filesystem::copy(shard / "cases" / name, out / "cases" / name,
                            std::filesystem::copy_options::recursive |
                                std::filesystem::copy_options::overwrite_existing,
                            ec);
      if (ec) throw InputError("merge: cannot copy the heatmaps of " + name + ": " + ec.message());
    } else {
      fmt::print(stderr,
                 "note: {}: no heatmaps of {} (cases/{}/): the merged report.html shows "
                 "none for it\n",
                 printable(dirs[from[i]], 200), name, name);
    }
    if (f.contains("result"))
      minimal.push_back(
          report::case_result_from_json(f["result"].dump(), (shard / "results.json").string()));
    new_failures += !f.value("known", false);
    stop_if_interrupted();
  }
  write_campaign_files(out, merged);
  RunInfo page;
  try {
    page = report::run_info_from_json(merged["run"].dump(), dirs[0]);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string("merge: ") + e.what());
  }
  page.total_cases = minimal.size();
  report::write_run_html(out / "report.html", {page, minimal}, out);
  earlier.keep_new();
  const nlohmann::json& st = merged["stats"];
  fmt::print("merged {}: {}, {} triangles, {} ({} new)\n",
             report::count_text(dirs.size(), "campaign shard", "campaign shards"),
             report::count_text(st.value("cases", uint64_t(0)), "case", "cases"),
             st.value("triangles", uint64_t(0)),
             report::count_text(merged["failures"].size(), "distinct failure", "distinct failures"),
             new_failures);
  fmt::print("results in {}\n", shown_path(out.string()));
  return new_failures == 0 ? 0 : 1;
}

int cmd_merge(const std::vector<std::string>& dirs, const std::string& out_dir, bool html) {
  // SIGINT or SIGTERM stops the merge between two steps (stop_if_interrupted), and the folder's
  // earlier merge comes back, rather than staying aside until the next command there.
  catch_interrupts();
  if (!dirs.empty())
    if (const auto first = raw_results(dirs[0]); first && campaign::is_campaign_json(first->doc))
      return cmd_merge_campaign(dirs, out_dir);
  std::vector<report::RunResults> shards;
  for (const auto& d : dirs) {
    shards.push_back(read_run_results(d, "merge"));
  }
  report::RunResults merged;
  try {
    merged = report::merge_shards(shards, dirs);
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  const RunInfo& info = merged.run;
  const std::vector<CaseResult>& list = merged.cases;
  check_apart(dirs, out_dir);
  for (const auto& d : dirs)
    check_copyable(report::run_folder(d) / "cases");
  const OutputFolder folder = output_folder(out_dir);
  const std::filesystem::path& out = folder.path;
  // Heatmaps and files of an earlier run or merge here would be taken for this merge's; they come
  // back if this merge fails halfway.
  EarlierOutputs earlier = set_aside_outputs(out, {"failures"});
  for (size_t k = 0; k < shards.size(); ++k) {
    const auto images = report::run_folder(dirs[k]) / "cases";
    std::error_code ec;
    if (std::filesystem::is_directory(images, ec))
      std::filesystem::copy(images, out / "cases",
                            std::filesystem::copy_options::recursive |
                                std::filesystem::copy_options::overwrite_existing);
    stop_if_interrupted();
  }
  fmt::print("merged {}: {}\n", report::count_text(shards.size(), "shard", "shards"),
             report::run_summary(list, info.seconds));
  write_outputs(out, info, list, html);
  earlier.keep_new();
  return report::any_fails_run(list) ? 1 : 0;
}

int cmd_report(const std::string& dir, const std::string& file) {
  if (dir.empty())
    throw InputError(
        "report: expected a run folder or its results.json, got \"\" (an empty or "
        "unset variable?)");
  report::RunResults results;
  const std::filesystem::path run_dir = report::run_folder(dir);
  // A folder of glrefcheck's is held while the page is written: a run still writing into it is
  // named (it is not a killed run), and no run starts there meanwhile.
  FolderLock lock;
  if (is_marked(run_dir)) {
    lock = lock_folder(run_dir, "report");
    // A run killed before it had GL left the folder's results aside: they are the folder's.
    std::error_code ec;
    if (std::filesystem::exists(run_dir / kEarlierFolder, ec)) {
      restore_earlier_outputs(run_dir);
      fmt::print(
          "put back {}'s earlier results, which a glrefcheck stopped before it finished "
          "had set aside\n",
          shown_path(run_dir.string()));
    }
  }
  results = read_run_results(dir, "report");
  const std::filesystem::path html =
      file.empty() ? run_dir / "report.html" : std::filesystem::path(file);
  // Only a page glrefcheck wrote (a run's, a merge's, a campaign's, report's: each stamps it
  // "glrefcheck report") and nobody edited since, in the run's folder or anywhere.
  check_replaceable(html, file.empty() ? "report" : "--out", "report");
  report::write_run_html(html, results, run_dir);
  fmt::print("wrote {}\n", html.string());
  return 0;
}

}  // namespace glrc::cli
