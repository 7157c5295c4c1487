// The worker pool's processes: starts workers, hands out cases one at a time (so a slow case
// never holds up a queue behind it), watches for deaths and timeouts with poll().
#include "cli/workers/pool.hpp"

#include <poll.h>
#include <signal.h>

#include <fmt/core.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <utility>
#include <variant>

#include "cli/workers/protocol.hpp"

namespace glrc::cli {

namespace {

// std::visit with one lambda per state.
template <class... Handlers>
struct PerState : Handlers... {
  using Handlers::operator()...;
};
// Clang 14 deduces no aggregate's template arguments (C++20's P1816) without a guide.
template <class... Handlers>
PerState(Handlers...) -> PerState<Handlers...>;

}  // namespace

std::vector<std::string> worker_argv(const WorkerSettings& s) {
  std::vector<std::string> argv = s.command;
  if (argv.empty()) argv = {self_executable(), "worker"};
  if (s.wrapper.empty()) return argv;
  // sh -c 'exec WRAPPER "$@"' glrefcheck-worker COMMAND...: the shell splits the wrapper as a
  // user typed it, the command's words pass untouched, and exec leaves no shell between the
  // runner and the wrapper (a stalled worker's parent is the runner).
  std::vector<std::string> wrapped = {"/bin/sh", "-c", "exec " + s.wrapper + " \"$@\"",
                                      "glrefcheck-worker"};
  wrapped.insert(wrapped.end(), argv.begin(), argv.end());
  return wrapped;
}

Pool::Pool(std::vector<const Case*> cases, Options o, WorkerSettings s, OnStart on_start,
           std::function<void(size_t, CaseResult)> on_result, PoolLifetime lifetime)
    : cases_(std::move(cases)),
      o_(std::move(o)),
      s_(std::move(s)),
      on_start_(std::move(on_start)),
      on_result_(std::move(on_result)),
      lifetime_(lifetime) {
  for (size_t k = 0; k < cases_.size(); ++k)
    queue_.push_back(k);
  options_line_ = options_json(o_) + "\n";
  env_ = environment_with(s_.environment);
  argv_ = worker_argv(s_);
}

Pool::~Pool() {
  for (auto& w : workers_)
    stop(w, true);
}

void Pool::add(const std::vector<const Case*>& more) {
  for (const Case* c : more) {
    queue_.push_back(cases_.size());
    cases_.push_back(c);
  }
}

void Pool::run() {
  if (interrupted()) return;
  if (workers_.empty()) {
    const size_t jobs = size_t(std::max(s_.jobs, 1));
    const size_t n = lifetime_ == PoolLifetime::persistent ? jobs : std::min(jobs, cases_.size());
    workers_.resize(n);
    for (size_t k = 0; k < n; ++k)
      start(workers_[k], k);
  } else {
    // Persistent workers from the last run: idle ones get cases, ended ones start again.
    for (size_t k = 0; k < workers_.size() && !queue_.empty(); ++k) {
      Worker& w = workers_[k];
      if (!w.process.running())
        start(w, k);
      else if (w.in<worker_state::Idle>())
        assign(w);
    }
  }
  while (done_ < cases_.size() || imaging()) {
    std::vector<pollfd> fds;
    std::vector<size_t> owner;
    for (size_t k = 0; k < workers_.size(); ++k)
      if (workers_[k].process.running()) {
        fds.push_back({workers_[k].process.output_fd(), POLLIN, 0});
        owner.push_back(k);
      }
    if (fds.empty()) throw std::runtime_error("no worker left with cases to check");
    if (s_.interrupt_fd >= 0) fds.push_back({s_.interrupt_fd, POLLIN, 0});
    const int ready = poll(fds.data(), fds.size(), next_deadline_ms());
    if (ready < 0 && errno != EINTR) throw std::runtime_error("poll failed");
    // Stop before reading more: a result that comes in now is checked again on --resume.
    if (interrupted()) {
      for (auto& w : workers_)
        stop(w, true);
      return;
    }
    for (size_t i = 0; i < owner.size(); ++i)
      if (fds[i].revents) read_from(workers_[owner[i]], owner[i]);
    check_deadlines();
  }
}

bool Pool::imaging() const {
  return std::any_of(workers_.begin(), workers_.end(),
                     [](const Worker& w) { return w.in<worker_state::Imaging>(); });
}

bool Pool::interrupted() const {
  if (s_.interrupt_fd < 0) return false;
  pollfd p{s_.interrupt_fd, POLLIN, 0};
  return poll(&p, 1, 0) > 0;
}

int Pool::next_deadline_ms() const {
  std::optional<Clock::time_point> next;
  for (const auto& w : workers_)
    if (w.busy() && (!next || w.deadline < *next)) next = w.deadline;
  if (!next) return -1;
  const double ms = std::chrono::duration<double, std::milli>(*next - Clock::now()).count();
  return int(std::clamp(std::ceil(ms), 0.0, 3.6e6));
}

double Pool::startup_seconds() const {
  return std::max(s_.timeout, 30.0);
}

void Pool::start(Worker& w, size_t slot) {
  w = Worker{};
  w.process = ChildProcess(argv_, env_, s_.log_dir / fmt::format("worker-{}.log", slot + 1));
  // A driver can hang making its context too.
  w.enter(worker_state::Starting{}, startup_seconds());
  // A worker that died cannot be written to: reading its end of the pipe will say so.
  (void)w.process.send(options_line_);
}

void Pool::read_from(Worker& w, size_t slot) {
  const long n = w.process.read_some(w.buffer);
  if (n < 0) return;
  if (n == 0) return died(w, slot);
  for (size_t eol; (eol = w.buffer.find('\n')) != std::string::npos;) {
    const std::string line = w.buffer.substr(0, eol);
    w.buffer.erase(0, eol + 1);
    handle(w, line);
    if (!w.process.running()) return;
  }
}

void Pool::died(Worker& w, size_t slot) {
  namespace state = worker_state;
  const std::string how = w.process.wait();
  const std::string tail = w.process.log_tail();
  const std::string log_ends = tail.empty() ? "" : "; its log ends: " + tail;
  const WorkerState was = std::exchange(w.state, state::Ended{});
  std::visit(PerState{
                 [&](state::Starting) {
                   // It died making its context. Once is a broken driver or prefix, not a case.
                   if (!started_ || ++startup_deaths_ > 3)
                     throw InputError("a GL worker " + how + " before it could make a GL context" +
                                      log_ends);
                 },
                 [&](state::Identifying) { model_chosen(fallback_model(o_, "its worker " + how)); },
                 [&](state::Checking checking) {
                   finish(checking.job,
                          unfinished_result(*cases_[checking.job], Status::crash,
                                            "worker " + how + log_ends, seconds_since(w.started)));
                 },
                 [&](state::Imaging imaging) {
                   images_lost(imaging.job, "heatmaps not written: the worker " + how +
                                                " writing them" + log_ends);
                 },
                 [](state::Idle) {},
                 [](state::Ended) {},
             },
             was);
  if (!queue_.empty()) start(w, slot);
}

void Pool::check_deadlines() {
  namespace state = worker_state;
  const auto now = Clock::now();
  for (size_t k = 0; k < workers_.size(); ++k) {
    Worker& w = workers_[k];
    if (!w.busy() || now < w.deadline) continue;
    w.process.kill_now();
    const WorkerState was = std::exchange(w.state, state::Ended{});
    std::visit(
        PerState{
            [&](state::Starting) {
              throw InputError(fmt::format("a GL worker took over {} s to make a GL context",
                                           startup_seconds()));
            },
            [&](state::Identifying) {
              model_chosen(fallback_model(
                  o_, fmt::format("no answer after {} s; worker killed", startup_seconds())));
            },
            [&](state::Checking checking) {
              finish(checking.job,
                     unfinished_result(
                         *cases_[checking.job], Status::timeout,
                         fmt::format("no result after {} s (--timeout); worker killed", s_.timeout),
                         seconds_since(w.started)));
            },
            [&](state::Imaging imaging) {
              images_lost(imaging.job, fmt::format("heatmaps not written: not done after {} s "
                                                   "(--timeout); worker killed",
                                                   s_.timeout));
            },
            [](state::Idle) {},
            [](state::Ended) {},
        },
        was);
    if (!queue_.empty()) start(w, k);
  }
}

// Ends a worker: closing its input makes it exit; `now` kills it instead.
void Pool::stop(Worker& w, bool now) {
  if (!w.process.running()) return;
  if (!now) return w.process.finish();
  w.process.kill_now();
  w.state = worker_state::Ended{};
}

void Pool::finish(size_t k, CaseResult r) {
  ++done_;
  on_result_(k, std::move(r));
}

void Pool::images_lost(size_t k, const std::string& why) const {
  if (s_.images_lost) s_.images_lost(k, why);
}

void run_in_workers(const std::vector<const Case*>& cases, const Options& o,
                    const WorkerSettings& s, const OnStart& on_start,
                    const std::function<void(size_t, CaseResult)>& on_result) {
  if (cases.empty()) return;
  // A worker that dies while we write to it must not take the runner with it.
  signal(SIGPIPE, SIG_IGN);
  std::filesystem::create_directories(s.log_dir);
  Pool pool(cases, o, s, on_start, on_result, PoolLifetime::queue);
  pool.run();
}

WorkerSession::WorkerSession(const Options& o, const WorkerSettings& s, OnStart on_start) {
  signal(SIGPIPE, SIG_IGN);
  std::filesystem::create_directories(s.log_dir);
  auto on_result = [this](size_t k, CaseResult r) {
    if (k >= offset_ && k - offset_ < results_.size()) results_[k - offset_] = std::move(r);
  };
  pool_ = std::make_unique<Pool>(std::vector<const Case*>{}, o, s, std::move(on_start),
                                 std::move(on_result), PoolLifetime::persistent);
}

WorkerSession::~WorkerSession() = default;

bool WorkerSession::interrupted() const {
  return pool_->interrupted();
}

std::vector<CaseResult> WorkerSession::check(const std::vector<const Case*>& cases) {
  results_.assign(cases.size(), std::nullopt);
  pool_->add(cases);
  pool_->run();
  offset_ += cases.size();
  std::vector<CaseResult> out;
  for (size_t k = 0; k < cases.size(); ++k) {
    if (results_[k]) {
      out.push_back(std::move(*results_[k]));
      continue;
    }
    CaseResult r;
    r.name = cases[k]->name, r.description = cases[k]->description;
    r.status = r.outcome = Status::skip;
    r.message = "not checked: interrupted";
    out.push_back(std::move(r));
  }
  results_.clear();
  return out;
}

}  // namespace glrc::cli
