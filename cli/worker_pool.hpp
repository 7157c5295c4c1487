// The runner side of cli/workers.hpp, inside cli/ only: the pool of worker processes.
// worker_pool.cpp holds the processes' side (start, poll, deaths, deadlines, stop);
// worker_messages.cpp the protocol's (each message a worker sends, and choosing the model).
// The pool sees a worker only through ChildProcess and the protocol's lines, so the tests run it
// on a fake worker (WorkerSettings::command) and on a wrapped real one (WorkerSettings::wrapper).
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/process.hpp"
#include "cli/workers.hpp"
#include "identify/model_cache.hpp"

namespace glrc::cli {

// `seconds` after `from`: a deadline.
inline Clock::time_point after(Clock::time_point from, double seconds) {
  return from + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

struct Worker {
  ChildProcess process;
  std::string buffer;             // what it sent that is not yet a whole line
  bool ready = false;             // said hello
  bool identifying = false;       // asked to identify the implementation
  std::optional<size_t> job;      // index into cases of the case it is checking
  std::optional<size_t> imaging;  // the case whose verdict came and whose heatmaps it writes
  Clock::time_point deadline;
  Clock::time_point started;
};

// The argv that starts one worker: `command` (default: this program's `worker` subcommand),
// under `wrapper` when one is given, through /bin/sh so that the wrapper is written as on a
// shell's command line ("valgrind -q", "taskset -c 2", "gdb -batch -ex run -ex bt --args").
std::vector<std::string> worker_argv(const WorkerSettings& s);

class Pool {
 public:
  // `persistent`: the workers outlive the cases given so far and wait, idle, for add() and the
  // next run() (a campaign's batches and its shrinking use the same processes); otherwise each
  // worker ends once the queue is empty.
  Pool(std::vector<const Case*> cases, const Options& o, const WorkerSettings& s,
       const OnStart& on_start, const std::function<void(size_t, CaseResult)>& on_result,
       bool persistent = false);
  ~Pool();
  Pool(const Pool&) = delete;
  Pool& operator=(const Pool&) = delete;

  // Until every verdict is in and every heatmap written, or the interrupt fd is readable.
  void run();
  // More cases, their indices following the earlier ones'; checked by the next run().
  void add(const std::vector<const Case*>& more);
  // Whether the interrupt fd is readable (the run is to stop).
  bool interrupted() const;

 private:
  // worker_pool.cpp: the processes.
  bool imaging() const;
  int next_deadline_ms() const;
  void start(Worker& w, size_t slot);
  void read_from(Worker& w, size_t slot);
  void died(Worker& w, size_t slot);
  void check_deadlines();
  void stop(Worker& w, bool now);
  void finish(size_t k, CaseResult r);
  void images_lost(size_t k, const std::string& why) const;

  // worker_messages.cpp: the protocol.
  void handle(Worker& w, const std::string& line);
  // Case k's result from worker w: recorded, then w's heatmaps (`images`) or its next case.
  void result_in(Worker& w, size_t k, CaseResult r, bool images);
  void hello(Worker& w, const nlohmann::json& hello);
  void assign(Worker& w);
  void begin_model(Worker& w, const std::vector<std::string>& driver_files);
  void model_chosen(const ModelChoice& chosen);

  std::vector<const Case*> cases_;
  bool persistent_ = false;
  const Options& o_;
  const WorkerSettings& s_;
  const OnStart& on_start_;
  const std::function<void(size_t, CaseResult)>& on_result_;
  std::deque<size_t> queue_;
  std::vector<Worker> workers_;
  std::vector<std::string> argv_, env_;
  std::string options_line_;
  size_t done_ = 0;
  bool started_ = false;  // the first worker said hello
  gl::GlInfo gl_;         // its GL strings
  identify::ModelCacheSlot cache_;
  std::optional<ModelChoice> model_;  // what judges every case, once known
  int startup_deaths_ = 0;
};

}  // namespace glrc::cli
