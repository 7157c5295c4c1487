#include "cli/run.hpp"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <fmt/core.h>
#include <algorithm>
#include <cerrno>
#include <fstream>
#include <map>
#include <optional>

#include "casefile/casefile.hpp"
#include "cli/expectations.hpp"
#include "cli/journal.hpp"
#include "cli/mesa_prefix.hpp"
#include "cli/output_dir.hpp"
#include "cli/text.hpp"
#include "cli/workers.hpp"
#include "report/format.hpp"
#include "report/html.hpp"
#include "report/report.hpp"

namespace glrc::cli {

namespace {

int available_cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return 1;
}

Patterns load_patterns(const std::string& file, const char* option) {
  if (file.empty()) return {};
  try {
    return read_patterns(file);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string(option) + ": " + e.what());
  }
}

// The summary line: every status that occurred, in a fixed order.
std::string summary(const std::vector<CaseResult>& results, double seconds) {
  std::map<Status, int> count;
  for (const auto& r : results)
    ++count[r.status];
  std::string text = fmt::format("{}: {} pass, {} fail, {} expected fail, {} unexpected pass",
                                 report::count_text(results.size(), "case", "cases"),
                                 count[Status::pass], count[Status::fail],
                                 count[Status::expected_fail], count[Status::unexpected_pass]);
  for (Status s : {Status::crash, Status::timeout, Status::flake})
    if (count[s]) text += fmt::format(", {} {}", count[s], to_string(s));
  return text + fmt::format(", {} error, {} skip in {:.2f} s", count[Status::error],
                            count[Status::skip], seconds);
}

void write_outputs(const std::filesystem::path& out, const RunInfo& info,
                   const std::vector<CaseResult>& results, bool html) {
  report::write_run_files(out, info, results);
  std::string files = "results.json, results.csv, failures.csv, junit.xml";
  if (html) {
    report::write_run_html(out / "report.html", {info, results}, out);
    files += ", report.html";
  }
  fmt::print("wrote {} to {}/\n", files, out.string());
}

// A path under the working folder as a relative one, so logs and READMEs stay short.
std::string shown_path(const std::string& path) {
  std::error_code ec;
  const auto rel = std::filesystem::relative(path, ec);
  return !ec && !rel.empty() && *rel.begin() != ".." ? rel.string() : path;
}

bool any_fails_run(const std::vector<CaseResult>& results) {
  return std::any_of(results.begin(), results.end(),
                     [](const CaseResult& r) { return fails_run(r.status); });
}

}  // namespace

namespace {

// SIGINT and SIGTERM: the handler only records the signal and writes a byte to a pipe the worker
// pool polls, so the run stops between two results and writes what finished.
int g_interrupt_pipe[2] = {-1, -1};
volatile sig_atomic_t g_signal = 0;

extern "C" void on_interrupt(int sig) {
  const int saved = errno;
  if (!g_signal) g_signal = sig;
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = write(g_interrupt_pipe[1], &byte, 1);
  errno = saved;
}

int catch_interrupts() {
  if (g_interrupt_pipe[0] < 0 && pipe2(g_interrupt_pipe, O_CLOEXEC | O_NONBLOCK) != 0)
    throw std::runtime_error("cannot make a pipe for SIGINT and SIGTERM");
  struct sigaction sa = {};
  sa.sa_handler = on_interrupt;
  // Restarted: a write to stdout or the journal must not fail because a signal came; the pool's
  // poll() returns at once all the same (poll is never restarted, and it watches the pipe).
  sa.sa_flags = SA_RESTART;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  return g_interrupt_pipe[0];
}

// What in a case name would break a line of results.csv or failures.csv (`case,Status,seconds`,
// no quoting: Mesa CI's tools split on commas), or nullptr. Such names are refused, not quoted:
// a quoted name would not match the same case in a --baseline read by those tools.
const char* csv_breaking(const std::string& name) {
  for (const char ch : name) {
    if (ch == ',') return "a comma";
    if (ch == '"') return "a double quote";
    if (ch == '\n' || ch == '\r') return "a line break";
    if ((unsigned char)ch < 0x20 || ch == 0x7f) return "a control character";
  }
  if (!name.empty() && (name.front() == ' ' || name.back() == ' '))
    return "a space at an end (baselines trim it)";
  return nullptr;
}

// Every case of the run can be written into results.json, the journal and the CSVs as it is:
// refused up front otherwise, never a half-written run.
void check_case_names(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    if (!is_utf8(c.source_path) || !is_utf8(c.name))
      throw InputError("case file \"" + printable(c.source_path) +
                       "\": expected a path in UTF-8 (results.json and the run journal record "
                       "it): rename the file");
    if (const char* what = csv_breaking(c.name))
      throw InputError(printable(c.source_path) +
                       ": expected a case name fit for results.csv, got \"" + printable(c.name) +
                       "\", which holds " + what + ": rename the file");
  }
}

