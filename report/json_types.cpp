#include "report/json_types.hpp"

#include <climits>

#include "report/format.hpp"

namespace glrc {

using nlohmann::json;
using report::json_number;

void to_json(json& j, const WorstPixel& w) {
  j = {{"x", w.x},
       {"y", w.y},
       {"reference", json_number(w.reference)},
       {"gl", json_number(w.gl)},
       {"abs_error", json_number(w.abs_error)},
       {"ulps", json_number(w.ulps)},
       {"allowed", json_number(w.allowed)},
       {"ratio", json_number(w.ratio)}};
}

void to_json(json& j, const ChannelStats& c) {
  j = {{"name", c.name},
       {"compared", c.compared},
       {"over_tolerance", c.over_tolerance},
       {"non_finite", c.non_finite},
       {"undetermined", c.undetermined},
       {"differing", c.differing},
       {"max_abs", json_number(c.max_abs)},
       {"max_ulps", json_number(c.max_ulps)},
       {"mean_ulps", json_number(c.mean_ulps)},
       {"rms_ulps", json_number(c.rms_ulps)},
       {"p99_ulps", json_number(c.p99_ulps)},
       {"tolerance_ulps", json_number(c.tolerance_ulps)},
       {"max_ratio", json_number(c.max_ratio)},
       {"p99_ratio", json_number(c.p99_ratio)},
       {"pass", c.pass()},
       {"worst", c.worst}};
}

void to_json(json& j, const CoverageStats::Pixel& p) {
  j = {{"x", p.x},
       {"y", p.y},
       {"reference", p.reference},
       {"gl", p.gl},
       {"boundary", p.boundary},
       {"label", std::string(name_of(p.label))}};
}

void to_json(json& j, const CoverageStats& c) {
  j = {{"both", c.both},
       {"neither", c.neither},
       {"reference_only", c.reference_only},
       {"gl_only", c.gl_only},
       {"other_primitive", c.other_primitive},
       {"boundary", c.boundary},
       {"exact_tie", c.exact_tie},
       {"within_snapping", c.within_snapping},
       {"fill_rule", c.fill_rule},
       {"gaps", c.gaps},
       {"double_hits", c.double_hits},
       {"fragments_checked", c.fragments_checked},
       {"counts_traced", c.counts_traced},
       {"counts_untraced", c.counts_untraced},
       {"failures", c.failures},
       {"mismatches", c.mismatches}};
}

void to_json(json& j, const Tolerance& t) {
  j = {{"mode", to_string(t.mode)},
       {"subpixel_bits", t.subpixel_bits},
       {"varying_ulps", json_number(t.varying_ulps)},
       {"depth_ulps", json_number(t.depth_ulps)},
       {"allow_boundary", t.allow_boundary}};
}

void to_json(json& j, const CaseResult& r) {
  j = {{"name", r.name},
       {"description", r.description},
       {"status", to_string(r.status)},
       {"outcome", to_string(r.outcome)},
       {"message", r.message},
       {"gl_digest", r.gl_digest},
       {"seconds", json_number(r.seconds)},
       {"tolerance", r.tolerance},
       {"coverage", r.coverage},
       {"channels", r.channels}};
}

void to_json(json& j, const RunInfo& r) {
  j = {{"backend", r.backend},
       {"driver", r.driver},
       {"model", r.model},
       {"model_source", r.model_source},
       {"tolerance", r.tolerance},
       {"gl_subpixel_bits", r.subpixel_bits},
       {"gl_vendor", r.gl_vendor},
       {"gl_renderer", r.gl_renderer},
       {"gl_version", r.gl_version},
       {"mesa_prefix", r.mesa_prefix},
       {"gl_library", r.gl_library},
       {"gl_warnings", r.gl_warnings},
       {"gl_primitive_id_from_geometry_shader", r.gl_primitive_id_from_geometry_shader},
       {"jobs", r.jobs},
       {"fraction", r.fraction},
       {"fraction_start", r.fraction_start},
       {"total_cases", r.total_cases},
       {"seconds", json_number(r.seconds)},
       {"interrupted", r.interrupted},
       {"verdict_inputs", r.verdict_inputs}};
}

namespace {

// No source: a from_json caller knows where its JSON came from; the path says where in it.
template <class T>
void read_unsourced(const json& j, T& out) {
  report::read(typed_json::Reader("", typed_json::Wording::brief), j, "", out);
}

}  // namespace

void from_json(const json& j, WorstPixel& w) {
  read_unsourced(j, w);
}
void from_json(const json& j, ChannelStats& c) {
  read_unsourced(j, c);
}
void from_json(const json& j, CoverageStats::Pixel& p) {
  read_unsourced(j, p);
}
void from_json(const json& j, CoverageStats& c) {
  read_unsourced(j, c);
}
void from_json(const json& j, Tolerance& t) {
  read_unsourced(j, t);
}
void from_json(const json& j, CaseResult& r) {
  read_unsourced(j, r);
}
void from_json(const json& j, RunInfo& r) {
  read_unsourced(j, r);
}

}  // namespace glrc

