#include "cli/run.hpp"

#include <signal.h>

#include <fmt/core.h>

#include <optional>
#include <set>

#include "casefile/casefile.hpp"
#include "cli/interrupts.hpp"
#include "cli/journal.hpp"
#include "cli/mesa_prefix.hpp"
#include "cli/output_dir.hpp"
#include "cli/run_support.hpp"
#include "cli/workers/process.hpp"
#include "cli/workers/workers.hpp"
#include "core/text.hpp"
#include "core/verdict_inputs.hpp"
#include "report/expectations.hpp"
#include "report/format.hpp"
#include "report/merge.hpp"
#include "report/report.hpp"
#include "report/stamp.hpp"

namespace glrc::cli {

namespace {

// What a run checks, as asked for: the plan, made before anything is written.
struct RunPlan {
  Clock::time_point start = Clock::now();  // the run's time counts from its planning
  Options o;                  // as the run began (--resume: the journal's, with this --jobs)
  Options expectations;       // where --baseline, --flakes and --skips are read from
  std::vector<Case> all;      // the suite, before sharding
  std::filesystem::path out;  // --resume: the folder (a fresh run claims one when prepared)
  FolderLock lock;            // the output folder, held while the run writes into it
  std::optional<JournalContents> earlier;  // --resume: what the run had done
};

// The run as it began: its options and case files, from the journal; --jobs may differ.
RunPlan plan_resume(const Options& given) {
  if (!is_utf8(given.resume))
    throw InputError("--resume: expected a path in UTF-8, got \"" + printable(given.resume) + "\"");
  RunPlan p;
  p.out = given.resume;
  // Held before the journal is read: two resumes of one folder at once would check the rest
  // twice. A folder glrefcheck did not mark gets no lock file: read_journal refuses it.
  if (is_marked(p.out)) {
    p.lock = lock_folder(p.out, "--resume " + printable(given.resume, 200));
    // A run killed before it had GL left the folder's earlier outputs aside: the run to go on
    // with is that one, whose journal is there (the earlier ones go, as once it had GL); one
    // killed before it wrote a journal started nothing, and the earlier run comes back.
    settle_earlier_outputs(p.out);
    // The rest of the run writes heatmaps into cases/ and logs into logs/, as a fresh run does.
    check_no_output_folder_inside(p.out, run_output_names());
  }
  p.earlier = read_journal(p.out);
  Options& o = p.o;
  o = p.earlier->options;
  o.out = given.resume;
  if (given.jobs > 0) o.jobs = given.jobs, o.jobs_force = given.jobs_force;
  o.worker_wrapper = given.worker_wrapper;
  o.threads = given.threads;
  for (const std::string& file : p.earlier->files) {
    try {
      p.all.push_back(casefile::load(file));
    } catch (const std::exception& e) {
      throw InputError("--resume: a case of the run cannot be loaded again: " +
                       std::string(e.what()));
    }
  }
  check_case_names(p.all);
  // The cases as the run began: a file edited since (a git pull between the interrupt and
  // the resume) would mix two suites in one result.
  std::vector<std::string> changed;
  for (size_t k = 0; k < p.earlier->file_digests.size(); ++k)
    if (report::content_digest(read_file(p.earlier->files[k])) != p.earlier->file_digests[k])
      changed.push_back(p.earlier->files[k]);
  if (!changed.empty())
    throw InputError(fmt::format(
        "--resume {}: {} changed since the run began ({}{}): start a new run", o.out,
        report::count_text(changed.size(), "case file", "case files"), printable(changed[0], 200),
        changed.size() > 1 ? fmt::format(" and {} more", changed.size() - 1) : ""));
  // Judged by the expectation files as the run read them (its copies).
  p.expectations = o;
  const auto copy = p.out / kInputsFolder;
  if (!o.baseline.empty()) p.expectations.baseline = (copy / "baseline").string();
  if (!o.flakes.empty()) p.expectations.flakes = (copy / "flakes").string();
  if (!o.skips.empty()) p.expectations.skips = (copy / "skips").string();
  return p;
}

RunPlan plan_fresh(const Options& given) {
  RunPlan p;
  p.o = p.expectations = given;
  check_paths_utf8(p.o);
  if (p.o.fraction < 1 || p.o.fraction_start < 1 || p.o.fraction_start > p.o.fraction)
    throw InputError(
        fmt::format("--fraction {} --fraction-start {}: expected 1 <= fraction-start <= fraction",
                    p.o.fraction, p.o.fraction_start));
  p.all = load_cases(p.o);
  check_case_names(p.all);
  return p;
}

// What judges the cases besides GL and the model, read and checked before the output folder is
// touched.
struct Judging {
  Baseline baseline;
  Patterns flakes, skips;
  std::map<std::string, std::string> judged_by;  // RunInfo::verdict_inputs
  std::vector<std::string> case_digests;         // each case file's content, for the journal
};

// InputError when what judges a resumed run (its copies of the expectation files above all) is
// not what judged it as it began: one results.json would hold verdicts of two baselines.
void check_judged_alike(const JournalContents& earlier,
                        const std::map<std::string, std::string>& judged_by,
                        const std::filesystem::path& out) {
  // A journal written before they were recorded holds none: nothing to compare.
  if (earlier.verdict_inputs.empty()) return;
  const auto d = verdict_input_difference(earlier.verdict_inputs, judged_by);
  if (!d) return;
  const bool copy = d->name == "baseline" || d->name == "flakes" || d->name == "skips";
  throw InputError(fmt::format(
      "--resume {}: {} is not as the run began{}: start a new run", printable(out.string(), 200),
      copy ? (out / kInputsFolder / d->name).string() : "verdict input " + d->name,
      copy ? " (edited since)" : ""));
}

Judging read_judging(const RunPlan& p) {
  Judging j{load_baseline(p.expectations),
            load_patterns(p.expectations.flakes, "--flakes"),
            load_patterns(p.expectations.skips, "--skips"),
            verdict_inputs(p.expectations),
            {}};
  // The suite's case files by name and content, before sharding: shards of one name but two
  // checkouts (a case edited between them) are two suites, which merge refuses.
  std::string suite;
  for (const Case& c : p.all) {
    j.case_digests.push_back(report::content_digest(read_file(c.source_path)));
    suite += c.name + " " + j.case_digests.back() + "\n";
  }
  j.judged_by["case_files"] = report::content_digest(suite);
  // A case past --timeout is a Timeout: shards of two timeouts would merge into a run no single
  // --timeout gives.
  j.judged_by["timeout"] = fmt::format("{}", p.o.timeout);
  if (p.earlier) check_judged_alike(*p.earlier, j.judged_by, p.out);
  return j;
}

// The output folder claimed, its earlier run set aside (given back if this one never gets GL),
// the expectation files copied in, and the journal begun; --resume reopens the journal.
struct Prepared {
  std::optional<EarlierOutputs> earlier_outputs;
  Journal journal;
};

Prepared prepare_folder(RunPlan& p, const Judging& judging) {
  if (p.earlier) return {std::nullopt, Journal::reopen(p.out)};
  const Options& o = p.o;
  Inputs inputs;
  for (const auto& [name, file] :
       {std::pair{"baseline", &o.baseline}, {"flakes", &o.flakes}, {"skips", &o.skips}})
    if (!file->empty()) inputs.files.emplace_back(name, read_file(*file));
  OutputFolder folder = output_folder(o.out);
  p.out = folder.path;
  p.lock = std::move(folder.lock);
  // The run replaces its own outputs; case files or expectation files among them would go
  // with them (`--baseline O/failures.csv --out O`: the run's failures.csv, which lists no
  // expected failure, replaces the baseline). Each path resolved once (a resolution is a system
  // call per folder of the path).
  std::vector<std::pair<std::string, std::string>> read;
  for (const Case& c : p.all)
    read.emplace_back("this run's case files", c.source_path);
  for (const auto& [option, file] :
       {std::pair{"--baseline", &o.baseline}, {"--flakes", &o.flakes}, {"--skips", &o.skips}})
    if (!file->empty()) read.emplace_back(std::string("this run's ") + option, *file);
  check_inputs_outside(p.out, {"failures"}, read, "--out " + o.out);
  // A campaign's failures/ too, where the folder held one: no minimal case beside a run's
  // results passes for this run's.
  std::optional<EarlierOutputs> earlier_outputs(set_aside_outputs(p.out, {"failures"}));
  if (!inputs.files.empty()) std::filesystem::create_directories(p.out / kInputsFolder);
  for (const auto& [name, text] : inputs.files)
    report::write_file_atomically(p.out / kInputsFolder / name, text);
  // Absolute, so that --resume finds them from any working folder.
  std::vector<std::string> files;
  for (const Case& c : p.all)
    files.push_back(std::filesystem::absolute(c.source_path).lexically_normal().string());
  return {std::move(earlier_outputs),
          Journal::start(p.out, o, files, judging.case_digests, judging.judged_by)};
}

// The run itself: this shard's cases, those the journal holds already, the rest checked in
// workers, each result on the journal before the terminal, and the run files written at the
// end.
class SuiteRun {
 public:
  SuiteRun(RunPlan& plan, const Judging& judging, Prepared& prepared,
           const std::optional<MesaPrefix>& prefix, int interrupt_fd)
      : p_(plan), o_(plan.o), judging_(judging), prepared_(prepared), prefix_(prefix) {
    // deqp-runner's sharding: every N-th case, starting at K (1-based).
    for (size_t k = size_t(o_.fraction_start - 1); k < p_.all.size(); k += size_t(o_.fraction))
      cases_.push_back(&p_.all[k]);
    before_ = p_.earlier ? p_.earlier->elapsed : 0.0;  // time the run took before --resume
    s_ = worker_settings(o_, p_.out, interrupt_fd, prefix_);
    if (p_.earlier && p_.earlier->model) s_.model = p_.earlier->model;
    // Known failures get their heatmaps only for the HTML report: triage needs the new ones.
    s_.images = [this](const Case& c) {
      return o_.html || !judging_.baseline.expected.count(c.name);
    };
    if (p_.earlier && p_.earlier->run) info_ = *p_.earlier->run;
    run_fields(info_);
    results_.resize(cases_.size());
    take_journal_results();
    plan_checks();
  }