// The options that name files: recorded in JSON (the journal), so UTF-8 only.
void check_paths_utf8(const Options& o) {
  for (const auto& [option, value] : {std::pair{"--baseline", &o.baseline},
                                      {"--flakes", &o.flakes},
                                      {"--skips", &o.skips},
                                      {"--mesa", &o.mesa},
                                      {"--filter", &o.filter},
                                      {"--out", &o.out}})
    if (!is_utf8(*value))
      throw InputError(std::string(option) + ": expected UTF-8 text, got \"" + printable(*value) +
                       "\"");
  for (const std::string& p : o.paths)
    if (!is_utf8(p))
      throw InputError("\"" + printable(p) +
                       "\": expected a case path in UTF-8 (results.json "
                       "and the run journal record it)");
}

std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Whether `inner` is `outer` or lies inside it (both as they resolve now).
bool inside(const std::filesystem::path& inner, const std::filesystem::path& outer) {
  std::error_code ec;
  const auto a = std::filesystem::weakly_canonical(inner, ec);
  const auto b = std::filesystem::weakly_canonical(outer, ec);
  const auto rel = a.lexically_relative(b);
  return !rel.empty() && *rel.begin() != "..";
}

// The expectation files as this run read them: copied into the run folder, since --resume must
// judge by the same ones (a --baseline may be this folder's failures.csv, which the run
// replaces).
struct Inputs {
  std::vector<std::pair<std::string, std::string>> files;  // name in kInputsFolder, text
};

int workers_for(const Options& o) {
  const int cores = available_cores();
  if (o.jobs <= 0) return cores;
  if (o.jobs > cores && !o.jobs_force) {
    fmt::print("note: --jobs {}: {} worker{}, one per core (--jobs-force starts {})\n", o.jobs,
               cores, cores == 1 ? "" : "s", o.jobs);
    return cores;
  }
  return o.jobs;
}

}  // namespace

