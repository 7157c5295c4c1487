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
  // Model: "identified" (what `identify` finds for the implementation), "ideal" (the exact
  // reference with the choices below), or a bit-exact model of one driver ("llvmpipe",
  // "softpipe").
  std::string model = "identified";
  int subpixel_bits = 8;
  Planes planes = Planes::unsnapped;
  TieBreak tie_break = TieBreak::bottom_left;
  // Whether --subpixel-bits, --planes or --tie-break was on the command line: then the
  // reference's model is the command line's, whatever --model says.
  bool model_given = false;
  // GL
  gl::Backend backend = gl::Backend::osmesa;
  std::string driver = "llvmpipe";
  int device = 0;
  // Verdict
  ToleranceMode tolerance = ToleranceMode::spec;  // spec or exact (ulps: the numbers below)
  std::optional<int> spec_subpixel_bits;          // overrides GL_SUBPIXEL_BITS as reported
  std::optional<double> varying_ulps, depth_ulps;
  bool strict_coverage = false;
  std::string baseline, out = "out";
  // Mesa CI's expectations beyond the baseline: regular expressions, one per line.
  std::string flakes, skips;
  // A Mesa install tree to run instead of the system's (scripts/mesa-fetch.sh makes one).
  std::string mesa;
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
// model (model, subpixel_bits, planes, tie_break, model_given), GL (backend, driver, device),
// the verdict (tolerance, strict_coverage, and spec_subpixel_bits, varying_ulps, depth_ulps
// when set) and out; not the runner's own (paths, jobs, ...: cli/journal.cpp adds those).
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

// --model's choices: identified, ideal, and the driver models' names.
std::vector<std::string> model_choices();

// The exact reference's model from subpixel_bits, planes and tie_break.
Model model_of(const Options& o);
// Sets subpixel_bits, planes and tie_break to `m` (so that model_of(o) is m).
void set_model(Options& o, const Model& m);

// RunInfo::verdict_inputs of a run judged under `o`: strict coverage, the fixed ULPs, and the
// --baseline, --flakes and --skips files as they read now (their SHA-256; on --resume, the
// copies the run began with). InputError when one cannot be read.
std::map<std::string, std::string> verdict_inputs(const Options& o);

// InputError naming the option when the options cannot judge a case (check::judging_problem:
// a driver model under the specification's allowance, exact with ULP thresholds): before any
// work, in every command that judges.
void check_judgeable(const Options& o);

// The model when the command line decides it, nullopt when the implementation must be
// identified (--model identified, the default, with no --subpixel-bits, --planes, --tie-break).
// With a driver model (--model llvmpipe) the reference's model only labels ties and bands.
std::optional<ModelChoice> model_from_command_line(const Options& o);
// The fixed default model (the command line's choices), when identification failed: `why`.
ModelChoice fallback_model(const Options& o, const std::string& why);
// How a case is judged, from the options: model_of(o) is the model (set_model sets the one that
// judges), --model names a driver model, and the tolerance options.
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
