#include "cli/run_support.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <fstream>

#include "cli/output_dir.hpp"
#include "cli/workers/process.hpp"
#include "core/text.hpp"
#include "ref/tiles.hpp"
#include "report/html.hpp"
#include "report/merge.hpp"
#include "report/report.hpp"

namespace glrc::cli {

int available_cores() {
  return ref::thread_count(0);
}

Patterns load_patterns(const std::string& file, const char* option) {
  if (file.empty()) return {};
  try {
    return report::read_patterns(file);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string(option) + ": " + e.what());
  }
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

std::string shown_path(const std::string& path) {
  std::error_code ec;
  const auto rel = std::filesystem::relative(path, ec);
  return !ec && !rel.empty() && *rel.begin() != ".." ? rel.string() : path;
}

void check_case_names(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    if (!is_utf8(c.source_path) || !is_utf8(c.name))
      throw InputError("case file \"" + printable(c.source_path) +
                       "\": expected a path in UTF-8 (results.json and the run journal record "
                       "it): rename the file");
    if (const char* what = report::csv_breaking(c.name))
      throw InputError(printable(c.source_path) +
                       ": expected a case name fit for results.csv, got \"" + printable(c.name) +
                       "\", which holds " + what + ": rename the file");
  }
}

void check_paths_utf8(const Options& o) {
  for (const auto& [option, value] : {std::pair{"--baseline", &o.baseline},
                                      {"--flakes", &o.flakes},
                                      {"--skips", &o.skips},
                                      {"--mesa", &o.gl.mesa},
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

bool inside(const std::filesystem::path& inner, const std::filesystem::path& outer) {
  std::error_code ec;
  return inside_resolved(std::filesystem::weakly_canonical(inner, ec),
                         std::filesystem::weakly_canonical(outer, ec));
}

void check_inputs_outside(const std::filesystem::path& out, const std::vector<std::string>& also,
                          const std::vector<std::pair<std::string, std::string>>& inputs,
                          const std::string& option) {
  std::error_code ec;
  std::vector<std::pair<std::string, std::filesystem::path>> outputs;
  for (const std::string& name : run_output_names())
    outputs.emplace_back(name, std::filesystem::weakly_canonical(out / name, ec));
  for (const std::string& name : also)
    outputs.emplace_back(name, std::filesystem::weakly_canonical(out / name, ec));
  for (const auto& [what, path] : inputs) {
    const auto source = std::filesystem::weakly_canonical(path, ec);
    for (const auto& [name, output] : outputs)
      if (inside_resolved(source, output))
        throw InputError(option + ": " + (out / name).string() + " holds " + what + " (" +
                         printable(path, 200) +
                         "), and a run replaces it: copy it out of the folder, or name another "
                         "--out");
  }
}

bool inside_resolved(const std::filesystem::path& inner, const std::filesystem::path& outer) {
  const auto rel = inner.lexically_relative(outer);
  return !rel.empty() && *rel.begin() != "..";
}

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

WorkerSettings worker_settings(Options& o, const std::filesystem::path& out, int interrupt_fd,
                               const std::optional<MesaPrefix>& prefix) {
  WorkerSettings s;
  s.jobs = workers_for(o);
  if (o.threads == 0) o.threads = std::max(1, available_cores() / s.jobs);
  s.timeout = o.timeout;
  s.log_dir = out / "logs";
  s.interrupt_fd = interrupt_fd;
  s.wrapper = o.worker_wrapper;
  if (prefix) s.environment = mesa_environment(*prefix, out);
  s.environment.push_back(huge_page_malloc_tunable());
  s.environment.push_back(huge_page_jemalloc_conf());
  return s;
}

void check_settled(const std::string& path, const std::string& command) {
  std::error_code ec;
  // A folder, or its results.json: another file names no folder of glrefcheck's.
  if (!std::filesystem::is_directory(path, ec) &&
      std::filesystem::path(path).filename() != "results.json")
    return;
  const std::filesystem::path dir = report::run_folder(path);
  const std::string shown = printable(path, 200);
  const bool results =
      std::filesystem::exists(std::filesystem::symlink_status(dir / "results.json", ec));
  if (const auto holder = lock_holder(dir))
    throw InputError(command + ": " + shown + (results ? "" : " holds no results.json yet:") +
                     " another glrefcheck is writing into it (" + *holder +
                     "): wait for it to end");
  // Set aside by a glrefcheck stopped before it finished: beside them, what it wrote of its own
  // (a merge killed halfway) is no run's results.
  if (std::filesystem::exists(dir / kEarlierFolder, ec))
    throw InputError(
        command + ": " + shown +
        (results ? " holds what a glrefcheck stopped before it finished wrote, beside "
                   "the earlier results it set aside ("
                 : " holds no results.json: a glrefcheck stopped before it finished "
                   "(a run or campaign before GL started, or a merge) set them aside (") +
        kEarlierFolder + "/); `glrefcheck report " + shown + "` puts the earlier ones back");
  if (!results && std::filesystem::exists(dir / kJournalFile, ec))
    throw InputError(command + ": " + shown + " holds no results.json but a " + kJournalFile +
                     ": the run was killed; `glrefcheck run --resume " + shown + "` finishes it");
}

report::RunResults read_run_results(const std::string& path, const std::string& command) {
  check_settled(path, command);
  report::RunResults results;
  try {
    results = report::read_results_json(path);
  } catch (const std::runtime_error& e) {
    // One line on stderr, whatever the JSON parser's message holds.
    throw InputError(command + ": " + printable(e.what(), 2000));
  }
  if (results.stamp == report::JsonStamp::none) note_unstamped(path);
  return results;
}

void note_unstamped(const std::string& path) {
  fmt::print(stderr,
             "note: {}: its results.json holds no written_by stamp (an older glrefcheck's, or "
             "made by hand): read as it stands\n",
             printable(path, 200));
}

}  // namespace glrc::cli