  // Checks what is left, and writes the run files; the exit status.
  int execute() {
    s_.images_follow = [this](size_t i) { heatmaps_follow_.insert(i); };
    s_.images_written = [this](size_t i) {
      if (heatmaps_follow_.erase(i)) journal().record_heatmaps_written(checked_index_[i]);
    };
    s_.images_lost = [this](size_t i, const std::string& why) { images_lost(i, why); };
    run_in_workers(
        to_check_, o_, s_, [this](const gl::GlInfo& gl, const ModelChoice& m) { on_start(gl, m); },
        [this](size_t i, CaseResult r) { on_result(i, std::move(r)); });
    progress_.clear();
    return write();
  }

 private:
  Journal& journal() { return prepared_.journal; }
  double elapsed() const { return before_ + seconds_since(p_.start); }

  // What the run knows before GL (enough when every case is skipped), and again once a worker
  // has told the GL strings.
  void run_fields(RunInfo& i) const {
    i.backend = gl::to_string(o_.gl.backend), i.driver = o_.gl.driver;
    i.jobs = s_.jobs;
    i.fraction = o_.fraction, i.fraction_start = o_.fraction_start;
    i.total_cases = p_.all.size();
    i.mesa_prefix = o_.gl.mesa;  // as typed: results name the tree the way its user does
    i.verdict_inputs = judging_.judged_by;
  }

