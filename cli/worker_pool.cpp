// The runner side of cli/workers.hpp: starts workers, hands out cases one at a time (so a slow
// case never holds up a queue behind it), watches for deaths and timeouts with poll().
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <fmt/core.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <deque>
#include <optional>

#include <nlohmann/json.hpp>

#include "cli/process.hpp"
#include "cli/worker_protocol.hpp"
#include "cli/workers.hpp"
#include "identify/model_cache.hpp"
#include "report/report.hpp"

namespace glrc::cli {

namespace {

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

class Pool {
 public:
  Pool(const std::vector<const Case*>& cases, const Options& o, const WorkerSettings& s,
       const OnStart& on_start, const std::function<void(size_t, CaseResult)>& on_result)
      : cases_(cases), o_(o), s_(s), on_start_(on_start), on_result_(on_result) {
    for (size_t k = 0; k < cases.size(); ++k)
      queue_.push_back(k);
    options_line_ = options_json(o) + "\n";
    env_ = environment_with(s.environment);
    exe_ = self_executable();
  }

  ~Pool() {
    for (auto& w : workers_)
      stop(w, true);
  }

  void run() {
    const size_t n = std::min<size_t>(size_t(std::max(s_.jobs, 1)), cases_.size());
    workers_.resize(n);
    if (interrupted()) return;
    for (size_t k = 0; k < n; ++k)
      start(workers_[k], k);
    // Until every verdict is in and every heatmap written.
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
      const int wait_ms = next_deadline_ms();
      const int ready = poll(fds.data(), fds.size(), wait_ms);
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

 private:
  // `seconds` after `from`: a deadline.
  static Clock::time_point after(Clock::time_point from, double seconds) {
    return from +
           std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  }

  bool imaging() const {
    return std::any_of(workers_.begin(), workers_.end(),
                       [](const Worker& w) { return w.process.running() && w.imaging; });
  }

  // Busy: a case, heatmaps, identification or its start-up, each under a deadline.
  static bool busy(const Worker& w) { return w.job || w.imaging || !w.ready || w.identifying; }

  bool interrupted() const {
    if (s_.interrupt_fd < 0) return false;
    pollfd p{s_.interrupt_fd, POLLIN, 0};
    return poll(&p, 1, 0) > 0;
  }

  int next_deadline_ms() const {
    std::optional<Clock::time_point> next;
    for (const auto& w : workers_)
      if (w.process.running() && busy(w) && (!next || w.deadline < *next)) next = w.deadline;
    if (!next) return -1;
    const double ms = std::chrono::duration<double, std::milli>(*next - Clock::now()).count();
    return int(std::clamp(std::ceil(ms), 0.0, 3.6e6));
  }

  void start(Worker& w, size_t slot) {
    w = Worker{};
    w.process =
        ChildProcess({exe_, "worker"}, env_, s_.log_dir / fmt::format("worker-{}.log", slot + 1));
    w.started = Clock::now();
    // A driver can hang making its context too; that gets at least 30 s, since starting a
    // process and JIT-compiling shaders on a loaded CI machine takes a while.
    w.deadline = after(w.started, std::max(s_.timeout, 30.0));
    send(w, options_line_);
  }

  // A worker that died cannot be written to: reading its end of the pipe will say so.
  static void send(Worker& w, const std::string& line) { (void)w.process.send(line); }

  void assign(Worker& w) {
    if (queue_.empty()) {
      stop(w, false);  // nothing left for it: end of input lets it exit
      return;
    }
    if (!model_) return;  // it waits for the model
    const size_t k = queue_.front();
    queue_.pop_front();
    w.job = k;
    w.started = Clock::now();
    w.deadline = after(w.started, s_.timeout);
    send(w, job_line(k, *cases_[k], s_.images(*cases_[k]), model_->model));
  }

  void read_from(Worker& w, size_t slot) {
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

  void handle(Worker& w, const std::string& line) {
    nlohmann::json msg;
    try {
      msg = nlohmann::json::parse(line);
    } catch (const nlohmann::json::parse_error&) {
      throw std::runtime_error("a worker sent something that is not JSON: " + line.substr(0, 200));
    }
    if (msg.contains("error")) {
      // No GL context: the same for every worker, so the run cannot go on.
      throw InputError(msg["error"].get<std::string>());
    }
    if (msg.contains("hello")) {
      w.ready = true;
      if (!started_) {
        const auto& h = msg["hello"];
        gl_ = h.get<gl::GlInfo>();
        started_ = true;
        return begin_model(w, h.value("driver_files", std::vector<std::string>{}));
      }
      return assign(w);
    }
    if (msg.contains("images_done")) {
      const size_t k = msg.at("images_done");
      w.imaging.reset();
      if (msg.contains("images_error"))
        images_lost(k, "heatmaps not written: " + msg["images_error"].get<std::string>());
      return assign(w);
    }
    if (msg.contains("identified") || msg.contains("identify_error")) {
      w.identifying = false;
      if (msg.contains("identify_error"))
        return model_chosen(fallback_model(o_, msg["identify_error"].get<std::string>()));
      const auto m = identify::model_from_json(msg["identified"]);
      if (!m) return model_chosen(fallback_model(o_, "a worker sent " + line.substr(0, 200)));
      cache_.save(*m);
      return model_chosen({*m, "identify"});
    }
    const size_t k = msg.at("index");
    CaseResult r = report::case_result_from_json(msg.at("result").dump(), "worker result");
    w.job.reset();
    // The verdict is in and recorded; the heatmaps follow, under a deadline of their own, and
    // the worker gets no case until they are written.
    const bool images = msg.value("images", false);
    finish(k, std::move(r));
    if (!images) return assign(w);
    w.imaging = k;
    w.started = Clock::now();
    w.deadline = after(w.started, s_.timeout);
  }

  void images_lost(size_t k, const std::string& why) const {
    if (s_.images_lost) s_.images_lost(k, why);
  }

  // The first worker said hello: the model comes from the command line, or the cache, or
  // that worker identifies the implementation while the others wait.
  void begin_model(Worker& w, const std::vector<std::string>& driver_files) {
    if (s_.model) return model_chosen(*s_.model);
    if (auto chosen = model_from_command_line(o_)) return model_chosen(*chosen);
    cache_ = identify::model_cache_slot(gl_.renderer, gl_.version, driver_files);
    if (const auto cached = cache_.load()) return model_chosen({*cached, "identify (cached)"});
    w.identifying = true;
    w.deadline = after(Clock::now(), std::max(s_.timeout, 30.0));
    send(w, "{\"identify\":true}\n");
  }

  // Every case is judged by `chosen`: the run starts, and the workers waiting get cases.
  void model_chosen(const ModelChoice& chosen) {
    model_ = chosen;
    on_start_(gl_, chosen);
    for (Worker& w : workers_)
      if (w.process.running() && w.ready && !w.job && !w.identifying) assign(w);
  }

  void finish(size_t k, CaseResult r) {
    ++done_;
    on_result_(k, std::move(r));
  }

  // A result the worker could not give: Crash or Timeout.
  CaseResult lost(size_t k, Status status, const std::string& message, double seconds) const {
    return unfinished_result(*cases_[k], status, message, seconds);
  }

  void died(Worker& w, size_t slot) {
    const std::string how = w.process.wait();
    const std::string tail = w.process.log_tail();
    const auto job = w.job;
    const auto imaging = w.imaging;
    const bool was_ready = w.ready, was_identifying = w.identifying;
    w.identifying = false;
    w.imaging.reset();
    if (imaging)
      images_lost(*imaging, "heatmaps not written: the worker " + how + " writing them" +
                                (tail.empty() ? "" : "; its log ends: " + tail));
    if (was_identifying) model_chosen(fallback_model(o_, "its worker " + how));
    if (job) {
      finish(*job, lost(*job, Status::crash,
                        "worker " + how + (tail.empty() ? "" : "; its log ends: " + tail),
                        seconds_since(w.started)));
    } else if (!was_ready) {
      // It died making its context. Once is a broken driver or prefix, not a case.
      if (!started_ || ++startup_deaths_ > 3)
        throw InputError("a GL worker " + how + " before it could make a GL context" +
                         (tail.empty() ? "" : "; its log ends: " + tail));
    }
    if (!queue_.empty()) start(w, slot);
  }

  void check_deadlines() {
    const auto now = Clock::now();
    for (size_t k = 0; k < workers_.size(); ++k) {
      Worker& w = workers_[k];
      if (!w.process.running() || now < w.deadline || !busy(w)) continue;
      w.process.kill_now();
      if (w.imaging) {
        images_lost(*w.imaging,
                    fmt::format("heatmaps not written: not done after {} s (--timeout); worker "
                                "killed",
                                s_.timeout));
        w.imaging.reset();
        if (!queue_.empty()) start(w, k);
        continue;
      }
      if (w.identifying) {
        w.identifying = false;
        model_chosen(fallback_model(
            o_, fmt::format("no answer after {} s; worker killed", std::max(s_.timeout, 30.0))));
        if (!queue_.empty()) start(w, k);
        continue;
      }
      if (!w.job)
        throw InputError(fmt::format("a GL worker took over {} s to make a GL context",
                                     std::max(s_.timeout, 30.0)));
      const size_t job = *w.job;
      finish(job, lost(job, Status::timeout,
                       fmt::format("no result after {} s (--timeout); worker killed", s_.timeout),
                       seconds_since(w.started)));
      if (!queue_.empty()) start(w, k);
    }
  }

  // Ends a worker: closing its input makes it exit; `now` kills it instead.
  void stop(Worker& w, bool now) {
    if (!w.process.running()) return;
    if (now)
      w.process.kill_now();
    else
      w.process.finish();
  }

  const std::vector<const Case*>& cases_;
  const Options& o_;
  const WorkerSettings& s_;
  const OnStart& on_start_;
  const std::function<void(size_t, CaseResult)>& on_result_;
  std::deque<size_t> queue_;
  std::vector<Worker> workers_;
  std::vector<std::string> env_;
  std::string exe_, options_line_;
  size_t done_ = 0;
  bool started_ = false;  // the first worker said hello
  gl::GlInfo gl_;         // its GL strings
  identify::ModelCacheSlot cache_;
  std::optional<ModelChoice> model_;  // what judges every case, once known
  int startup_deaths_ = 0;
};

}  // namespace

void run_in_workers(const std::vector<const Case*>& cases, const Options& o,
                    const WorkerSettings& s, const OnStart& on_start,
                    const std::function<void(size_t, CaseResult)>& on_result) {
  if (cases.empty()) return;
  // A worker that dies while we write to it must not take the runner with it.
  signal(SIGPIPE, SIG_IGN);
  std::filesystem::create_directories(s.log_dir);
  Pool pool(cases, o, s, on_start, on_result);
  pool.run();
}

}  // namespace glrc::cli
