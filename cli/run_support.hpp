// What `run` and `merge` need around the run itself: the inputs checked before any work (case
// names, UTF-8 paths, expectation files), the number of workers, and the run files written at
// the end.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/mesa_prefix.hpp"
#include "cli/session.hpp"
#include "cli/workers/workers.hpp"
#include "core/result.hpp"
#include "report/report.hpp"

namespace glrc::cli {

// --flakes or --skips: the patterns of `file` (none when empty); InputError naming `option`.
Patterns load_patterns(const std::string& file, const char* option);

// Every case of the run can be written into results.json, the journal and the CSVs as it is:
// refused up front otherwise (InputError), never a half-written run.
void check_case_names(const std::vector<Case>& cases);
// The options that name files are recorded in JSON (the journal), so UTF-8 only: InputError.
void check_paths_utf8(const Options& o);

// A file's bytes; empty when it cannot be read.
std::string read_file(const std::filesystem::path& file);
// Whether `inner` is `outer` or lies inside it (both as they resolve now).
bool inside(const std::filesystem::path& inner, const std::filesystem::path& outer);
// The same for paths resolved already (std::filesystem::weakly_canonical): each of many paths
// resolved once, not once per comparison (a suite's cases against the run's outputs).
bool inside_resolved(const std::filesystem::path& inner, const std::filesystem::path& outer);

// InputError when one of `inputs` (what it is, its path: "this run's case files", a case file)
// lies among what a run, merge or campaign into `out` replaces (run_output_names() and `also`):
// it would be gone with them. `option` names the output folder in the message.
void check_inputs_outside(const std::filesystem::path& out, const std::vector<std::string>& also,
                          const std::vector<std::pair<std::string, std::string>>& inputs,
                          const std::string& option);

// The expectation files as this run read them: copied into the run folder, since --resume must
// judge by the same ones (the files named may change after the run began).
struct Inputs {
  std::vector<std::pair<std::string, std::string>> files;  // name in kInputsFolder, text
};

// The cores this process may run on (taskset, cgroups' cpusets).
int available_cores();
// --jobs, or one worker per available core; more than the cores only with --jobs-force (a
// note says so otherwise).
int workers_for(const Options& o);

// The worker settings `run` and `fuzz` share: workers_for(o) workers, their logs in out/logs,
// --timeout, --worker-wrapper, the interrupt pipe, the Mesa prefix's environment and the
// huge-page malloc tunable. Sets o.threads, when 0, to each worker's share of the cores (workers
// times threads never more than the cores). The caller adds images and the model.
WorkerSettings worker_settings(Options& o, const std::filesystem::path& out, int interrupt_fd,
                               const std::optional<MesaPrefix>& prefix);

// results.json, results.csv, failures.csv, junit.xml (and report.html with `html`) in `out`,
// and the line saying so.
void write_outputs(const std::filesystem::path& out, const RunInfo& info,
                   const std::vector<CaseResult>& results, bool html);

// A run's results.json (or its folder) read back for `command` (compare, merge, report): its
// problems one line (InputError, "<command>: ..."), and a note on stderr when it holds no stamp
// (an older glrefcheck's, or made by hand: read as it stands, which a stamped one that a
// person edited is not).
report::RunResults read_run_results(const std::string& path, const std::string& command);
// InputError when the results folder of `path` is not one to read now: held by a live glrefcheck
// (lock_holder), holding what a glrefcheck stopped before it finished set aside (and perhaps half
// of its own outputs), or a killed run's journal without results.
void check_settled(const std::string& path, const std::string& command);
// That note, for the results folder or file `path`.
void note_unstamped(const std::string& path);

// A path under the working folder as a relative one, so logs and READMEs stay short.
std::string shown_path(const std::string& path);

}  // namespace glrc::cli
