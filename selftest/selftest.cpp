#include "selftest/selftest.hpp"

#include <cstring>
#include <utility>

#include "compare/compare.hpp"
#include "selftest/faults.hpp"

namespace glrc::selftest {
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

}  // namespace

int SelftestResult::missed() const {
  int n = 0;
  for (const FaultRow& row : faults)
    n += row.caught == 0;
  return n;
}

SelftestResult run_selftest(const std::vector<Case>& cases, gl::Renderer& renderer,
                            const check::CheckOptions& o, const report::Baseline& baseline,
                            const SelftestProgress& progress) {
  const auto step = [&](size_t k, size_t n, const std::string& what) {
    if (progress.step) progress.step(k, n, what);
  };
  SelftestResult out;
  out.cases = cases.size();
  const int reported = renderer.info().subpixel_bits;
  // Without a fault every case must pass (or fail only as the baseline expects); only the
  // cases that pass clean can show that they catch a fault.
  std::vector<CaseRun> runs;
  for (size_t k = 0; k < cases.size(); ++k) {
    step(k, cases.size(), "clean: " + cases[k].name);
    CaseRun run{&cases[k], check::expectation_for(cases[k], o, reported), Frame(),
                check::tolerance_for(cases[k], o, reported)};
    CaseResult r;
    try {
      run.clean = renderer.render(cases[k]);
      // Judged as `run` judges it, the coverage its edge bits excuse traced to triangles (the
      // renderer's traces are this case's until it draws another; the faults below are planted
      // where the coverage is decided, and judged without).
      const auto traces = check::trace_source(cases[k], renderer, o, reported);
      r = compare::compare(cases[k], run.expected, run.clean, run.tolerance, 1,
                           traces ? &*traces : nullptr);
    } catch (const gl::FeatureMissing&) {
      ++out.skipped;
      continue;
    } catch (const gl::RenderError& e) {
      r.name = cases[k].name, r.status = r.outcome = Status::error, r.message = e.what();
    }
    report::apply(baseline, r);
    if (r.status == Status::pass) {
      runs.push_back(std::move(run));
    } else if (r.status == Status::expected_fail) {
      ++out.expected_failures;
    } else {
      if (progress.clean_failure) progress.clean_failure(r);
      out.clean_failures.push_back(std::move(r));
    }
  }
  out.passed_clean = runs.size();

  for (const Fault& fault : faults()) {
    FaultRow row{fault.name, fault.description};
    for (size_t k = 0; k < runs.size(); ++k) {
      const CaseRun& run = runs[k];
      step(k, runs.size(), fault.name + ": " + run.c->name);
      Case planted = *run.c;
      if (fault.before) fault.before(planted);
      try {
        Frame gl = fault.before ? renderer.render(planted) : run.clean;
        if (fault.after) fault.after(*run.c, run.expected, gl);
        if (same_bits(gl, run.clean)) continue;
        ++row.changed;
        const CaseResult r = compare::compare(*run.c, run.expected, gl, run.tolerance);
        if (r.status != Status::fail) continue;
        if (row.caught++ == 0) row.example = run.c->name + ": " + r.message;
      } catch (const gl::RenderError&) {
        ++row.errors;
      }
    }
    out.faults.push_back(std::move(row));
  }
  return out;
}

}  // namespace glrc::selftest
