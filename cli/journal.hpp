// The run journal, <out>/journal.jsonl: what `run` has done so far, one JSON document per line,
// each line handed to the kernel with one write(2) as it happens, so that a run killed at any
// moment (kill -9 included) leaves every finished case on disk and `run --resume` can go on.
//
// Every line ends in "digest": the SHA-256 of the previous line's digest and the line without
// it, so that --resume refuses a journal edited by hand or holding another run's lines (version
// 3; earlier versions are refused).
//
// Line 1: {"glrefcheck_journal": 2, "options": {every option of the run}, "files": [the case
// files, after --filter, before sharding, in order], "file_digests": [each one's content,
// report::content_digest]}. Once GL is known: {"run": results.json's
// "run", "model": {...}, "model_source": "..."}, so a resumed run is judged by the same model.
// Per case: {"index": k (into the run's cases, after sharding), "at": seconds since the run
// began, "result": the CaseResult as in results.json}, with "heatmaps": "follow" when its
// heatmaps are being written, then {"index": k, "heatmaps": "written"} once they are; a case
// whose heatmaps are then lost is recorded again, its message saying so, and the later line
// counts (a later line of another name or verdict is refused). A case whose heatmaps were
// still to follow when the run stopped is not done: --resume checks it again, so that no case
// of a finished run lacks its heatmaps without a word. A last line cut short by a kill is
// ignored.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cli/session.hpp"
#include "core/result.hpp"

namespace glrc::cli {

inline constexpr int kJournalVersion = 3;

struct JournalContents {
  Options options;
  std::vector<std::string> files;
  // Each file's content as the run began (report::content_digest), for --resume to notice an
  // edit; empty in a journal written before it was recorded.
  std::vector<std::string> file_digests;
  // What judged the run besides GL and the model as it began (RunInfo::verdict_inputs: the
  // expectation files' digests among them), for --resume to notice a copy edited since; empty
  // in a journal written before it was recorded.
  std::map<std::string, std::string> verdict_inputs;
  std::optional<RunInfo> run;
  std::optional<ModelChoice> model;
  std::map<size_t, CaseResult> results;
  size_t heatmaps_cut = 0;  // cases left out of `results`: stopped while writing their heatmaps
  double elapsed = 0;       // the latest "at": how long the run had been going when it stopped
};

class Journal {
 public:
  // Starts a new journal (replacing any) with its first line.
  static Journal start(const std::filesystem::path& dir, const Options& o,
                       const std::vector<std::string>& files,
                       const std::vector<std::string>& file_digests,
                       const std::map<std::string, std::string>& verdict_inputs);
  // Appends to an existing one.
  static Journal reopen(const std::filesystem::path& dir);
  Journal(Journal&& other) noexcept
      : fd_(other.fd_), file_(std::move(other.file_)), last_digest_(std::move(other.last_digest_)) {
    other.fd_ = -1;
  }
  Journal(const Journal&) = delete;
  ~Journal();

  void record_start(const RunInfo& info, const ModelChoice& model);
  // Whether a case's heatmaps are being written after its verdict.
  enum class Heatmaps { none, follow };
  void record_result(size_t index, const CaseResult& r, double at,
                     Heatmaps heatmaps = Heatmaps::none);
  void record_heatmaps_written(size_t index);

 private:
  Journal(int fd, std::filesystem::path file) : fd_(fd), file_(std::move(file)) {}
  void append(std::string line);
  int fd_;
  std::filesystem::path file_;
  std::string last_digest_;  // the last line's, which the next line's digest chains on
};

// InputError naming the file and line for a journal that is missing or malformed.
JournalContents read_journal(const std::filesystem::path& dir);

}  // namespace glrc::cli
