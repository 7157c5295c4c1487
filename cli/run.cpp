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
#include "cli/process.hpp"
#include "cli/run_support.hpp"
#include "cli/workers.hpp"
#include "core/text.hpp"
#include "report/expectations.hpp"
#include "report/format.hpp"
#include "report/merge.hpp"
#include "report/report.hpp"
#include "report/stamp.hpp"

namespace glrc::cli {

int cmd_run(const Options& given) {
  const auto start = Clock::now();
  Options o = given;
  std::filesystem::path out;
  FolderLock lock;  // the output folder held while the run writes into it
  // The folder's earlier run, given back if this one never gets GL.
  std::optional<EarlierOutputs> earlier_outputs;
  std::optional<JournalContents> earlier;
  std::vector<Case> all;
  std::optional<Journal> journal;
  Options expectations = o;  // where --baseline, --flakes and --skips are read from
  if (!given.resume.empty()) {
    // The run as it began: its options and case files, from the journal; --jobs may differ.
    if (!is_utf8(given.resume))
      throw InputError("--resume: expected a path in UTF-8, got \"" + printable(given.resume) +
                       "\"");
    out = given.resume;
    // Held before the journal is read: two resumes of one folder at once would check the rest
    // twice. A folder glrefcheck did not mark gets no lock file: read_journal refuses it.
    if (is_marked(out)) {
      lock = lock_folder(out, "--resume " + printable(given.resume, 200));
      // A run killed before it had GL left the folder's earlier outputs aside: the run to go on
      // with is that one, whose journal is there (the earlier ones go, as once it had GL); one
      // killed before it wrote a journal started nothing, and the earlier run comes back.
      settle_earlier_outputs(out);
      // The rest of the run writes heatmaps into cases/ and logs into logs/, as a fresh run does.
      check_no_output_folder_inside(out, run_output_names());
    }
    earlier = read_journal(out);
    o = earlier->options;
    o.out = given.resume;
    if (given.jobs > 0) o.jobs = given.jobs, o.jobs_force = given.jobs_force;
    o.worker_wrapper = given.worker_wrapper;
    o.threads = given.threads;
    for (const std::string& file : earlier->files) {
      try {
        all.push_back(casefile::load(file));
      } catch (const std::exception& e) {
        throw InputError("--resume: a case of the run cannot be loaded again: " +
                         std::string(e.what()));
      }
    }
    check_case_names(all);
    // The cases as the run began: a file edited since (a git pull between the interrupt and
    // the resume) would mix two suites in one result.
    std::vector<std::string> changed;
    for (size_t k = 0; k < earlier->file_digests.size(); ++k)
      if (report::content_digest(read_file(earlier->files[k])) != earlier->file_digests[k])
        changed.push_back(earlier->files[k]);
    if (!changed.empty())
      throw InputError(fmt::format(
          "--resume {}: {} changed since the run began ({}{}): start a new run", o.out,
          report::count_text(changed.size(), "case file", "case files"), printable(changed[0], 200),
          changed.size() > 1 ? fmt::format(" and {} more", changed.size() - 1) : ""));
    expectations = o;
    const auto copy = out / kInputsFolder;
    if (!o.baseline.empty()) expectations.baseline = (copy / "baseline").string();
    if (!o.flakes.empty()) expectations.flakes = (copy / "flakes").string();
    if (!o.skips.empty()) expectations.skips = (copy / "skips").string();
  } else {
    check_paths_utf8(o);
    if (o.fraction < 1 || o.fraction_start < 1 || o.fraction_start > o.fraction)
      throw InputError(
          fmt::format("--fraction {} --fraction-start {}: expected 1 <= fraction-start <= fraction",
                      o.fraction, o.fraction_start));
    all = load_cases(o);
    check_case_names(all);
  }
  // Every input is read and checked before the output folder is touched.
  const Baseline baseline = load_baseline(expectations);
  const Patterns flakes = load_patterns(expectations.flakes, "--flakes");
  const Patterns skips = load_patterns(expectations.skips, "--skips");
  std::map<std::string, std::string> judged_by = verdict_inputs(expectations);
  // The suite's case files by name and content, before sharding: shards of one name but two
  // checkouts (a case edited between them) are two suites, which merge refuses.
  std::vector<std::string> case_digests;
  {
    std::string suite;
    for (const Case& c : all) {
      case_digests.push_back(report::content_digest(read_file(c.source_path)));
      suite += c.name + " " + case_digests.back() + "\n";
    }
    judged_by["case_files"] = report::content_digest(suite);
  }
  // A case past --timeout is a Timeout: shards of two timeouts would merge into a run no single
  // --timeout gives.
  judged_by["timeout"] = fmt::format("{}", o.timeout);
  std::optional<MesaPrefix> prefix;
  if (!o.mesa.empty()) prefix = find_mesa_prefix(o.mesa, gl::to_string(o.backend));
  const int interrupt_fd = catch_interrupts();
  if (!earlier) {
    Inputs inputs;
    for (const auto& [name, file] :
         {std::pair{"baseline", &o.baseline}, {"flakes", &o.flakes}, {"skips", &o.skips}})
      if (!file->empty()) inputs.files.emplace_back(name, read_file(*file));
    OutputFolder folder = output_folder(o.out);
    out = folder.path;
    lock = std::move(folder.lock);
    // The run replaces its own outputs; case files among them would go with them. Each path
    // resolved once (a resolution is a system call per folder of the path).
    std::error_code ec;
    std::vector<std::pair<std::string, std::filesystem::path>> outputs;
    for (const std::string& name : run_output_names())
      outputs.emplace_back(name, std::filesystem::weakly_canonical(out / name, ec));
    for (const Case& c : all) {
      const auto source = std::filesystem::weakly_canonical(c.source_path, ec);
      for (const auto& [name, output] : outputs)
        if (inside_resolved(source, output))
          throw InputError("--out " + o.out + ": " + (out / name).string() +
                           " holds this run's case files (" + c.source_path +
                           "), and a run replaces it: name another --out");
    }
    earlier_outputs.emplace(set_aside_outputs(out));
    if (!inputs.files.empty()) std::filesystem::create_directories(out / kInputsFolder);
    for (const auto& [name, text] : inputs.files)
      report::write_file_atomically(out / kInputsFolder / name, text);
    // Absolute, so that --resume finds them from any working folder.
    std::vector<std::string> files;
    for (const Case& c : all)
      files.push_back(std::filesystem::absolute(c.source_path).lexically_normal().string());
    journal.emplace(Journal::start(out, o, files, case_digests));
  } else {
    journal.emplace(Journal::reopen(out));
  }
  // deqp-runner's sharding: every N-th case, starting at K (1-based).
  std::vector<const Case*> cases;
  for (size_t k = size_t(o.fraction_start - 1); k < all.size(); k += size_t(o.fraction))
    cases.push_back(&all[k]);
  const double before = earlier ? earlier->elapsed : 0.0;  // time the run took before --resume
  const auto elapsed = [&] { return before + seconds_since(start); };

  WorkerSettings s = worker_settings(o, out, interrupt_fd, prefix);
  if (earlier && earlier->model) s.model = earlier->model;
  // Known failures get their heatmaps only for the HTML report: triage needs the new ones.
  s.images = [&](const Case& c) { return o.html || !baseline.expected.count(c.name); };

  // What the run knows before GL (enough when every case is skipped), and again once a worker
  // has told the GL strings.
  const auto run_fields = [&](RunInfo& i) {
    i.backend = gl::to_string(o.backend), i.driver = o.driver;
    i.jobs = s.jobs;
    i.fraction = o.fraction, i.fraction_start = o.fraction_start;
    i.total_cases = all.size();
    i.mesa_prefix = o.mesa;  // as typed: results name the tree the way its user does
    i.verdict_inputs = judged_by;
  };
  RunInfo info;
  if (earlier && earlier->run) info = *earlier->run;
  run_fields(info);

  std::vector<std::optional<CaseResult>> results(cases.size());
  if (earlier) {
    for (auto& [index, r] : earlier->results) {
      if (index >= cases.size() || r.name != cases[index]->name)
        throw InputError(fmt::format(
            "--resume {}: {} names case {} as \"{}\", which the run's case files do not: the "
            "journal belongs to another run",
            o.out, kJournalFile, index, printable(r.name)));
      results[index] = std::move(r);
    }
    fmt::print("glrefcheck run --resume {}: {} of {} done before{}\n", o.out,
               earlier->results.size(), report::count_text(cases.size(), "case", "cases"),
               earlier->heatmaps_cut
                   ? fmt::format(" ({} stopped while writing {} heatmaps: checked again)",
                                 report::count_text(earlier->heatmaps_cut, "case", "cases"),
                                 earlier->heatmaps_cut == 1 ? "its" : "their")
                   : "");
  }
  std::vector<const Case*> to_check;
  std::vector<size_t> checked_index;  // to_check[i] is cases[checked_index[i]]
  for (size_t k = 0; k < cases.size(); ++k) {
    if (results[k]) continue;
    if (const std::string* pattern = skips.match(cases[k]->name)) {
      CaseResult r =
          report::skipped_result(cases[k]->name, cases[k]->description, *pattern, o.skips);
      fmt::print("{}\n", report::case_line(r));
      journal->record_result(k, r, elapsed());
      results[k] = std::move(r);
    } else {
      to_check.push_back(cases[k]);
      checked_index.push_back(k);
    }
  }

  const Progress progress;
  size_t done = results.size() - to_check.size();
  bool gl_started = false;
  const auto on_start = [&](const gl::GlInfo& gl, const ModelChoice& model) {
    if (prefix && !from_prefix(*prefix, gl.library))
      throw InputError("--mesa " + o.mesa + ": GL came from " +
                       (gl.library.empty() ? "an unknown library" : gl.library) +
                       ", not from the prefix (GL_VERSION " + gl.version + ")");
    // Half a run on one GL and half on another would be one run on neither.
    if (earlier && earlier->run &&
        (gl.renderer != earlier->run->gl_renderer || gl.version != earlier->run->gl_version ||
         gl.library != earlier->run->gl_library))
      throw InputError("--resume " + o.out + ": the run began on " + earlier->run->gl_renderer +
                       ", GL " + earlier->run->gl_version + " (" + earlier->run->gl_library +
                       "), now GL is " + gl.renderer + ", GL " + gl.version + " (" + gl.library +
                       "): start a new run");
    info = run_info(o, gl, model);
    run_fields(info);
    journal->record_start(info, model);
    gl_started = true;
    if (earlier_outputs) earlier_outputs->keep_new();
    std::string shard;
    if (o.fraction > 1)
      shard = fmt::format(" (shard {} of {}, {} in all)", o.fraction_start, o.fraction,
                          report::count_text(all.size(), "case", "cases"));
    fmt::print(
        "glrefcheck run: {}{} on {} ({}), GL {} | model {} from {} | tolerance {} | {} "
        "worker{}\n",
        report::count_text(cases.size(), "case", "cases"), shard, info.gl_renderer,
        gl::to_string(o.backend), info.gl_version, info.model, info.model_source, info.tolerance,
        std::min(size_t(s.jobs), to_check.size()),
        std::min(size_t(s.jobs), to_check.size()) == 1 ? "" : "s");
    if (prefix) fmt::print("Mesa from {}: {}\n", info.mesa_prefix, shown_path(info.gl_library));
    for (const std::string& w : info.gl_warnings)
      fmt::print("warning: {}\n", w);
    std::fflush(stdout);
  };
  std::set<size_t> heatmaps_follow;  // indices into to_check whose heatmaps are on their way
  s.images_follow = [&](size_t i) { heatmaps_follow.insert(i); };
  s.images_written = [&](size_t i) {
    if (heatmaps_follow.erase(i)) journal->record_heatmaps_written(checked_index[i]);
  };
  const auto on_result = [&](size_t i, CaseResult r) {
    report::apply(baseline, r);
    report::apply_flakes(flakes, o.flakes, r);
    // On disk before anything else: a kill after this line loses nothing of this case.
    journal->record_result(
        checked_index[i], r, elapsed(),
        heatmaps_follow.count(i) ? Journal::Heatmaps::follow : Journal::Heatmaps::none);
    progress.clear();
    fmt::print("{}\n", report::case_line(r));
    std::fflush(stdout);
    progress.show(done++, cases.size(), r.name);
    results[checked_index[i]] = std::move(r);
  };
  // A case whose verdict came but whose heatmaps did not keeps its verdict, and says so.
  s.images_lost = [&](size_t i, const std::string& why) {
    auto& r = results[checked_index[i]];
    if (!r) return;
    r->message += (r->message.empty() ? "" : "; ") + why;
    heatmaps_follow.erase(i);
    journal->record_result(checked_index[i], *r, elapsed());
    progress.clear();
    fmt::print("{}: {}\n", r->name, why);
    std::fflush(stdout);
  };
  run_in_workers(to_check, o, s, on_start, on_result);
  progress.clear();
  // Stopped before GL started: this run checked nothing, and the folder's earlier results come
  // back as they were (earlier_outputs, as it goes) rather than a run of no cases over them.
  if (earlier_outputs && !gl_started && !to_check.empty() && caught_signal()) {
    fmt::print("interrupted by {} before GL started: {} holds its earlier results as they were\n",
               signal_name(caught_signal()), o.out);
    return 128 + caught_signal();
  }

  std::vector<CaseResult> list;
  for (auto& r : results)
    if (r) list.push_back(std::move(*r));
  info.interrupted = list.size() < results.size();
  info.seconds = elapsed();
  fmt::print("\n{}\n", report::run_summary(list, info.seconds));
  if (info.interrupted)
    fmt::print("interrupted by {} after {} of {}: `glrefcheck run --resume {}` checks the rest\n",
               signal_name(caught_signal()), list.size(),
               report::count_text(cases.size(), "case", "cases"), o.out);
  write_outputs(out, info, list, o.html);
  if (earlier_outputs) earlier_outputs->keep_new();
  // 128 + the signal, as a shell reports a process the signal ended.
  if (info.interrupted) return 128 + (caught_signal() ? caught_signal() : SIGINT);
  return report::any_fails_run(list) ? 1 : 0;
}

}  // namespace glrc::cli