  void take_journal_results() {
    if (!p_.earlier) return;
    for (auto& [index, r] : p_.earlier->results) {
      if (index >= cases_.size() || r.name != cases_[index]->name)
        throw InputError(fmt::format(
            "--resume {}: {} names case {} as \"{}\", which the run's case files do not: the "
            "journal belongs to another run",
            o_.out, kJournalFile, index, printable(r.name)));
      results_[index] = std::move(r);
    }
    fmt::print("glrefcheck run --resume {}: {} of {} done before{}\n", o_.out,
               p_.earlier->results.size(), report::count_text(cases_.size(), "case", "cases"),
               p_.earlier->heatmaps_cut
                   ? fmt::format(" ({} stopped while writing {} heatmaps: checked again)",
                                 report::count_text(p_.earlier->heatmaps_cut, "case", "cases"),
                                 p_.earlier->heatmaps_cut == 1 ? "its" : "their")
                   : "");
  }

  // Skipped cases are recorded at once; the others are left to the workers.
  void plan_checks() {
    for (size_t k = 0; k < cases_.size(); ++k) {
      if (results_[k]) continue;
      if (const std::string* pattern = judging_.skips.match(cases_[k]->name)) {
        CaseResult r =
            report::skipped_result(cases_[k]->name, cases_[k]->description, *pattern, o_.skips);
        fmt::print("{}\n", report::case_line(r));
        journal().record_result(k, r, elapsed());
        results_[k] = std::move(r);
      } else {
        to_check_.push_back(cases_[k]);
        checked_index_.push_back(k);
      }
    }
    done_ = results_.size() - to_check_.size();
  }

