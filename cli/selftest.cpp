#include "cli/selftest.hpp"

#include <fmt/core.h>

#include <bit>
#include <cstring>

#include "cli/identify.hpp"
#include "compare/compare.hpp"
#include "report/format.hpp"
#include "report/report.hpp"
#include "selftest/faults.hpp"

namespace glrc::cli {

namespace {

// Whether two frames hold the same bits: a fault that changes nothing cannot be caught, and is
// reported as not applicable to that case rather than as missed.
bool same_bits(const Frame& a, const Frame& b) {
  auto same = [](const std::vector<float>& x, const std::vector<float>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(float)) == 0;
  };
  if (a.primitive != b.primitive || a.fragments != b.fragments || !same(a.depth, b.depth) ||
      a.components.size() != b.components.size())
    return false;
  for (size_t k = 0; k < a.components.size(); ++k)
    if (!same(a.components[k], b.components[k])) return false;
  return true;
}

struct CaseRun {
  const Case* c = nullptr;
  Expectation expected;
  Frame clean;  // GL without a fault
  Tolerance tolerance;
};

struct FaultRow {
  std::string name, description;
  int changed = 0, caught = 0, errors = 0;
  std::string example;  // the first catching case and why
};

}  // namespace

int cmd_selftest(const Options& options) {
  const auto start = Clock::now();
  const std::vector<Case> cases = load_cases(options);
  const Baseline baseline = load_baseline(options);
  auto renderer = open_renderer(options);
  // Every case, clean and with a fault, is judged by one model.
  const ModelChoice model = choose_model(options, *renderer);
  Options o = options;
  set_model(o, model.model);
  const RunInfo info = run_info(options, renderer->info(), model);
  const int reported = renderer->info().subpixel_bits;
  fmt::print("glrefcheck selftest: {} on {} ({}), GL {} | model {} from {} | tolerance {}\n",
             report::count_text(cases.size(), "case", "cases"), info.gl_renderer, o.backend,
             info.gl_version, info.model, info.model_source, info.tolerance);
  for (const std::string& w : info.gl_warnings)
    fmt::print("warning: {}\n", w);

  // Without a fault every case must pass (or fail only as the baseline expects); only the
  // cases that pass clean can show that they catch a fault.
  const Progress progress;
  std::vector<CaseRun> runs;
  int clean_failures = 0, expected_failures = 0;
  for (size_t k = 0; k < cases.size(); ++k) {
    progress.show(k, cases.size(), "clean: " + cases[k].name);
    CaseRun run{&cases[k], expectation_for(cases[k], o, reported), Frame(),
                tolerance_for(cases[k], o, reported)};
    CaseResult r;
    try {
      run.clean = renderer->render(cases[k]);
      r = compare::compare(cases[k], run.expected, run.clean, run.tolerance);
    } catch (const gl::RenderError& e) {
      r.name = cases[k].name, r.status = r.outcome = Status::error, r.message = e.what();
    }
    apply(baseline, r);
    if (r.status == Status::pass) {
      runs.push_back(std::move(run));
    } else if (r.status == Status::expected_fail) {
      ++expected_failures;
    } else {
      ++clean_failures;
      progress.clear();
      fmt::print("without a fault: {}\n", report::case_line(r));
    }
  }

  std::vector<FaultRow> rows;
  for (const selftest::Fault& fault : selftest::faults()) {
    FaultRow row{fault.name, fault.description};
    for (size_t k = 0; k < runs.size(); ++k) {
      const CaseRun& run = runs[k];
      progress.show(k, runs.size(), fault.name + ": " + run.c->name);
      Case planted = *run.c;
      if (fault.before) fault.before(planted);
      try {
        Frame gl = fault.before ? renderer->render(planted) : run.clean;
        if (fault.after) fault.after(*run.c, run.expected, gl);
        if (same_bits(gl, run.clean)) continue;
        ++row.changed;
        const CaseResult r = compare::compare(*run.c, run.expected, gl, run.tolerance);
        if (r.status != Status::fail) continue;
        if (row.caught++ == 0) row.example = run.c->name + ": " + r.message;
      } catch (const gl::RenderError& e) {
        ++row.errors;
      }
    }
    rows.push_back(std::move(row));
  }
  progress.clear();

  size_t name_width = 5;
  for (const FaultRow& row : rows)
    name_width = std::max(name_width, row.name.size());
  fmt::print("\n{:<{}}  {:>7}  {:>6}  {}\n", "fault", name_width, "changed", "caught",
             "first case that caught it");
  int missed = 0;
  for (const FaultRow& row : rows) {
    std::string example = row.caught ? row.example : "NOT CAUGHT";
    if (example.size() > 110) example = example.substr(0, 107) + "...";
    fmt::print("{:<{}}  {:>7}  {:>6}  {}\n", row.name, name_width, row.changed, row.caught,
               example);
    missed += row.caught == 0;
  }
  fmt::print(
      "\n{}, {} caught, {} missed; without a fault: {} of {} pass, {}, {} ({:.2f} s)\n",
      report::count_text(rows.size(), "fault", "faults"), int(rows.size()) - missed, missed,
      runs.size(), report::count_text(cases.size(), "case", "cases"),
      report::count_text(uint64_t(expected_failures), "expected failure", "expected failures"),
      report::count_text(uint64_t(clean_failures), "unexpected failure", "unexpected failures"),
      seconds_since(start));
  return missed == 0 && clean_failures == 0 ? 0 : 1;
}

}  // namespace glrc::cli
