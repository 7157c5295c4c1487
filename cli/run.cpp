#include "cli/run.hpp"

#include <sched.h>

#include <fmt/core.h>
#include <algorithm>
#include <map>
#include <optional>

#include "cli/expectations.hpp"
#include "cli/mesa_prefix.hpp"
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

int cmd_run(const Options& o) {
  const auto start = Clock::now();
  if (o.fraction < 1 || o.fraction_start < 1 || o.fraction_start > o.fraction)
    throw InputError(
        fmt::format("--fraction {} --fraction-start {}: expected 1 <= fraction-start <= fraction",
                    o.fraction, o.fraction_start));
  const std::vector<Case> all = load_cases(o);
  // deqp-runner's sharding: every N-th case, starting at K (1-based).
  std::vector<const Case*> cases;
  for (size_t k = size_t(o.fraction_start - 1); k < all.size(); k += size_t(o.fraction))
    cases.push_back(&all[k]);
  const std::filesystem::path out = output_folder(o.out);
  const Baseline baseline = load_baseline(o);
  const Patterns flakes = load_patterns(o.flakes, "--flakes");
  const Patterns skips = load_patterns(o.skips, "--skips");

  WorkerSettings s;
  s.jobs = o.jobs > 0 ? o.jobs : available_cores();
  s.timeout = o.timeout;
  s.log_dir = out / "logs";
  // Known failures get their heatmaps only for the HTML report: triage needs the new ones.
  s.images = [&](const Case& c) { return o.html || !baseline.expected.count(c.name); };
  std::optional<MesaPrefix> prefix;
  if (!o.mesa.empty()) {
    prefix = find_mesa_prefix(o.mesa, o.backend);
    s.environment = mesa_environment(*prefix, out);
  }
  // Heatmaps of an earlier run in this folder would be taken for this run's.
  std::filesystem::remove_all(out / "cases");

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
  run_fields(info);

  std::vector<std::optional<CaseResult>> results(cases.size());
  std::vector<const Case*> to_check;
  std::vector<size_t> checked_index;  // to_check[i] is cases[checked_index[i]]
  for (size_t k = 0; k < cases.size(); ++k) {
    if (const std::string* pattern = skips.match(cases[k]->name)) {
      CaseResult r;
      r.name = cases[k]->name, r.description = cases[k]->description;
      r.status = r.outcome = Status::skip;
      r.message = "skipped: matches \"" + *pattern + "\" in " + o.skips;
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
    info = run_info(o, gl, model);
    run_fields(info);
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
    progress.clear();
    fmt::print("{}\n", report::case_line(r));
    std::fflush(stdout);
    progress.show(done++, cases.size(), r.name);
    results[checked_index[i]] = std::move(r);
  };
  for (const auto& r : results)
    if (r) fmt::print("{}\n", report::case_line(*r));
  run_in_workers(to_check, o, s, on_start, on_result);
  progress.clear();

  std::vector<CaseResult> list;
  for (auto& r : results)
    list.push_back(std::move(*r));
  info.seconds = seconds_since(start);
  fmt::print("\n{}\n", summary(list, info.seconds));
  write_outputs(out, info, list, o.html);
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
  std::vector<int> seen(size_t(n) + 1, -1);
  for (size_t k = 0; k < shards.size(); ++k) {
    const RunInfo& r = shards[k].run;
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
    if (seen[size_t(r.fraction_start)] >= 0)
      throw InputError(fmt::format("merge: {} and {} are both shard {} of {}",
                                   dirs[size_t(seen[size_t(r.fraction_start)])], dirs[k],
                                   r.fraction_start, n));
    seen[size_t(r.fraction_start)] = int(k);
  }
  for (int start = 1; start <= n; ++start)
    if (seen[size_t(start)] < 0)
      throw InputError(fmt::format("merge: shard {} of {} is missing", start, n));

  // Case j of shard K is case K - 1 + j * N of the whole suite.
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
  const std::filesystem::path out = output_folder(out_dir);
  std::filesystem::remove_all(out / "cases");
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
  try {
    results = report::read_results_json(dir);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string("report: ") + e.what());
  }
  const std::filesystem::path run_dir = report::run_folder(dir);
  const std::filesystem::path html =
      file.empty() ? run_dir / "report.html" : std::filesystem::path(file);
  report::write_run_html(html, results, run_dir);
  fmt::print("wrote {}\n", html.string());
  return 0;
}

}  // namespace glrc::cli