  void on_start(const gl::GlInfo& gl, const ModelChoice& model) {
    if (prefix_ && !from_prefix(*prefix_, gl.library))
      throw InputError("--mesa " + o_.gl.mesa + ": GL came from " +
                       (gl.library.empty() ? "an unknown library" : gl.library) +
                       ", not from the prefix (GL_VERSION " + gl.version + ")");
    // Half a run on one GL and half on another would be one run on neither.
    if (const auto& earlier = p_.earlier;
        earlier && earlier->run &&
        (gl.renderer != earlier->run->gl_renderer || gl.version != earlier->run->gl_version ||
         gl.library != earlier->run->gl_library))
      throw InputError("--resume " + o_.out + ": the run began on " + earlier->run->gl_renderer +
                       ", GL " + earlier->run->gl_version + " (" + earlier->run->gl_library +
                       "), now GL is " + gl.renderer + ", GL " + gl.version + " (" + gl.library +
                       "): start a new run");
    info_ = run_info(o_, gl, model);
    run_fields(info_);
    journal().record_start(info_, model);
    gl_started_ = true;
    if (prepared_.earlier_outputs) prepared_.earlier_outputs->keep_new();
    print_start();
  }

  void print_start() const {
    std::string shard;
    if (o_.fraction > 1)
      shard = fmt::format(" (shard {} of {}, {} in all)", o_.fraction_start, o_.fraction,
                          report::count_text(p_.all.size(), "case", "cases"));
    const size_t workers = std::min(size_t(s_.jobs), to_check_.size());
    fmt::print(
        "glrefcheck run: {}{} on {} ({}), GL {} | model {} from {} | tolerance {} | {} "
        "worker{}\n",
        report::count_text(cases_.size(), "case", "cases"), shard, info_.gl_renderer,
        gl::to_string(o_.gl.backend), info_.gl_version, info_.model, info_.model_source,
        info_.tolerance, workers, workers == 1 ? "" : "s");
    if (prefix_) fmt::print("Mesa from {}: {}\n", info_.mesa_prefix, shown_path(info_.gl_library));
    for (const std::string& w : info_.gl_warnings)
      fmt::print("warning: {}\n", w);
    std::fflush(stdout);
  }

  void on_result(size_t i, CaseResult r) {
    report::apply(judging_.baseline, r);
    report::apply_flakes(judging_.flakes, o_.flakes, r);
    // On disk before anything else: a kill after this line loses nothing of this case.
    journal().record_result(
        checked_index_[i], r, elapsed(),
        heatmaps_follow_.count(i) ? Journal::Heatmaps::follow : Journal::Heatmaps::none);
    progress_.clear();
    fmt::print("{}\n", report::case_line(r));
    std::fflush(stdout);
    progress_.show(done_++, cases_.size(), r.name);
    results_[checked_index_[i]] = std::move(r);
  }