int cmd_run(const Options& given) {
  const auto start = Clock::now();
  Options o = given;
  std::filesystem::path out;
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
    earlier = read_journal(out);
    o = earlier->options;
    o.out = given.resume;
    if (given.jobs > 0) o.jobs = given.jobs, o.jobs_force = given.jobs_force;
    for (const std::string& file : earlier->files) {
      try {
        all.push_back(casefile::load(file));
      } catch (const std::exception& e) {
        throw InputError("--resume: a case of the run cannot be loaded again: " +
                         std::string(e.what()));
      }
    }
    check_case_names(all);
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
  std::optional<MesaPrefix> prefix;
  if (!o.mesa.empty()) prefix = find_mesa_prefix(o.mesa, o.backend);
  const int interrupt_fd = catch_interrupts();
  if (!earlier) {
    Inputs inputs;
    for (const auto& [name, file] :
         {std::pair{"baseline", &o.baseline}, {"flakes", &o.flakes}, {"skips", &o.skips}})
      if (!file->empty()) inputs.files.emplace_back(name, read_file(*file));
    out = output_folder(o.out);
    // The run replaces its own outputs; case files among them would go with them.
    for (const Case& c : all)
      for (const std::string& name : run_output_names())
        if (inside(c.source_path, out / name))
          throw InputError("--out " + o.out + ": " + (out / name).string() +
                           " holds this run's case files (" + c.source_path +
                           "), and a run replaces it: name another --out");
    clear_run_outputs(out);
    if (!inputs.files.empty()) std::filesystem::create_directories(out / kInputsFolder);
    for (const auto& [name, text] : inputs.files)
      report::write_file_atomically(out / kInputsFolder / name, text);
    // Absolute, so that --resume finds them from any working folder.
    std::vector<std::string> files;
    for (const Case& c : all)
      files.push_back(std::filesystem::absolute(c.source_path).lexically_normal().string());
    journal.emplace(Journal::start(out, o, files));
  } else {
    journal.emplace(Journal::reopen(out));
  }
  // deqp-runner's sharding: every N-th case, starting at K (1-based).
  std::vector<const Case*> cases;
  for (size_t k = size_t(o.fraction_start - 1); k < all.size(); k += size_t(o.fraction))
    cases.push_back(&all[k]);
  const double before = earlier ? earlier->elapsed : 0.0;  // time the run took before --resume
  const auto elapsed = [&] { return before + seconds_since(start); };

  WorkerSettings s;
  s.jobs = workers_for(o);
  s.timeout = o.timeout;
  s.log_dir = out / "logs";
  s.interrupt_fd = interrupt_fd;
  if (earlier && earlier->model) s.model = earlier->model;
  // Known failures get their heatmaps only for the HTML report: triage needs the new ones.
  s.images = [&](const Case& c) { return o.html || !baseline.expected.count(c.name); };
  if (prefix) s.environment = mesa_environment(*prefix, out);

  // What the run knows before GL (enough when every case is skipped), and again once a worker
  // has told the GL strings.
  const auto run_fields = [&](RunInfo& i) {
    i.backend = o.backend, i.driver = o.driver;
    i.jobs = s.jobs;
    i.fraction = o.fraction, i.fraction_start = o.fraction_start;
    i.total_cases = all.size();
    i.mesa_prefix = o.mesa;  // as typed: results name the tree the way its user does
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
    fmt::print("glrefcheck run --resume {}: {} of {} done before\n", o.out, earlier->results.size(),
               report::count_text(cases.size(), "case", "cases"));
  }
  std::vector<const Case*> to_check;
  std::vector<size_t> checked_index;  // to_check[i] is cases[checked_index[i]]
  for (size_t k = 0; k < cases.size(); ++k) {
    if (results[k]) continue;
    if (const std::string* pattern = skips.match(cases[k]->name)) {
      CaseResult r;
      r.name = cases[k]->name, r.description = cases[k]->description;
      r.status = r.outcome = Status::skip;
      r.message = "skipped: matches \"" + *pattern + "\" in " + o.skips;
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
    std::string shard;
    if (o.fraction > 1)
      shard = fmt::format(" (shard {} of {}, {} in all)", o.fraction_start, o.fraction,
                          report::count_text(all.size(), "case", "cases"));
    fmt::print(
        "glrefcheck run: {}{} on {} ({}), GL {} | model {} from {} | tolerance {} | {} "
        "worker{}\n",
        report::count_text(cases.size(), "case", "cases"), shard, info.gl_renderer, o.backend,
        info.gl_version, info.model, info.model_source, info.tolerance,
        std::min(size_t(s.jobs), to_check.size()),
        std::min(size_t(s.jobs), to_check.size()) == 1 ? "" : "s");
    if (prefix) fmt::print("Mesa from {}: {}\n", info.mesa_prefix, shown_path(info.gl_library));
    for (const std::string& w : info.gl_warnings)
      fmt::print("warning: {}\n", w);
    std::fflush(stdout);
  };
  const auto on_result = [&](size_t i, CaseResult r) {
    apply(baseline, r);
    if (fails_run(r.status))
      if (const std::string* pattern = flakes.match(r.name)) {
        r.message = "known flake (\"" + *pattern + "\" in " + o.flakes + "), was " +
                    to_string(r.status) + ": " + r.message;
        r.status = Status::flake;
      }
    // On disk before anything else: a kill after this line loses nothing of this case.
    journal->record_result(checked_index[i], r, elapsed());
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
    journal->record_result(checked_index[i], *r, elapsed());
    progress.clear();
    fmt::print("{}: {}\n", r->name, why);
    std::fflush(stdout);
  };
  run_in_workers(to_check, o, s, on_start, on_result);
  progress.clear();

  std::vector<CaseResult> list;
  for (auto& r : results)
    if (r) list.push_back(std::move(*r));
  info.interrupted = list.size() < results.size();
  info.seconds = elapsed();
  fmt::print("\n{}\n", summary(list, info.seconds));
  if (info.interrupted)
    fmt::print("interrupted by {} after {} of {}: `glrefcheck run --resume {}` checks the rest\n",
               g_signal == SIGTERM ? "SIGTERM" : "SIGINT", list.size(),
               report::count_text(cases.size(), "case", "cases"), o.out);
  write_outputs(out, info, list, o.html);
  // 128 + the signal, as a shell reports a process the signal ended.
  if (info.interrupted) return 128 + (g_signal ? int(g_signal) : SIGINT);
  return any_fails_run(list) ? 1 : 0;
}

int cmd_merge(const std::vector<std::string>& dirs, const std::string& out_dir, bool html) {
  std::vector<report::RunResults> shards;
  for (const auto& d : dirs) {
    try {
      shards.push_back(report::read_results_json(d));
    } catch (const std::runtime_error& e) {
      throw InputError(std::string("merge: ") + e.what());
    }
  }
  // Every shard of one fraction, each once, from the same GL and options.
  const RunInfo& first = shards.front().run;
  const int n = first.fraction;
  // Read back, 1 <= fraction_start <= fraction holds (report::read_results_json checks it). The
  // shards seen are a map, not a table of `fraction` entries: that number comes from a file.
  std::map<int, size_t> seen;
  for (size_t k = 0; k < shards.size(); ++k) {
    const RunInfo& r = shards[k].run;
    if (r.interrupted)
      throw InputError("merge: " + dirs[k] + ": an interrupted run: `glrefcheck run --resume " +
                       dirs[k] + "` completes it");
    if (r.fraction != n)
      throw InputError(
          fmt::format("merge: {}: expected a shard of --fraction {}, got --fraction {}", dirs[k], n,
                      r.fraction));
    if (r.total_cases != first.total_cases)
      throw InputError(fmt::format("merge: {}: expected a shard of a {}-case suite, got {} cases",
                                   dirs[k], first.total_cases, r.total_cases));
    if (r.gl_version != first.gl_version || r.gl_renderer != first.gl_renderer ||
        r.backend != first.backend || r.model != first.model || r.tolerance != first.tolerance)
      throw InputError(fmt::format(
          "merge: {}: expected the same GL and options as {} ({}, {}), got {}, {}", dirs[k],
          dirs[0], first.gl_renderer, first.gl_version, r.gl_renderer, r.gl_version));
    if (const auto [it, added] = seen.emplace(r.fraction_start, k); !added)
      throw InputError(fmt::format("merge: {} and {} are both shard {} of {}", dirs[it->second],
                                   dirs[k], r.fraction_start, n));
  }
  // N distinct shards among the folders are all of them; the first gap is at most one past the
  // number of folders.
  for (int start = 1; start <= n; ++start)
    if (!seen.contains(start))
      throw InputError(fmt::format("merge: shard {} of {} is missing", start, n));

  // Case j of shard K is case K - 1 + j * N of the whole suite: shard K holds
  // ceil((total - K + 1) / N) cases. Checked before the table is made, so that a forged
  // total_cases is a line, not 2^62 elements.
  for (size_t k = 0; k < shards.size(); ++k) {
    const RunInfo& r = shards[k].run;
    const uint64_t start = uint64_t(r.fraction_start);
    const uint64_t holds =
        first.total_cases >= start ? (first.total_cases - start) / uint64_t(n) + 1 : 0;
    if (shards[k].cases.size() != holds)
      throw InputError(fmt::format(
          "merge: {}: shard {} of {} of a {}-case suite: expected {} "
          "cases, got {}",
          dirs[k], r.fraction_start, n, first.total_cases, holds, shards[k].cases.size()));
  }
  std::vector<std::optional<CaseResult>> merged(first.total_cases);
  RunInfo info = first;
  info.fraction = info.fraction_start = 1;
  info.seconds = 0;
  info.jobs = 0;
  for (const auto& shard : shards) {
    info.seconds = std::max(info.seconds, shard.run.seconds);  // shards run side by side
    info.jobs += shard.run.jobs;
    for (size_t j = 0; j < shard.cases.size(); ++j) {
      const size_t at = size_t(shard.run.fraction_start - 1) + j * size_t(n);
      if (at >= merged.size())
        throw InputError(fmt::format("merge: shard {} holds more cases than a {}-case suite has",
                                     shard.run.fraction_start, merged.size()));
      merged[at] = shard.cases[j];
    }
  }
  std::vector<CaseResult> list;
  for (size_t k = 0; k < merged.size(); ++k) {
    if (!merged[k])
      throw InputError(fmt::format("merge: case {} of {} is in no shard", k + 1, merged.size()));
    list.push_back(std::move(*merged[k]));
  }
  for (const auto& r : list)
    if (const char* what = csv_breaking(r.name))
      throw InputError("merge: expected case names fit for results.csv, got \"" +
                       printable(r.name) + "\", which holds " + what);
  // The merge replaces its folder's run files: never a shard's own.
  for (const auto& d : dirs) {
    bool clash = inside(out_dir, report::run_folder(d)) && inside(report::run_folder(d), out_dir);
    for (const std::string& name : run_output_names())
      clash = clash || inside(report::run_folder(d), std::filesystem::path(out_dir) / name);
    if (clash)
      throw InputError("merge --out " + out_dir + ": expected a folder apart from the shards, " +
                       "got the shard " + d + " or a folder whose run files hold it");
  }
  const std::filesystem::path out = output_folder(out_dir);
  // Heatmaps and files of an earlier run or merge here would be taken for this merge's.
  clear_run_outputs(out);
  for (size_t k = 0; k < shards.size(); ++k) {
    const auto images = report::run_folder(dirs[k]) / "cases";
    std::error_code ec;
    if (std::filesystem::is_directory(images, ec))
      std::filesystem::copy(images, out / "cases",
                            std::filesystem::copy_options::recursive |
                                std::filesystem::copy_options::overwrite_existing);
  }
  fmt::print("merged {} shards: {}\n", shards.size(), summary(list, info.seconds));
  write_outputs(out, info, list, html);
  return any_fails_run(list) ? 1 : 0;
}

int cmd_report(const std::string& dir, const std::string& file) {
  report::RunResults results;
  std::error_code ec;
  if (std::filesystem::is_directory(dir, ec) &&
      !std::filesystem::exists(std::filesystem::path(dir) / "results.json", ec) &&
      std::filesystem::exists(std::filesystem::path(dir) / kJournalFile, ec))
    throw InputError("report: " + dir + " holds no results.json but a " + kJournalFile +
                     ": the run was killed; `glrefcheck run --resume " + dir + "` finishes it");
  try {
    results = report::read_results_json(dir);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string("report: ") + e.what());
  }
  const std::filesystem::path run_dir = report::run_folder(dir);
  const std::filesystem::path html =
      file.empty() ? run_dir / "report.html" : std::filesystem::path(file);
  check_replaceable(html, file.empty() ? "report" : "--out", "<title>glrefcheck");
  report::write_run_html(html, results, run_dir);
  fmt::print("wrote {}\n", html.string());
  return 0;
}

}  // namespace glrc::cli
