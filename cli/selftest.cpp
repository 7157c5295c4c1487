#include "cli/selftest.hpp"

#include <fmt/core.h>

#include <algorithm>

#include "cli/identify.hpp"
#include "report/format.hpp"
#include "report/report.hpp"
#include "selftest/selftest.hpp"

namespace glrc::cli {

int cmd_selftest(const Options& options) {
  const auto start = Clock::now();
  const std::vector<Case> cases = load_cases(options);
  const Baseline baseline = load_baseline(options);
  auto renderer = open_renderer(options);
  // Every case, clean and with a fault, is judged by one model.
  const ModelChoice model = choose_model(options, *renderer);
  check::CheckOptions judged = check_options(options);
  judged.model = model.model;
  const RunInfo info = run_info(options, renderer->info(), model);
  fmt::print("glrefcheck selftest: {} on {} ({}), GL {} | model {} from {} | tolerance {}\n",
             report::count_text(cases.size(), "case", "cases"), info.gl_renderer,
             gl::to_string(options.gl.backend), info.gl_version, info.model, info.model_source,
             info.tolerance);
  for (const std::string& w : info.gl_warnings)
    fmt::print("warning: {}\n", w);

  const Progress progress;
  selftest::SelftestProgress report_progress;
  report_progress.step = [&](size_t k, size_t n, const std::string& what) {
    progress.show(k, n, what);
  };
  report_progress.clean_failure = [&](const CaseResult& r) {
    progress.clear();
    fmt::print("without a fault: {}\n", report::case_line(r));
  };
  const selftest::SelftestResult result =
      selftest::run_selftest(cases, *renderer, judged, baseline, report_progress);
  progress.clear();

  size_t name_width = 5;
  for (const selftest::FaultRow& row : result.faults)
    name_width = std::max(name_width, row.name.size());
  fmt::print("\n{:<{}}  {:>7}  {:>6}  {}\n", "fault", name_width, "changed", "caught",
             "first case that caught it");
  for (const selftest::FaultRow& row : result.faults) {
    std::string example = row.caught ? row.example : "NOT CAUGHT";
    if (example.size() > 110) example = example.substr(0, 107) + "...";
    fmt::print("{:<{}}  {:>7}  {:>6}  {}\n", row.name, name_width, row.changed, row.caught,
               example);
  }
  const int missed = result.missed();
  fmt::print(
      "\n{}, {} caught, {} missed; without a fault: {} of {} pass, {}, {}{} ({:.2f} s)\n",
      report::count_text(result.faults.size(), "fault", "faults"),
      int(result.faults.size()) - missed, missed, result.passed_clean,
      report::count_text(cases.size(), "case", "cases"),
      report::count_text(uint64_t(result.expected_failures), "expected failure",
                         "expected failures"),
      result.skipped ? std::to_string(result.skipped) + " skipped (a feature GL lacks), " : "",
      report::count_text(result.clean_failures.size(), "unexpected failure", "unexpected failures"),
      seconds_since(start));
  return result.ok() ? 0 : 1;
}

}  // namespace glrc::cli