namespace glrc::report {
namespace {

using typed_json::path_key;
using typed_json::Reader;

// The field `key` of the object `j`, each of results.json's kinds. A field that is missing
// (or `j` no object) is `expected a field "key"`.
double num(const Reader& r, const json& j, const std::string& path, const char* key) {
  return r.number_or_nonfinite(r.required(j, path, key), path_key(path, key));
}
uint64_t count(const Reader& r, const json& j, const std::string& path, const char* key) {
  return r.count(r.required(j, path, key), path_key(path, key));
}
bool boolean(const Reader& r, const json& j, const std::string& path, const char* key) {
  return r.boolean(r.required(j, path, key), path_key(path, key));
}
// A size, a count of ULPs or a share of the allowance: never below 0 (NaN and +inf pass: a
// statistic of non-finite values).
double magnitude(const Reader& r, const json& j, const std::string& path, const char* key) {
  const double v = num(r, j, path, key);
  if (v < 0) r.fail(path_key(path, key), "a number >= 0", Reader::describe(j.at(key)));
  return v;
}
// `optional`: "" when absent (a field added later than the first results.json).
std::string str(const Reader& r, const json& j, const std::string& path, const char* key,
                bool optional = false) {
  if (optional && !Reader::find(j, key)) return "";
  return r.string(r.required(j, path, key), path_key(path, key));
}
// An integer in [lo, hi]; `fallback` when absent (fields added later than the first
// results.json). Out of range names the range and what came; of another type, the range, or
// "an integer" when any int goes.
int integer(const Reader& r, const json& j, const std::string& path, const char* key, int fallback,
            int lo = INT_MIN, int hi = INT_MAX) {
  const json* v = Reader::find(j, key);
  if (!v) return fallback;
  const std::string at = path_key(path, key);
  const std::string range =
      hi == INT_MAX ? "an integer >= " + std::to_string(lo)
                    : "an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
  if (!v->is_number_integer()) r.fail(at, lo == INT_MIN ? "an integer" : range);
  return int(r.integer(*v, at, lo, hi, range));
}

}  // namespace

void read(const Reader& r, const json& j, const std::string& path, WorstPixel& w) {
  w.x = integer(r, j, path, "x", 0);
  w.y = integer(r, j, path, "y", 0);
  w.reference = float(num(r, j, path, "reference"));
  w.gl = float(num(r, j, path, "gl"));
  w.abs_error = magnitude(r, j, path, "abs_error");
  w.ulps = magnitude(r, j, path, "ulps");
  w.allowed = magnitude(r, j, path, "allowed");
  w.ratio = magnitude(r, j, path, "ratio");
}

void read(const Reader& r, const json& j, const std::string& path, ChannelStats& c) {
  c.name = str(r, j, path, "name");
  c.compared = count(r, j, path, "compared");
  c.over_tolerance = count(r, j, path, "over_tolerance");
  c.non_finite = count(r, j, path, "non_finite");
  // Absent in files written before it was counted (there it was 0).
  c.undetermined = j.contains("undetermined") ? count(r, j, path, "undetermined") : 0;
  c.differing = count(r, j, path, "differing");
  // The counts among the compared pixels: no more than those.
  for (const auto& [key, n] : {std::pair{"over_tolerance", c.over_tolerance},
                               {"non_finite", c.non_finite},
                               {"differing", c.differing}})
    if (n > c.compared)
      r.fail(path_key(path, key),
             "at most the pixels compared (" + std::to_string(c.compared) + ")",
             Reader::describe(j.at(key)));
  c.max_abs = magnitude(r, j, path, "max_abs");
  c.max_ulps = magnitude(r, j, path, "max_ulps");
  c.mean_ulps = magnitude(r, j, path, "mean_ulps");
  c.rms_ulps = magnitude(r, j, path, "rms_ulps");
  c.p99_ulps = magnitude(r, j, path, "p99_ulps");
  c.tolerance_ulps = magnitude(r, j, path, "tolerance_ulps");
  c.max_ratio = magnitude(r, j, path, "max_ratio");
  c.p99_ratio = magnitude(r, j, path, "p99_ratio");
  c.worst.clear();
  r.elements(r.required(j, path, "worst"), path_key(path, "worst"), "an array",
             [&](const json& e, const std::string& at) { read(r, e, at, c.worst.emplace_back()); });
}

void read(const Reader& r, const json& j, const std::string& path, CoverageStats::Pixel& p) {
  p.x = integer(r, j, path, "x", 0);
  p.y = integer(r, j, path, "y", 0);
  p.reference = integer(r, j, path, "reference", -1);
  p.gl = integer(r, j, path, "gl", -1);
  p.boundary = boolean(r, j, path, "boundary");
  p.label =
      r.name<CoverageStats::Label>(r.required(j, path, "label"), path_key(path, "label"),
                                   "exact_tie, within_snapping, fill_rule, gap or double_hit");
}

void read(const Reader& r, const json& j, const std::string& path, CoverageStats& c) {
  c.both = count(r, j, path, "both");
  c.neither = count(r, j, path, "neither");
  c.reference_only = count(r, j, path, "reference_only");
  c.gl_only = count(r, j, path, "gl_only");
  c.other_primitive = count(r, j, path, "other_primitive");
  c.boundary = count(r, j, path, "boundary");
  c.exact_tie = count(r, j, path, "exact_tie");
  c.within_snapping = count(r, j, path, "within_snapping");
  c.fill_rule = count(r, j, path, "fill_rule");
  c.gaps = count(r, j, path, "gaps");
  c.double_hits = count(r, j, path, "double_hits");
  c.fragments_checked = boolean(r, j, path, "fragments_checked");
  // Added later than the first results.json: 0 when absent.
  c.counts_traced = j.contains("counts_traced") ? count(r, j, path, "counts_traced") : 0;
  c.counts_untraced = j.contains("counts_untraced") ? count(r, j, path, "counts_untraced") : 0;
  c.failures = count(r, j, path, "failures");
  c.mismatches.clear();
  r.elements(
      r.required(j, path, "mismatches"), path_key(path, "mismatches"), "an array",
      [&](const json& e, const std::string& at) { read(r, e, at, c.mismatches.emplace_back()); });
}

void read(const Reader& r, const json& j, const std::string& path, Tolerance& t) {
  t.mode = r.name<ToleranceMode>(r.required(j, path, "mode"), path_key(path, "mode"),
                                 "spec, ulps or exact");
  t.subpixel_bits = integer(r, j, path, "subpixel_bits", 4);
  t.varying_ulps = num(r, j, path, "varying_ulps");
  t.depth_ulps = num(r, j, path, "depth_ulps");
  t.allow_boundary = boolean(r, j, path, "allow_boundary");
}

void read(const Reader& r, const json& j, const std::string& path, CaseResult& c) {
  const char* kStatus = "a status (Pass, Fail, Crash, ...)";
  c.name = str(r, j, path, "name");
  c.description = str(r, j, path, "description");
  c.status = r.name<Status>(r.required(j, path, "status"), path_key(path, "status"), kStatus);
  if (const json* outcome = Reader::find(j, "outcome")) {
    c.outcome = r.name<Status>(*outcome, path_key(path, "outcome"), kStatus);
  } else {  // written before outcomes were recorded
    c.outcome = c.status == Status::expected_fail     ? Status::fail
                : c.status == Status::unexpected_pass ? Status::pass
                                                      : c.status;
  }
  c.message = str(r, j, path, "message");
  c.gl_digest = str(r, j, path, "gl_digest", true);
  // SHA-256 in hex (ref::digest), or none where GL drew nothing to digest.
  if (!c.gl_digest.empty() &&
      (c.gl_digest.size() != 64 ||
       c.gl_digest.find_first_not_of("0123456789abcdef") != std::string::npos))
    r.fail(path_key(path, "gl_digest"), "a SHA-256 in 64 lowercase hex digits, or \"\"",
           Reader::describe(j.at("gl_digest")));
  c.seconds = magnitude(r, j, path, "seconds");
  read(r, r.required(j, path, "tolerance"), path_key(path, "tolerance"), c.tolerance);
  read(r, r.required(j, path, "coverage"), path_key(path, "coverage"), c.coverage);
  c.channels.clear();
  r.elements(
      r.required(j, path, "channels"), path_key(path, "channels"), "an array",
      [&](const json& e, const std::string& at) { read(r, e, at, c.channels.emplace_back()); });
}

void read(const Reader& r, const json& j, const std::string& path, RunInfo& run) {
  run.backend = str(r, j, path, "backend");
  run.driver = str(r, j, path, "driver");
  run.model = str(r, j, path, "model");
  run.model_source = str(r, j, path, "model_source", true);
  run.tolerance = str(r, j, path, "tolerance");
  run.subpixel_bits = integer(r, j, path, "gl_subpixel_bits", 0);
  run.gl_vendor = str(r, j, path, "gl_vendor");
  run.gl_renderer = str(r, j, path, "gl_renderer");
  run.gl_version = str(r, j, path, "gl_version");
  run.mesa_prefix = str(r, j, path, "mesa_prefix", true);
  run.gl_library = str(r, j, path, "gl_library", true);
  run.gl_warnings.clear();
  if (const json* w = Reader::find(j, "gl_warnings"))  // optional: runs before it have none
    r.elements(
        *w, path_key(path, "gl_warnings"), "an array of strings",
        [&](const json& e, const std::string& at) { run.gl_warnings.push_back(r.string(e, at)); });
  run.gl_primitive_id_from_geometry_shader = false;
  if (const json* v = Reader::find(j, "gl_primitive_id_from_geometry_shader"))  // added later
    run.gl_primitive_id_from_geometry_shader =
        r.boolean(*v, path_key(path, "gl_primitive_id_from_geometry_shader"));
  run.jobs = integer(r, j, path, "jobs", 1, 0);  // a merged run of no shards would say 0
  // The command line's own limits on --fraction and --fraction-start.
  run.fraction = integer(r, j, path, "fraction", 1, 1);
  run.fraction_start = integer(r, j, path, "fraction_start", 1, 1, run.fraction);
  run.total_cases = Reader::find(j, "total_cases") ? count(r, j, path, "total_cases") : 0;
  run.seconds = magnitude(r, j, path, "seconds");
  run.interrupted = false;
  if (const json* v = Reader::find(j, "interrupted"))
    run.interrupted = r.boolean(*v, path_key(path, "interrupted"));
  run.verdict_inputs.clear();
  if (const json* v = Reader::find(j, "verdict_inputs")) {  // added later
    const std::string at = path_key(path, "verdict_inputs");
    if (!v->is_object()) r.fail(at, "an object of strings", Reader::describe(*v));
    for (const auto& [key, value] : v->items())
      run.verdict_inputs[key] = r.string(value, path_key(at, key));
  }
}

}  // namespace glrc::report
