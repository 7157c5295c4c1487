// GL in worker processes. A driver that crashes or hangs takes its process with it, not the
// run: `run` starts worker processes (`glrefcheck worker`, the same binary), each making one GL
// context and checking many cases with it, since a context costs 20 to 170 ms here. A case whose
// worker dies is `Crash`, one that runs past the timeout is `Timeout` (its worker is killed);
// either way a fresh worker takes the next case. A failing case's verdict comes before its
// heatmaps, so a worker that dies or times out writing them costs the heatmaps, not the verdict.
//
// Protocol, one JSON document per line. On the worker's stdin: the options (options_json), then
// {"index": k, "file": path, "case": the loaded case (casefile/wire.hpp, so that the worker
// does not parse the file again), "name": case name, "images": bool, "model": {"subpixel_bits",
// "planes", "tie_break"}} per case, or {"identify": true}; end of input means stop. On its
// stdout: {"hello": {every gl::GlInfo field, "driver_files": [paths]}} (GL strings, subpixel
// bits, the initial provoking vertex, whether gl_PrimitiveID comes from a geometry shader, and
// warnings: what the implementation got wrong while the context set up; cli/workers/protocol.hpp)
// or
// {"error": "one line"} once the context exists, then
// {"index": k, "result": CaseResult, "images": true when heatmaps follow} per case (the verdict
// comes first), then for a case with heatmaps {"images_done": k} or {"images_done": k,
// "images_error": "one line"} once they are written, and {"identified": model} or
// {"identify_error": "one line"} per identify. The worker's own stdout and stderr (and the
// driver's messages) go to a log file: a crash report quotes its last lines.
//
// The model: the runner decides it once per run, from the command line, or from the model cache
// (identify/model_cache.hpp) for the first worker's GL strings and driver files, or else by asking
// the first worker to identify the implementation (about 0.5 s); the other workers wait for it.
// Every case of the run then carries that one model.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/session.hpp"
#include "core/case.hpp"
#include "core/result.hpp"
#include "gl_harness/gl_harness.hpp"

namespace glrc::cli {

// The child side: `glrefcheck worker`. Exit 0 at end of input, 2 when GL is unavailable.
int cmd_worker();

struct WorkerSettings {
  int jobs = 1;
  double timeout = 60;                                           // seconds per case
  std::vector<std::pair<std::string, std::string>> environment;  // added for the children only
  std::filesystem::path log_dir;                                 // worker-<n>.log
  // Whether a case, should it fail, gets its heatmaps (about 0.8 s per case): by default not
  // those the baseline already expects to fail.
  std::function<bool(const Case&)> images = [](const Case&) { return true; };
  // Called when a case's verdict came but its heatmaps did not (the worker failed to write them,
  // died, or took longer than `timeout` for them), with its index and one line saying why.
  std::function<void(size_t, const std::string&)> images_lost;
  // Called with a case's index just before its verdict (on_result) when its heatmaps follow,
  // and once they are written: a run's journal records both, so that a run killed between them
  // checks that case again on --resume rather than keep it without its heatmaps.
  std::function<void(size_t)> images_follow;
  std::function<void(size_t)> images_written;
  // The model that judges every case when it is already known (a resumed run keeps the model it
  // started with); otherwise the runner chooses it as above.
  std::optional<ModelChoice> model;
  // Readable once the run is to stop (SIGINT, SIGTERM): no more cases are handed out and the
  // workers are killed; run_in_workers returns with the cases finished so far reported.
  int interrupt_fd = -1;
  // The worker program and its arguments; empty: this program's `worker` subcommand. Anything
  // that speaks the protocol above will do (the tests' fake workers do).
  std::vector<std::string> command;
  // A command the workers run under, as typed on a shell (`run --worker-wrapper`): a debugger,
  // valgrind, taskset, rr. Its words come before the worker's command; "" for none. The
  // wrapper's own processes are killed with the worker (the worker's process group).
  std::string wrapper;
};

// Checks `cases` in worker processes. `on_start` gets the first worker's GL strings and the
// model that judges every case before any result (throw from it to stop the run); `on_result`
// gets each result as it arrives (in completion order), with its index into `cases`. Throws
// InputError when no worker can make a GL context. Workers die with the runner (a kill -9 of it
// included: PR_SET_PDEATHSIG) and are not in its process group, so a Ctrl-C on the terminal
// reaches the runner only, which then ends them itself. An identification that fails (the worker
// dies, times out or cannot draw a probe) leaves the run to the fixed default model
// (fallback_model), which the model's source says.
using OnStart = std::function<void(const gl::GlInfo&, const ModelChoice&)>;
void run_in_workers(const std::vector<const Case*>& cases, const Options& o,
                    const WorkerSettings& s, const OnStart& on_start,
                    const std::function<void(size_t, CaseResult)>& on_result);

class Pool;

// Workers kept between batches of cases: `fuzz` checks a batch of generated cases, then the
// shrinker's candidates, then the next batch, on the same processes and GL contexts (a worker
// costs 0.1 to 0.5 s to start). Deaths, timeouts and the model are as in run_in_workers; the
// model is chosen once, at the first batch, and `on_start` is called then.
class WorkerSession {
 public:
  WorkerSession(const Options& o, const WorkerSettings& s, OnStart on_start);
  ~WorkerSession();
  WorkerSession(const WorkerSession&) = delete;
  WorkerSession& operator=(const WorkerSession&) = delete;

  // One result per case, in order. The cases need live only until this returns. Once
  // interrupted() the cases not checked come back as Skip with the message "not checked:
  // interrupted". Throws as run_in_workers.
  std::vector<CaseResult> check(const std::vector<const Case*>& cases);
  bool interrupted() const;

 private:
  std::vector<std::optional<CaseResult>> results_;
  size_t offset_ = 0;  // the pool's index of results_[0]
  std::unique_ptr<Pool> pool_;
};

}  // namespace glrc::cli
