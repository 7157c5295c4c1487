// What the subcommands share: options, loading cases and baselines, opening the GL side, and
// checking one case end to end.
#pragma once

#include <unistd.h>

#include <fmt/core.h>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "check/check.hpp"
#include "cli/option_groups.hpp"
#include "core/case.hpp"
#include "core/model.hpp"
#include "core/result.hpp"
#include "gl_harness/gl_harness.hpp"
#include "identify/identify.hpp"
#include "report/expectations.hpp"

namespace glrc::typed_json {
class Reader;
}

namespace glrc::cli {

using identify::ModelChoice;
using report::Baseline;
using report::Patterns;
using report::Regex;

// Bad input: one line on stderr, exit 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Options {
  std::vector<std::string> paths;
  std::string filter;
  // What judges, on which GL, by which tolerance (cli/option_groups.hpp).
  ModelOptions model;
  GlOptions gl;
  VerdictOptions verdict;
  std::string baseline, out = "out";
  // Mesa CI's expectations beyond the baseline: regular expressions, one per line.
  std::string flakes, skips;
  // Worker processes: how many in parallel, and how long one case may take.
  int jobs = 0;  // 0: one per available core
  // More workers than cores only when asked: each holds a GL context (25 MB and up) and they
  // would only take turns on the cores.
  bool jobs_force = false;
  double timeout = 60;
  // Threads drawing the reference: 0 for the default, every core this process may use (`run`:
  // the cores shared among its workers). How, not what: --resume takes it from its own line.
  int threads = 0;
  // A command the workers run under (cli/workers/workers.hpp WorkerSettings::wrapper); "" for none.
  // How the run is carried out, not what it checks: --resume takes it from its own command line.
  std::string worker_wrapper;
  // Sharding as deqp-runner does it: every `fraction`-th case, starting at `fraction_start`
  // (1-based, like GitLab's CI_NODE_INDEX).
  int fraction = 1, fraction_start = 1;
  bool html = false;
  // run --resume DIR: continue the run recorded in DIR/journal.jsonl.
  std::string resume;
};

// What a worker process needs of the options, as JSON (the options travel on its stdin): the
// groups' fields (ModelOptions, GlOptions, VerdictOptions: their write()), out and threads; not
// the runner's own (paths, jobs, ...: cli/journal.cpp adds those).
// nlohmann's ADL conversions; from_json checks each field as the command line checks it and
// throws InputError ("options.subpixel_bits: expected a whole number from 0 to 16, got 99").
void to_json(nlohmann::json& j, const Options& o);
void from_json(const nlohmann::json& j, Options& o);
// from_json with a source and path for the messages ("<r's source>: options.model: ..."):
// sets the fields to_json writes, leaving the others as they are.
void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path,
          Options& o);
// to_json as one line, and back (the parse error of text that is no JSON is nlohmann's
// json::parse_error; a bad field is InputError naming "the worker's options").
std::string options_json(const Options& o);
Options options_from_json(const std::string& text);

// RunInfo::verdict_inputs of a run judged under `o`: strict coverage, the fixed ULPs, and the
// --baseline, --flakes and --skips files as they read now (their SHA-256; on --resume, the
// copies the run began with). InputError when one cannot be read.
std::map<std::string, std::string> verdict_inputs(const Options& o);

// What the options judge by (model, driver model, tolerance), built and checked here only:
// InputError naming the option when they cannot judge a case (check::judging_problem: a driver
// model under the specification's allowance, exact with ULP thresholds). Every command that
// judges calls it before any work.
check::Judging judging(const Options& o);

// The model when the command line decides it, nullopt when the implementation must be
// identified (--model identified, the default, with no --subpixel-bits, --planes, --tie-break).
// With a driver model (--model llvmpipe) the reference's model only labels ties and bands.
std::optional<ModelChoice> model_from_command_line(const Options& o);
// The fixed default model (the command line's choices), when identification failed: `why`.
ModelChoice fallback_model(const Options& o, const std::string& why);
// judging(o) and how a case is checked (--threads): o.model.reference_model() is the model
// (set_reference_model sets the one that judges).
check::CheckOptions check_options(const Options& o);
// The cases named on the command line (default cases/), filtered; InputError when none.
std::vector<Case> load_cases(const Options& o);
// --baseline, or an empty one; InputError for a bad file.
Baseline load_baseline(const Options& o);
std::unique_ptr<gl::Renderer> open_renderer(const Options& o);
// The run's description; `model` is what judged it (model_from_command_line or identified).
RunInfo run_info(const Options& o, const gl::GlInfo& gl, const ModelChoice& model);

// Progress on a terminal only: CI logs get the per-case lines and nothing else.
class Progress {
 public:
  Progress() : on_(isatty(STDERR_FILENO) && !std::getenv("CI")) {}
  void show(size_t k, size_t n, const std::string& name) const {
    if (on_) fmt::print(stderr, "\r\033[K[{}/{}] {}", k + 1, n, name), std::fflush(stderr);
  }
  void clear() const {
    if (on_) fmt::print(stderr, "\r\033[K"), std::fflush(stderr);
  }

 private:
  bool on_;
};

// Creates (or checks and claims) the output folder before any case runs, so that a folder that
// cannot be written, that holds what glrefcheck did not write, or that another glrefcheck is
// writing into, is one line and exit 2 at once, not a lost run or lost files; held (locked)
// while the result lives. In cli/output_dir.cpp.
struct OutputFolder;
OutputFolder output_folder(const std::string& out, const std::string& option = "--out");

}  // namespace glrc::cli
