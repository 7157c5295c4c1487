// glrefcheck: run the suite against a GL implementation, diff one case, print reference
// digests, list cases. Exit codes: 0 all as expected, 1 a case failed, 2 usage or input error.
#include <unistd.h>

#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <regex>

#include "casefile/casefile.hpp"
#include "cli/case_commands.hpp"
#include "cli/compare.hpp"
#include "cli/export.hpp"
#include "cli/fuzz.hpp"
#include "cli/identify.hpp"
#include "cli/interrupts.hpp"
#include "cli/mesa_prefix.hpp"
#include "cli/output_dir.hpp"
#include "cli/run.hpp"
#include "cli/selftest.hpp"
#include "cli/session.hpp"
#include "cli/validators.hpp"
#include "cli/workers/workers.hpp"
#include "compare/compare.hpp"
#include "core/large_buffer.hpp"
#include "core/text.hpp"
#include "driver_models/driver_models.hpp"
#include "gl_harness/gl_harness.hpp"
#include "ref/reference.hpp"
#include "report/format.hpp"
#include "report/report.hpp"

namespace glrc::cli {
namespace {
void add_case_options(CLI::App& app, Options& o) {
  app.add_option("cases", o.paths, "case files or folders (default: cases/)");
  app.add_option("--filter", o.filter, "only cases whose name matches this regular expression");
}

// --threads (how the reference is drawn) and the model's options (what judges).
void add_model_options(CLI::App& app, Options& o) {
  app.add_option("--threads", o.threads,
                 "threads drawing the reference, the same bits for any number (default: every "
                 "core; run: the cores shared among its workers)")
      ->check(whole_number(1))
      ->check(CLI::Range(1, 4096));
  o.model.add_to(app);
}

// CLI11's own words where they do not say what was expected: an option given twice.
std::string plain_parse_error(const std::string& what) {
  const std::string twice = ": At Most 1 required but received ";
  if (const size_t at = what.find(twice); at != std::string::npos)
    return what.substr(0, at) + ": expected once, given " + what.substr(at + twice.size()) +
           " times";
  return what;
}

// The GL and verdict groups, and --out.
void add_gl_options(CLI::App& app, Options& o) {
  o.gl.add_to(app);
  o.verdict.add_to(app);
  app.add_option("--out", o.out, "output folder");
}

void add_worker_wrapper_option(CLI::App& command, Options& o) {
  command
      .add_option("--worker-wrapper", o.worker_wrapper,
                  "run each worker under this command, as typed on a shell (\"valgrind -q\", "
                  "\"taskset -c 2\", \"gdb -batch -ex run -ex bt --args\"); its processes are "
                  "killed with the worker")
      ->check(CLI::Validator(
          [](const std::string& s) {
            return s.find_first_not_of(" \t") == std::string::npos ? "expected a command"
                                                                   : std::string();
          },
          "COMMAND"));
}

// An option naming a file or folder given as "" (an unset shell variable: --resume "$DIR") was
// taken for the option not given: `run --resume ''` ran a fresh run into out/, `fuzz --emit ''`
// a campaign. Refused in every subcommand, before anything is done.
void check_no_empty_paths(const CLI::App& app) {
  static const std::vector<std::string> paths = {
      "--resume", "--out",  "--mesa", "--baseline", "--flakes",
      "--skips",  "--emit", "--json", "--markdown", "--worker-wrapper"};
  for (const CLI::App* sub : app.get_subcommands())
    for (const CLI::Option* opt : sub->get_options()) {
      if (opt->count() == 0 || opt->get_expected_min() == 0) continue;  // not given, or a flag
      const std::string name = opt->get_name();
      // Every command's positional arguments are paths too: case files, run folders.
      const bool positional = !opt->nonpositional();
      const bool path = positional || std::find(paths.begin(), paths.end(), name) != paths.end() ||
                        (name == "--html" && sub->get_name() == "compare");
      if (!path) continue;
      for (const std::string& value : opt->results())
        if (value.empty())
          throw InputError((positional ? sub->get_name() + ": " + name : name) +
                           ": expected a path, got \"\" (an empty or unset variable?)");
    }
}

// --device picks among the EGL devices of --backend egl-device; with another backend it would be
// ignored without a word.
void check_device_with_its_backend(const CLI::App& app, const Options& o) {
  for (const CLI::App* sub : app.get_subcommands())
    if (const CLI::Option* device = sub->get_option_no_throw("--device");
        device && device->count() > 0 && o.gl.backend != gl::Backend::egl_device)
      throw InputError(std::string("--device: expected with --backend egl-device, whose EGL "
                                   "devices it picks among, got --backend ") +
                       gl::to_string(o.gl.backend));
}

// `run --resume DIR` runs what DIR's journal recorded: any other option would be silently
// overridden, so it is refused instead. --jobs only changes how fast.
void check_resume_alone(const CLI::App& run) {
  for (const CLI::Option* opt : run.get_options()) {
    const std::string name = opt->get_name();
    if (opt->count() == 0 || name == "--resume" || name == "--jobs" || name == "--jobs-force" ||
        name == "--worker-wrapper" || name == "--threads")
      continue;
    throw InputError(
        "--resume: expected no other option than --jobs, --jobs-force, --threads and "
        "--worker-wrapper (the run goes on with the options and cases it began with), got " +
        (opt->get_positional() ? "case paths" : name));
  }
}

// Starts this program again with the prefix's environment, once (a marker variable says it is
// done), so that the dynamic loader finds the prefix's libraries first.
void reexec_with_mesa(const Options& o, char** argv) {
  const MesaPrefix prefix = find_mesa_prefix(o.gl.mesa, gl::to_string(o.gl.backend));
  const char* done = std::getenv("GLRC_MESA_PREFIX_APPLIED");
  if (done && prefix.root == done) return;
  for (const auto& [name, value] : mesa_environment(prefix, output_folder(o.out).path))
    setenv(name.c_str(), value.c_str(), 1);
  setenv("GLRC_MESA_PREFIX_APPLIED", prefix.root.c_str(), 1);
  execv("/proc/self/exe", argv);
  throw InputError(std::string("--mesa: cannot start glrefcheck again: ") + std::strerror(errno));
}

// Every subcommand, with where its arguments go.
struct Commands {
  Options o;
  FuzzOptions fuzz_options;
  CompareOptions compare_options;
  ExportOptions export_options;
  std::vector<std::string> merge_dirs;
  std::string report_dir, report_file;
  CLI::App *run = nullptr, *fuzz = nullptr, *compare = nullptr, *export_command = nullptr,
           *worker = nullptr, *merge = nullptr, *report = nullptr, *diff = nullptr,
           *digest = nullptr, *list = nullptr, *identify = nullptr, *selftest = nullptr;
};

// --jobs-force, --timeout, --fraction, --fraction-start and --worker-wrapper: how run and fuzz
// spread their cases over worker processes (each says its own --jobs).
void add_worker_options(CLI::App& command, Options& o, const std::string& timeout_status,
                        const std::string& fraction_help) {
  command.add_flag("--jobs-force", o.jobs_force, "allow --jobs beyond the number of cores");
  command
      .add_option("--timeout", o.timeout,
                  "seconds a case may take before its worker is killed (" + timeout_status + ")")
      ->check(finite_range(0.001, 1e6));
  command.add_option("--fraction", o.fraction, fraction_help)->check(whole_number(1));
  command
      .add_option("--fraction-start", o.fraction_start,
                  "the first case of this shard, 1-based (GitLab's CI_NODE_INDEX)")
      ->check(whole_number(1));
  add_worker_wrapper_option(command, o);
}

void add_run_command(CLI::App& app, Commands& c) {
  Options& o = c.o;
  c.run = app.add_subcommand("run", "run cases against a GL implementation");
  CLI::App& run = *c.run;
  add_case_options(run, o), add_model_options(run, o), add_gl_options(run, o);
  run.add_option("--baseline", o.baseline,
                 "expected failures, `case,Status` lines (Mesa CI's *-fails.txt, or a previous "
                 "run's failures.csv)");
  run.add_option("--flakes", o.flakes,
                 "known flaky cases, one regular expression per line: their failures do not "
                 "fail the run (status Flake)");
  run.add_option("--skips", o.skips, "cases not to run, one regular expression per line");
  run.add_option("--jobs,-j", o.jobs,
                 "worker processes in parallel (default and most: one per core; never more "
                 "than cases)")
      ->check(whole_number(1));
  add_worker_options(run, o, "status Timeout", "run every N-th case (a shard, as deqp-runner)");
  run.add_flag("--html", o.html, "also write report.html, a self-contained page");
  run.add_option("--resume", o.resume,
                 "continue the interrupted or killed run in this folder, with the options and "
                 "cases it began with (only --jobs, --jobs-force, --threads and --worker-wrapper "
                 "may be given with it)");
}

void add_fuzz_and_result_commands(CLI::App& app, Commands& c) {
  Options& o = c.o;
  c.fuzz = add_fuzz_command(app, c.fuzz_options);
  add_model_options(*c.fuzz, o), add_gl_options(*c.fuzz, o);
  c.fuzz
      ->add_option("--jobs,-j", o.jobs,
                   "worker processes in parallel (default and most: one per core)")
      ->check(whole_number(1));
  add_worker_options(*c.fuzz, o, "class timeout",
                     "check every N-th case of the campaign (a shard; `merge` joins them)");
  c.compare = add_compare_command(app, c.compare_options);
  c.export_command = add_export_command(app, c.export_options);
  c.merge = app.add_subcommand("merge", "join the results of --fraction shards into one run");
  c.merge->add_option("shards", c.merge_dirs, "the shards' results folders")->required();
  c.merge->add_option("--out", o.out, "output folder")->required();
  c.merge->add_flag("--html", o.html, "also write report.html");
  c.report = app.add_subcommand("report", "write a self-contained HTML page of a run folder");
  c.report->add_option("run", c.report_dir, "a results folder (or its results.json)")->required();
  c.report->add_option("--out", c.report_file, "the HTML file (default: <run>/report.html)");
}

void add_case_commands(CLI::App& app, Commands& c) {
  Options& o = c.o;
  c.worker = app.add_subcommand("worker", "(internal) a GL worker process of `run`");
  c.worker->group("");  // not for people: `run` starts it
  c.diff = app.add_subcommand("diff", "check one case and write error heatmaps");
  add_case_options(*c.diff, o), add_model_options(*c.diff, o), add_gl_options(*c.diff, o);
  c.digest = app.add_subcommand("digest", "SHA-256 of each case's reference frame (no GL)");
  add_case_options(*c.digest, o), add_model_options(*c.digest, o);
  c.list = app.add_subcommand("list", "list cases with their descriptions");
  add_case_options(*c.list, o);
  c.identify = app.add_subcommand(
      "identify",
      "find which model (subpixel bits, planes, tie rule, default provoking vertex, 24-bit depth "
      "rounding) explains a GL implementation, with the evidence");
  add_gl_options(*c.identify, o);
  c.selftest = app.add_subcommand(
      "selftest", "plant faults on the GL side and show that the suite catches each one");
  add_case_options(*c.selftest, o), add_model_options(*c.selftest, o),
      add_gl_options(*c.selftest, o);
  // It prints its verdicts and writes no file: an --out would be silently ignored.
  c.selftest->remove_option(c.selftest->get_option("--out"));
  c.selftest->add_option("--baseline", o.baseline,
                         "known failures, `case,Status` lines: they cannot catch a fault");
}

// CLI11 says "A subcommand is required" for a misspelt one, without naming it: false (after one
// line on stderr) when argv[1] names no command.
bool command_known(CLI::App& app, int argc, char** argv) {
  if (argc <= 1 || argv[1][0] == '-') return true;
  std::string names;
  bool known = false;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    known = known || sub->get_name() == argv[1];
    if (sub->get_name() != "worker") names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  if (!known)
    fmt::print(stderr, "glrefcheck: expected a command ({}), got \"{}\" (see --help)\n", names,
               printable(argv[1], 80));
  return known;
}

// The parsed command run; its exit status (2: bad input, one line on stderr).
int dispatch(CLI::App& app, Commands& c, char** argv) {
  Options& o = c.o;
  try {
    check_no_empty_paths(app);
    check_device_with_its_backend(app, o);
    if (*c.run && !o.resume.empty()) check_resume_alone(*c.run);
    if (*c.worker) return cmd_worker();
    // GL from a Mesa prefix needs the loader's environment at process start: the commands that
    // render in this process start it again with that environment (`run` gives it to its
    // workers only).
    if (!o.gl.mesa.empty() && (*c.diff || *c.identify || *c.selftest)) reexec_with_mesa(o, argv);
    if (*c.run) return cmd_run(o);
    if (*c.fuzz) {
      // Its own default folder: a campaign's results.json is not a run's.
      c.fuzz_options.out_given = c.fuzz->count("--out") > 0;
      if (!c.fuzz_options.out_given) o.out = "fuzz-out";
      return cmd_fuzz(o, c.fuzz_options);
    }
    if (*c.merge) return cmd_merge(c.merge_dirs, o.out, o.html);
    if (*c.report) return cmd_report(c.report_dir, c.report_file);
    if (*c.compare) return cmd_compare(c.compare_options);
    if (*c.export_command) return cmd_export(c.export_options, *c.export_command);
    if (*c.diff) return cmd_diff(o);
    if (*c.digest) return cmd_digest(o);
    if (*c.selftest) return cmd_selftest(o);
    if (*c.identify) return cmd_identify(o);
    return cmd_list(o);
  } catch (const Interrupted& e) {
    fmt::print(stderr,
               "glrefcheck: interrupted by {}: the output folder holds what it held before\n",
               signal_name(e.signal));
    return 128 + e.signal;
  } catch (const std::exception& e) {
    // InputError, and whatever else went wrong (a report that could not be written, say): one
    // line, not an abort with a core dump.
    fmt::print(stderr, "glrefcheck: {}\n", e.what());
    return 2;
  }
}

int main_impl(int argc, char** argv) {
  CLI::App app{"glrefcheck: checks GL rasterization and interpolation against an exact reference"};
  app.require_subcommand(1);
  Commands c;
  add_run_command(app, c);
  add_fuzz_and_result_commands(app, c);
  add_case_commands(app, c);
  if (!command_known(app, argc, argv)) return 2;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, like every other input error; CLI11 quotes what was typed, which may be long
    // or hold control characters.
    fmt::print(stderr, "glrefcheck: {} (see --help)\n",
               printable(plain_parse_error(e.what()), 300));
    return 2;
  }
  c.o.model.given = ModelOptions::given_in(app);
  return dispatch(app, c, argv);
}

}  // namespace
}  // namespace glrc::cli

int main(int argc, char** argv) {
  glrc::keep_freed_buffers();  // core/large_buffer.hpp: band after band, case after case
  return glrc::cli::main_impl(argc, argv);
}
