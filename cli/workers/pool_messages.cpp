// The worker pool's side of the protocol (cli/workers/workers.hpp): what each line a worker sends
// means, what it gets next, and how the run's one model is chosen.
#include <nlohmann/json.hpp>

#include "cli/workers/pool.hpp"
#include "cli/workers/protocol.hpp"
#include "report/report.hpp"

namespace glrc::cli {

namespace {

// Line by line what a worker may send; anything else is a broken worker (or not a worker at
// all: the wrong --worker-wrapper), which stops the run with the line it sent.
[[noreturn]] void unexpected(const std::string& line, const std::string& why) {
  throw std::runtime_error("a worker sent " + why + ": " + line.substr(0, 200));
}

// Whether worker w is checking case k.
bool checking(const Worker& w, size_t k) {
  const auto* checking = std::get_if<worker_state::Checking>(&w.state);
  return checking && checking->job == k;
}

}  // namespace

void Pool::handle(Worker& w, const std::string& line) {
  // The common line, a result, is read once: not parsed whole, its result dumped and parsed
  // again (that was half of the runner's time in a suite of small cases, which it takes from
  // the workers on a machine of as many cores as workers).
  if (const auto raw = read_result_line(line)) {
    if (!checking(w, raw->index)) unexpected(line, "a result for a case it was not given");
    CaseResult r = report::case_result_from_json(std::string(raw->result), "worker result");
    return result_in(w, raw->index, std::move(r), raw->images);
  }
  nlohmann::json msg;
  try {
    msg = nlohmann::json::parse(line);
  } catch (const nlohmann::json::parse_error&) {
    unexpected(line, "something that is not JSON");
  }
  if (!msg.is_object()) unexpected(line, "something that is not a JSON object");
  try {
    if (msg.contains("error")) {
      // No GL context: the same for every worker, so the run cannot go on.
      throw InputError(msg["error"].get<std::string>());
    }
    if (msg.contains("hello")) {
      if (!w.in<worker_state::Starting>()) unexpected(line, "a second hello");
      return hello(w, msg["hello"]);
    }
    if (msg.contains("images_done")) {
      const size_t k = msg.at("images_done");
      const auto* imaging = std::get_if<worker_state::Imaging>(&w.state);
      if (!imaging || imaging->job != k) unexpected(line, "heatmaps it was not writing");
      w.state = worker_state::Idle{};
      if (msg.contains("images_error"))
        images_lost(k, "heatmaps not written: " + msg["images_error"].get<std::string>());
      else if (s_.images_written)
        s_.images_written(k);
      return assign(w);
    }
    if (msg.contains("identified") || msg.contains("identify_error")) {
      if (!w.in<worker_state::Identifying>())
        unexpected(line, "an identification nobody asked for");
      w.state = worker_state::Idle{};
      if (msg.contains("identify_error"))
        return model_chosen(fallback_model(o_, msg["identify_error"].get<std::string>()));
      const auto m = identify::model_from_json(msg["identified"]);
      if (!m) return model_chosen(fallback_model(o_, "a worker sent " + line.substr(0, 200)));
      cache_.save(*m);
      return model_chosen({*m, "identify"});
    }
    const size_t k = msg.at("index");
    if (!checking(w, k)) unexpected(line, "a result for a case it was not given");
    CaseResult r = report::case_result_from_json(msg.at("result").dump(), "worker result");
    result_in(w, k, std::move(r), msg.value("images", false));
  } catch (const nlohmann::json::exception&) {
    unexpected(line, "a message without the fields of the protocol");
  }
}

void Pool::result_in(Worker& w, size_t k, CaseResult r, bool images) {
  w.state = worker_state::Idle{};
  // The verdict is in and recorded; the heatmaps follow, under a deadline of their own, and
  // the worker gets no case until they are written.
  if (images && s_.images_follow) s_.images_follow(k);
  finish(k, std::move(r));
  if (!images) return assign(w);
  w.enter(worker_state::Imaging{k}, s_.timeout);
}

void Pool::hello(Worker& w, const nlohmann::json& hello) {
  w.state = worker_state::Idle{};
  if (started_) return assign(w);
  gl_ = hello.get<gl::GlInfo>();
  started_ = true;
  begin_model(w, hello.value("driver_files", std::vector<std::string>{}));
}

void Pool::assign(Worker& w) {
  if (queue_.empty()) {
    // Nothing left for it: end of input lets it exit, unless it waits for the next cases.
    if (lifetime_ == PoolLifetime::queue) stop(w, false);
    return;
  }
  if (!model_) return;  // it waits for the model
  const size_t k = queue_.front();
  queue_.pop_front();
  w.enter(worker_state::Checking{k}, s_.timeout);
  (void)w.process.send(job_line(k, *cases_[k], s_.images(*cases_[k]), model_->model));
}

// The first worker said hello: the model comes from the command line, or the cache, or that
// worker identifies the implementation while the others wait.
void Pool::begin_model(Worker& w, const std::vector<std::string>& driver_files) {
  if (s_.model) return model_chosen(*s_.model);
  if (auto chosen = model_from_command_line(o_)) return model_chosen(*chosen);
  cache_ = identify::model_cache_slot(gl_.renderer, gl_.version, driver_files);
  if (const auto cached = cache_.load()) return model_chosen({*cached, "identify (cached)"});
  w.enter(worker_state::Identifying{}, startup_seconds());
  (void)w.process.send("{\"identify\":true}\n");
}

// Every case is judged by `chosen`: the run starts, and the workers waiting get cases.
void Pool::model_chosen(const ModelChoice& chosen) {
  model_ = chosen;
  on_start_(gl_, chosen);
  for (Worker& w : workers_)
    if (w.in<worker_state::Idle>()) assign(w);
}

}  // namespace glrc::cli
