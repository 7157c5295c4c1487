// glrefcheck: run the suite against a GL implementation, diff one case, print reference
// digests, list cases. Exit codes: 0 all as expected, 1 a case failed, 2 usage or input error.
#include <unistd.h>

#include <fmt/core.h>
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <regex>

#include "casefile/casefile.hpp"
#include "cli/expectations.hpp"
#include "cli/identify.hpp"
#include "cli/selftest.hpp"
#include "cli/session.hpp"
#include "compare/compare.hpp"
#include "driver_models/driver_models.hpp"
#include "gl_harness/gl_harness.hpp"
#include "ref/reference.hpp"
#include "report/report.hpp"

namespace glrc::cli {
namespace {
int cmd_run(const Options& o) {
  const auto start = Clock::now();
  const std::vector<Case> cases = load_cases(o);
  const std::filesystem::path out = output_folder(o.out);
  const Baseline baseline = load_baseline(o);
  auto renderer = open_renderer(o);
  RunInfo info = run_info(o, *renderer);
  fmt::print("glrefcheck run: {} cases on {} ({}), GL {} | model {} | tolerance {}\n", cases.size(),
             info.gl_renderer, o.backend, info.gl_version, info.model, info.tolerance);
  std::fflush(stdout);

  const Progress progress;
  std::vector<CaseResult> results;
  for (size_t k = 0; k < cases.size(); ++k) {
    progress.show(k, cases.size(), cases[k].name);
    CaseResult r = check(cases[k], o, *renderer).result;
    apply(baseline, r);
    progress.clear();
    fmt::print("{}\n", report::case_line(r));
    std::fflush(stdout);
    results.push_back(std::move(r));
  }
  info.seconds = seconds_since(start);

  std::map<Status, int> count;
  for (const auto& r : results)
    ++count[r.status];
  fmt::print(
      "\n{} cases: {} pass, {} fail, {} expected fail, {} unexpected pass, {} error, {} skip"
      " in {:.2f} s\n",
      results.size(), count[Status::pass], count[Status::fail], count[Status::expected_fail],
      count[Status::unexpected_pass], count[Status::error], count[Status::skip], info.seconds);
  report::write_results_json(out / "results.json", info, results);
  report::write_junit(out / "junit.xml", info, results);
  fmt::print("wrote {}/results.json and {}/junit.xml\n", o.out, o.out);
  for (const auto& r : results)
    if (fails_run(r.status)) return 1;
  return 0;
}

int cmd_diff(const Options& o) {
  const std::vector<Case> cases = load_cases(o);
  if (cases.size() != 1)
    throw InputError("diff: expected exactly one case, got " + std::to_string(cases.size()) +
                     " (use --filter or name one file)");
  const Case& c = cases[0];
  const std::filesystem::path out = output_folder(o.out);
  auto renderer = open_renderer(o);
  const RunInfo info = run_info(o, *renderer);
  const Checked checked = check(c, o, *renderer);
  const CaseResult& r = checked.result;
  fmt::print("{}: {}\nGL: {} | {} | GL_SUBPIXEL_BITS {} | model {} | tolerance {}\n\n", c.name,
             c.description, info.gl_renderer, info.gl_version, info.subpixel_bits, info.model,
             info.tolerance);
  fmt::print("{}\n", report::case_line(r));
  if (r.status == Status::error) return 1;
  fmt::print("\n{}\n{}\n", report::stats_table(r), report::worst_pixels_table(r, 10));
  const auto files = report::write_diff_images(out, c, checked.reference, checked.gl, r);
  fmt::print("wrote {} images to {}/\n", files.size(), o.out);
  return fails_run(r.status) ? 1 : 0;
}

int cmd_digest(const Options& o) {
  const auto driver = driver_models::driver_from_string(o.model);
  for (const Case& c : load_cases(o))
    fmt::print(
        "{}  {}\n",
        ref::digest(driver ? driver_models::render(c, *driver) : ref::render(c, model_of(o)).frame),
        c.name);
  return 0;
}

int cmd_list(const Options& o) {
  const std::vector<Case> cases = load_cases(o);
  size_t width = 0;
  for (const Case& c : cases)
    width = std::max(width, c.name.size());
  for (const Case& c : cases)
    fmt::print("{:<{}}  {}\n", c.name, width, c.description);
  return 0;
}

void add_case_options(CLI::App& app, Options& o) {
  app.add_option("cases", o.paths, "case files or folders (default: cases/)");
  app.add_option("--filter", o.filter, "only cases whose name matches this regular expression");
}

void add_model_options(CLI::App& app, Options& o) {
  app.add_option("--model", o.model,
                 "ideal: the exact reference (default); llvmpipe, softpipe: bit-exact models of "
                 "those drivers, for --tolerance exact")
      ->check(CLI::IsMember({"ideal", "llvmpipe", "softpipe"}));
  app.add_option("--subpixel-bits", o.subpixel_bits, "reference snapping: 0 (none) to 16")
      ->check(CLI::Range(0, 16));
  app.add_option("--planes", o.planes, "attribute planes from snapped or unsnapped positions")
      ->check(CLI::IsMember({"snapped", "unsnapped"}));
  app.add_option("--tie-break", o.tie_break, "pixel centres on an edge")
      ->check(CLI::IsMember({"bottom-left", "top-left", "bottom-right", "top-right"}));
}

void add_gl_options(CLI::App& app, Options& o) {
  app.add_option("--backend", o.backend, "osmesa, egl (Mesa surfaceless) or egl-device")
      ->check(CLI::IsMember({"osmesa", "egl", "egl-device"}));
  app.add_option("--driver", o.driver, "Mesa gallium driver: llvmpipe, softpipe; \"\" for a GPU");
  app.add_option("--device", o.device, "egl-device: which EGL device");
  // A tolerance is a finite number of ULPs: NaN would compare false everywhere, and an
  // infinite one would say nothing.
  const CLI::Validator finite_ulps(
      [](std::string& s) -> std::string {
        double v = 0;
        try {
          size_t used = 0;
          v = std::stod(s, &used);
          if (used != s.size()) return "expected a number of ULPs, got \"" + s + "\"";
        } catch (const std::exception&) {
          return "expected a number of ULPs, got \"" + s + "\"";
        }
        return std::isfinite(v) && v >= 0 ? "" : "expected a finite number >= 0, got " + s;
      },
      "ULPS");
  app.add_option("--tolerance-ulps", o.varying_ulps,
                 "varying tolerance in ULPs of the attribute's scale (overrides case files)")
      ->check(finite_ulps);
  app.add_option("--depth-tolerance-ulps", o.depth_ulps, "depth tolerance in ULPs of 1.0")
      ->check(finite_ulps);
  app.add_option("--tolerance", o.tolerance,
                 "spec: what the GL specification allows (default); exact: zero differing bits")
      ->check(CLI::IsMember({"spec", "exact"}));
  app.add_option("--spec-subpixel-bits", o.spec_subpixel_bits,
                 "position freedom of the spec tolerance (default: GL_SUBPIXEL_BITS as reported)")
      ->check(CLI::Range(4, 16));
  app.add_flag("--strict-coverage", o.strict_coverage,
               "count coverage mismatches at edges (within a subpixel step) as failures");
  app.add_option("--out", o.out, "output folder");
}

int main_impl(int argc, char** argv) {
  CLI::App app{"glrefcheck: checks GL rasterization and interpolation against an exact reference"};
  app.require_subcommand(1);
  Options o;

  auto* run = app.add_subcommand("run", "run cases against a GL implementation");
  add_case_options(*run, o), add_model_options(*run, o), add_gl_options(*run, o);
  run->add_option("--baseline", o.baseline, "known failures, `case,Status` lines (Mesa CI format)");

  auto* diff = app.add_subcommand("diff", "check one case and write error heatmaps");
  add_case_options(*diff, o), add_model_options(*diff, o), add_gl_options(*diff, o);

  auto* digest = app.add_subcommand("digest", "SHA-256 of each case's reference frame (no GL)");
  add_case_options(*digest, o), add_model_options(*digest, o);

  auto* list = app.add_subcommand("list", "list cases with their descriptions");
  add_case_options(*list, o);

  auto* identify = app.add_subcommand(
      "identify",
      "find which model (subpixel bits, planes, tie rule, default provoking vertex, 24-bit depth "
      "rounding) explains a GL implementation, with the evidence");
  add_gl_options(*identify, o);

  auto* selftest = app.add_subcommand(
      "selftest", "plant faults on the GL side and show that the suite catches each one");
  add_case_options(*selftest, o), add_model_options(*selftest, o), add_gl_options(*selftest, o);
  selftest->add_option("--baseline", o.baseline,
                       "known failures, `case,Status` lines: they cannot catch a fault");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, like every other input error.
    fmt::print(stderr, "glrefcheck: {} (see --help)\n", e.what());
    return 2;
  }
  try {
    if (*run) return cmd_run(o);
    if (*diff) return cmd_diff(o);
    if (*digest) return cmd_digest(o);
    if (*selftest) return cmd_selftest(o);
    if (*identify) return cmd_identify(o);
    return cmd_list(o);
  } catch (const InputError& e) {
    fmt::print(stderr, "glrefcheck: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    // Whatever else went wrong (a report that could not be written, say): one line, not an
    // abort with a core dump.
    fmt::print(stderr, "glrefcheck: {}\n", e.what());
    return 2;
  }
}

}  // namespace
}  // namespace glrc::cli

int main(int argc, char** argv) {
  return glrc::cli::main_impl(argc, argv);
}
