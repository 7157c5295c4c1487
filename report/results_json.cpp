// results.json: everything a CaseResult holds, for scripts and later comparison between runs.
#include <cmath>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "report/report.hpp"

namespace glrc::report {
namespace {

using nlohmann::json;

// JSON has no NaN or infinity, and nlohmann would write them as null, which reads back as
// "missing" rather than as the very finding (GL gave NaN) the report is about. So a non-finite
// number is written as the string "nan", "inf" or "-inf"; every finite one stays a number.
// A reader must therefore accept a number or one of those three strings in any numeric field.
json number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

// Frame values are float32; widening to double is exact, and nlohmann prints the double with
// round-trip precision, so the float is recovered bit for bit.
json number(float v) {
  return number(double(v));
}

json run_json(const RunInfo& run) {
  return {{"backend", run.backend},
          {"driver", run.driver},
          {"model", run.model},
          {"tolerance", run.tolerance},
          {"gl_subpixel_bits", run.subpixel_bits},
          {"gl_vendor", run.gl_vendor},
          {"gl_renderer", run.gl_renderer},
          {"gl_version", run.gl_version},
          {"seconds", number(run.seconds)}};
}

json summary_json(const std::vector<CaseResult>& results) {
  // snake_case keys, unlike to_string(Status), so scripts can use them as identifiers.
  static constexpr struct {
    Status status;
    const char* key;
  } kKeys[] = {{Status::pass, "pass"},
               {Status::fail, "fail"},
               {Status::expected_fail, "expected_fail"},
               {Status::unexpected_pass, "unexpected_pass"},
               {Status::skip, "skip"},
               {Status::error, "error"}};
  json summary = {{"total", results.size()}};
  for (const auto& k : kKeys) {
    size_t n = 0;
    for (const auto& r : results)
      n += r.status == k.status;
    summary[k.key] = n;
  }
  return summary;
}

const char* label_name(CoverageStats::Label l) {
  switch (l) {
    case CoverageStats::Label::exact_tie:
      return "exact_tie";
    case CoverageStats::Label::within_snapping:
      return "within_snapping";
    case CoverageStats::Label::fill_rule:
      return "fill_rule";
    case CoverageStats::Label::gap:
      return "gap";
    case CoverageStats::Label::double_hit:
      return "double_hit";
  }
  return "fill_rule";
}

json coverage_json(const CoverageStats& cov) {
  json mismatches = json::array();
  for (const auto& p : cov.mismatches)
    mismatches.push_back({{"x", p.x},
                          {"y", p.y},
                          {"reference", p.reference},
                          {"gl", p.gl},
                          {"boundary", p.boundary},
                          {"label", label_name(p.label)}});
  return {{"both", cov.both},
          {"neither", cov.neither},
          {"reference_only", cov.reference_only},
          {"gl_only", cov.gl_only},
          {"other_primitive", cov.other_primitive},
          {"boundary", cov.boundary},
          {"exact_tie", cov.exact_tie},
          {"within_snapping", cov.within_snapping},
          {"fill_rule", cov.fill_rule},
          {"gaps", cov.gaps},
          {"double_hits", cov.double_hits},
          {"fragments_checked", cov.fragments_checked},
          {"failures", cov.failures},
          {"mismatches", std::move(mismatches)}};
}

json channel_json(const ChannelStats& ch) {
  json worst = json::array();
  for (const auto& w : ch.worst)
    worst.push_back({{"x", w.x},
                     {"y", w.y},
                     {"reference", number(w.reference)},
                     {"gl", number(w.gl)},
                     {"abs_error", number(w.abs_error)},
                     {"ulps", number(w.ulps)},
                     {"allowed", number(w.allowed)},
                     {"ratio", number(w.ratio)}});
  return {{"name", ch.name},
          {"compared", ch.compared},
          {"over_tolerance", ch.over_tolerance},
          {"non_finite", ch.non_finite},
          {"differing", ch.differing},
          {"max_abs", number(ch.max_abs)},
          {"max_ulps", number(ch.max_ulps)},
          {"mean_ulps", number(ch.mean_ulps)},
          {"rms_ulps", number(ch.rms_ulps)},
          {"p99_ulps", number(ch.p99_ulps)},
          {"tolerance_ulps", number(ch.tolerance_ulps)},
          {"max_ratio", number(ch.max_ratio)},
          {"p99_ratio", number(ch.p99_ratio)},
          {"pass", ch.pass()},
          {"worst", std::move(worst)}};
}

json case_json(const CaseResult& r) {
  json channels = json::array();
  for (const auto& ch : r.channels)
    channels.push_back(channel_json(ch));
  return {{"name", r.name},
          {"description", r.description},
          {"status", to_string(r.status)},
          {"message", r.message},
          {"seconds", number(r.seconds)},
          {"tolerance",
           {{"mode", to_string(r.tolerance.mode)},
            {"subpixel_bits", r.tolerance.subpixel_bits},
            {"varying_ulps", number(r.tolerance.varying_ulps)},
            {"depth_ulps", number(r.tolerance.depth_ulps)},
            {"allow_boundary", r.tolerance.allow_boundary}}},
          {"coverage", coverage_json(r.coverage)},
          {"channels", std::move(channels)}};
}

}  // namespace

void write_results_json(const std::filesystem::path& file, const RunInfo& run,
                        const std::vector<CaseResult>& results) {
  json cases = json::array();
  for (const auto& r : results)
    cases.push_back(case_json(r));
  json doc = {{"run", run_json(run)}, {"summary", summary_json(results)}, {"cases", cases}};

  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  // Case names and messages come from files and drivers; replace bad UTF-8 rather than throw.
  out << doc.dump(2, ' ', false, json::error_handler_t::replace) << '\n';
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace glrc::report
