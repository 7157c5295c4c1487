// The runner side of cli/workers/workers.hpp, inside cli/ only: the pool of worker processes.
// pool.cpp holds the processes' side (start, poll, deaths, deadlines, stop);
// pool_messages.cpp the protocol's (each message a worker sends, and choosing the model).
// The pool sees a worker only through ChildProcess and the protocol's lines, so the tests run it
// on a fake worker (WorkerSettings::command) and on a wrapped real one (WorkerSettings::wrapper).
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/workers/process.hpp"
#include "cli/workers/workers.hpp"
#include "identify/model_cache.hpp"

namespace glrc::cli {

// `seconds` after `from`: a deadline.
inline Clock::time_point after(Clock::time_point from, double seconds) {
  return from + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

// What a worker is doing: one type per state, a worker in exactly one. Every state but Idle
// and Ended runs under a deadline (Worker::deadline); what a death or a deadline costs depends on
// the state alone (Pool::died, Pool::check_deadlines).
namespace worker_state {
struct Ended {};        // no process: not started yet, or its process ended or was killed
struct Starting {};     // started, making its GL context; Idle once it says hello
struct Idle {};         // waits for a case, for the run's model, or for the end of its input
struct Identifying {};  // identifies the implementation: the run's model comes from it
struct Checking {       // checks case `job` (an index into the pool's cases)
  size_t job = 0;
};
struct Imaging {  // writes the heatmaps of case `job`, whose verdict is in
  size_t job = 0;
};
}  // namespace worker_state
using WorkerState =
    std::variant<worker_state::Ended, worker_state::Starting, worker_state::Idle,
                 worker_state::Identifying, worker_state::Checking, worker_state::Imaging>;

struct Worker {
  ChildProcess process;
  std::string buffer;  // what it sent that is not yet a whole line
  WorkerState state;
  Clock::time_point started;   // when its state began (a case's seconds count from it)
  Clock::time_point deadline;  // when its state must end, unless Idle or Ended

  template <class State>
  bool in() const {
    return std::holds_alternative<State>(state);
  }
  // Under a deadline: starting, identifying, checking or imaging.
  bool busy() const { return !in<worker_state::Idle>() && !in<worker_state::Ended>(); }
  // Enters `next`, which must end within `seconds` from now.
  void enter(WorkerState next, double seconds) {
    state = next;
    started = Clock::now();
    deadline = after(started, seconds);
  }
};

// The argv that starts one worker: `command` (default: this program's `worker` subcommand),
// under `wrapper` when one is given, through /bin/sh so that the wrapper is written as on a
// shell's command line ("valgrind -q", "taskset -c 2", "gdb -batch -ex run -ex bt --args").
std::vector<std::string> worker_argv(const WorkerSettings& s);

// How long a pool's workers live.
enum class PoolLifetime {
  queue,       // each worker ends once the queue is empty
  persistent,  // they outlive the cases given so far and wait, idle, for add() and the next run()
               // (a campaign's batches and its shrinking use the same processes)
};

// The GL worker pool: owns its configuration (copies of the run's options and settings and of
// the callbacks), its workers and the queue of cases not yet handed out.
class Pool {
 public:
  Pool(std::vector<const Case*> cases, Options o, WorkerSettings s, OnStart on_start,
       std::function<void(size_t, CaseResult)> on_result, PoolLifetime lifetime);
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
  // pool.cpp: the processes.
  bool imaging() const;
  int next_deadline_ms() const;
  // A start-up deadline: at least 30 s, since starting a process and JIT-compiling shaders on a
  // loaded CI machine takes a while.
  double startup_seconds() const;
  void start(Worker& w, size_t slot);
  void read_from(Worker& w, size_t slot);
  // The one place a worker's death is handled: what it cost depends on the state it died in.
  void died(Worker& w, size_t slot);
  // The one place deadlines are handled: a worker past its state's deadline is killed, and what
  // that costs depends on the state.
  void check_deadlines();
  void stop(Worker& w, bool now);
  void finish(size_t k, CaseResult r);
  void images_lost(size_t k, const std::string& why) const;

  // pool_messages.cpp: the protocol.
  void handle(Worker& w, const std::string& line);
  // Case k's result from worker w: recorded, then w's heatmaps (`images`) or its next case.
  void result_in(Worker& w, size_t k, CaseResult r, bool images);
  void hello(Worker& w, const nlohmann::json& hello);
  void assign(Worker& w);
  void begin_model(Worker& w, const std::vector<std::string>& driver_files);
  void model_chosen(const ModelChoice& chosen);

  std::vector<const Case*> cases_;
  const Options o_;
  const WorkerSettings s_;
  const OnStart on_start_;
  const std::function<void(size_t, CaseResult)> on_result_;
  const PoolLifetime lifetime_;
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