  // A case whose verdict came but whose heatmaps did not keeps its verdict, and says so.
  void images_lost(size_t i, const std::string& why) {
    auto& r = results_[checked_index_[i]];
    if (!r) return;
    r->message += (r->message.empty() ? "" : "; ") + why;
    heatmaps_follow_.erase(i);
    journal().record_result(checked_index_[i], *r, elapsed());
    progress_.clear();
    fmt::print("{}: {}\n", r->name, why);
    std::fflush(stdout);
  }

  int write() {
    // Stopped before GL started: this run checked nothing, and the folder's earlier results
    // come back as they were (earlier_outputs, as it goes) rather than a run of no cases over
    // them.
    if (prepared_.earlier_outputs && !gl_started_ && !to_check_.empty() && caught_signal()) {
      fmt::print("interrupted by {} before GL started: {}\n", signal_name(caught_signal()),
                 prepared_.earlier_outputs->left_as_it_was(o_.out));
      return 128 + caught_signal();
    }
    std::vector<CaseResult> list;
    for (auto& r : results_)
      if (r) list.push_back(std::move(*r));
    info_.interrupted = list.size() < results_.size();
    info_.seconds = elapsed();
    fmt::print("\n{}\n", report::run_summary(list, info_.seconds));
    if (info_.interrupted)
      fmt::print("interrupted by {} after {} of {}: `glrefcheck run --resume {}` checks the rest\n",
                 signal_name(caught_signal()), list.size(),
                 report::count_text(cases_.size(), "case", "cases"), o_.out);
    // The folder's page too when it holds one of glrefcheck's (`report` on the interrupted run,
    // before this resume): a page of the run as it stopped beside its whole results would be
    // stale. (A fresh run set the folder's page aside with its other outputs.)
    std::error_code ec;
    const std::filesystem::path page = p_.out / "report.html";
    const bool our_page =
        std::filesystem::is_regular_file(std::filesystem::symlink_status(page, ec)) &&
        report::stamp_intact(read_file(page));
    write_outputs(p_.out, info_, list, o_.html || our_page);
    if (prepared_.earlier_outputs) prepared_.earlier_outputs->keep_new();
    // 128 + the signal, as a shell reports a process the signal ended.
    if (info_.interrupted) return 128 + (caught_signal() ? caught_signal() : SIGINT);
    return report::any_fails_run(list) ? 1 : 0;
  }

  RunPlan& p_;
  Options& o_;
  const Judging& judging_;
  Prepared& prepared_;
  const std::optional<MesaPrefix>& prefix_;
  double before_ = 0;
  WorkerSettings s_;
  RunInfo info_;
  std::vector<const Case*> cases_;  // this shard's
  std::vector<std::optional<CaseResult>> results_;
  std::vector<const Case*> to_check_;
  std::vector<size_t> checked_index_;  // to_check_[i] is cases_[checked_index_[i]]
  std::set<size_t> heatmaps_follow_;   // indices into to_check_ whose heatmaps are on their way
  size_t done_ = 0;
  bool gl_started_ = false;
  const Progress progress_;
};

}  // namespace

// Plan (options, cases), read what judges them, prepare the folder and the journal, then check
// and write.
int cmd_run(const Options& given) {
  RunPlan plan = given.resume.empty() ? plan_fresh(given) : plan_resume(given);
  // Every input is read and checked before the output folder is touched.
  const Judging judging = read_judging(plan);
  std::optional<MesaPrefix> prefix;
  if (!plan.o.gl.mesa.empty())
    prefix = find_mesa_prefix(plan.o.gl.mesa, gl::to_string(plan.o.gl.backend));
  const int interrupt_fd = catch_interrupts();
  Prepared prepared = prepare_folder(plan, judging);
  return SuiteRun(plan, judging, prepared, prefix, interrupt_fd).execute();
}

}  // namespace glrc::cli
