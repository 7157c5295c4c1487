// results.json: everything a CaseResult holds, for scripts and later comparison between runs.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "report/format.hpp"
#include "report/report.hpp"

namespace glrc::report {
namespace {

using nlohmann::json;

json run_json(const RunInfo& run) {
  return {{"backend", run.backend},
          {"driver", run.driver},
          {"model", run.model},
          {"model_source", run.model_source},
          {"tolerance", run.tolerance},
          {"gl_subpixel_bits", run.subpixel_bits},
          {"gl_vendor", run.gl_vendor},
          {"gl_renderer", run.gl_renderer},
          {"gl_version", run.gl_version},
          {"mesa_prefix", run.mesa_prefix},
          {"gl_library", run.gl_library},
          {"gl_warnings", run.gl_warnings},
          {"gl_primitive_id_from_geometry_shader", run.gl_primitive_id_from_geometry_shader},
          {"jobs", run.jobs},
          {"fraction", run.fraction},
          {"fraction_start", run.fraction_start},
          {"total_cases", run.total_cases},
          {"seconds", json_number(run.seconds)},
          {"interrupted", run.interrupted}};
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
               {Status::error, "error"},
               {Status::crash, "crash"},
               {Status::timeout, "timeout"},
               {Status::flake, "flake"}};
  json summary = {{"total", results.size()}};
  for (const auto& k : kKeys) {
    size_t n = 0;
    for (const auto& r : results)
      n += r.status == k.status;
    summary[k.key] = n;
  }
  return summary;
}

std::string label_name(CoverageStats::Label l) {
  return std::string(name_of(l));
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
                     {"reference", json_number(w.reference)},
                     {"gl", json_number(w.gl)},
                     {"abs_error", json_number(w.abs_error)},
                     {"ulps", json_number(w.ulps)},
                     {"allowed", json_number(w.allowed)},
                     {"ratio", json_number(w.ratio)}});
  return {{"name", ch.name},
          {"compared", ch.compared},
          {"over_tolerance", ch.over_tolerance},
          {"non_finite", ch.non_finite},
          {"differing", ch.differing},
          {"max_abs", json_number(ch.max_abs)},
          {"max_ulps", json_number(ch.max_ulps)},
          {"mean_ulps", json_number(ch.mean_ulps)},
          {"rms_ulps", json_number(ch.rms_ulps)},
          {"p99_ulps", json_number(ch.p99_ulps)},
          {"tolerance_ulps", json_number(ch.tolerance_ulps)},
          {"max_ratio", json_number(ch.max_ratio)},
          {"p99_ratio", json_number(ch.p99_ratio)},
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
          {"outcome", to_string(r.outcome)},
          {"message", r.message},
          {"gl_digest", r.gl_digest},
          {"seconds", json_number(r.seconds)},
          {"tolerance",
           {{"mode", to_string(r.tolerance.mode)},
            {"subpixel_bits", r.tolerance.subpixel_bits},
            {"varying_ulps", json_number(r.tolerance.varying_ulps)},
            {"depth_ulps", json_number(r.tolerance.depth_ulps)},
            {"allow_boundary", r.tolerance.allow_boundary}}},
          {"coverage", coverage_json(r.coverage)},
          {"channels", std::move(channels)}};
}

// ---- Reading back: the inverse of the above, for compare, merge and report. -------------------

// A field that is missing or of the wrong type is one line naming the file and the field.
struct Reader {
  const std::filesystem::path& file;

  [[noreturn]] void bad(const std::string& where, const std::string& expected) const {
    throw std::runtime_error(file.string() + ": " + where + ": expected " + expected);
  }
  const json& field(const json& j, const std::string& where, const char* key) const {
    if (!j.is_object() || !j.contains(key))
      bad(where + "." + key, std::string("a field \"") + key + "\"");
    return j.at(key);
  }
  double num(const json& j, const std::string& where, const char* key) const {
    const json& v = field(j, where, key);
    if (v.is_number()) return v.get<double>();
    if (v.is_string()) {
      const auto t = v.get<std::string>();
      if (t == "nan") return std::nan("");
      if (t == "inf") return HUGE_VAL;
      if (t == "-inf") return -HUGE_VAL;
    }
    bad(where + "." + key, "a number or \"nan\", \"inf\", \"-inf\"");
  }
  uint64_t count(const json& j, const std::string& where, const char* key) const {
    const json& v = field(j, where, key);
    if (!v.is_number_unsigned()) bad(where + "." + key, "a count (an integer >= 0)");
    return v.get<uint64_t>();
  }
  // An integer in [lo, hi]: a forged or damaged file must not reach the code that indexes by it
  // (merge's shard table) or read 2^32 + 1 as 1.
  int integer(const json& j, const std::string& where, const char* key, int fallback,
              int lo = std::numeric_limits<int>::min(),
              int hi = std::numeric_limits<int>::max()) const {
    if (!j.contains(key)) return fallback;  // fields added later than the first results.json
    const json& v = field(j, where, key);
    const std::string range =
        hi == std::numeric_limits<int>::max()
            ? "an integer >= " + std::to_string(lo)
            : "an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
    if (!v.is_number_integer())
      bad(where + "." + key, lo == std::numeric_limits<int>::min() ? "an integer" : range);
    // Parsed, a number >= 0 is unsigned, and may be beyond int64_t.
    const bool in_range =
        v.is_number_unsigned()
            ? v.get<uint64_t>() <= uint64_t(hi) && (lo <= 0 || v.get<uint64_t>() >= uint64_t(lo))
            : v.get<int64_t>() >= lo && v.get<int64_t>() <= hi;
    if (!in_range) bad(where + "." + key, range + ", got " + v.dump());
    return v.get<int>();
  }
  std::string str(const json& j, const std::string& where, const char* key,
                  bool optional = false) const {
    if (optional && !j.contains(key)) return "";
    const json& v = field(j, where, key);
    if (!v.is_string()) bad(where + "." + key, "a string");
    return v.get<std::string>();
  }
  bool boolean(const json& j, const std::string& where, const char* key) const {
    const json& v = field(j, where, key);
    if (!v.is_boolean()) bad(where + "." + key, "true or false");
    return v.get<bool>();
  }
  Status status(const json& j, const std::string& where, const char* key) const {
    const auto s = status_from_string(str(j, where, key));
    if (!s) bad(where + "." + key, "a status (Pass, Fail, Crash, ...)");
    return *s;
  }
};

RunInfo read_run(const Reader& rd, const json& j) {
  RunInfo run;
  run.backend = rd.str(j, "run", "backend");
  run.driver = rd.str(j, "run", "driver");
  run.model = rd.str(j, "run", "model");
  run.model_source = rd.str(j, "run", "model_source", true);
  run.tolerance = rd.str(j, "run", "tolerance");
  run.subpixel_bits = rd.integer(j, "run", "gl_subpixel_bits", 0);
  run.gl_vendor = rd.str(j, "run", "gl_vendor");
  run.gl_renderer = rd.str(j, "run", "gl_renderer");
  run.gl_version = rd.str(j, "run", "gl_version");
  run.mesa_prefix = rd.str(j, "run", "mesa_prefix", true);
  run.gl_library = rd.str(j, "run", "gl_library", true);
  if (j.contains("gl_warnings")) {  // optional: runs before it have none
    const json& w = j["gl_warnings"];
    if (!w.is_array()) rd.bad("run.gl_warnings", "an array of strings");
    for (size_t k = 0; k < w.size(); ++k) {
      if (!w[k].is_string()) rd.bad("run.gl_warnings[" + std::to_string(k) + "]", "a string");
      run.gl_warnings.push_back(w[k].get<std::string>());
    }
  }
  if (j.contains("gl_primitive_id_from_geometry_shader"))  // optional: added later
    run.gl_primitive_id_from_geometry_shader =
        rd.boolean(j, "run", "gl_primitive_id_from_geometry_shader");
  run.jobs = rd.integer(j, "run", "jobs", 1, 0);  // a merged run of no shards would say 0
  // The command line's own limits on --fraction and --fraction-start.
  run.fraction = rd.integer(j, "run", "fraction", 1, 1);
  run.fraction_start = rd.integer(j, "run", "fraction_start", 1, 1, run.fraction);
  run.total_cases = j.contains("total_cases") ? rd.count(j, "run", "total_cases") : 0;
  run.seconds = rd.num(j, "run", "seconds");
  if (j.contains("interrupted")) run.interrupted = rd.boolean(j, "run", "interrupted");
  return run;
}

CoverageStats read_coverage(const Reader& rd, const json& j, const std::string& where) {
  CoverageStats c;
  c.both = rd.count(j, where, "both");
  c.neither = rd.count(j, where, "neither");
  c.reference_only = rd.count(j, where, "reference_only");
  c.gl_only = rd.count(j, where, "gl_only");
  c.other_primitive = rd.count(j, where, "other_primitive");
  c.boundary = rd.count(j, where, "boundary");
  c.exact_tie = rd.count(j, where, "exact_tie");
  c.within_snapping = rd.count(j, where, "within_snapping");
  c.fill_rule = rd.count(j, where, "fill_rule");
  c.gaps = rd.count(j, where, "gaps");
  c.double_hits = rd.count(j, where, "double_hits");
  c.fragments_checked = rd.boolean(j, where, "fragments_checked");
  c.failures = rd.count(j, where, "failures");
  const json& list = rd.field(j, where, "mismatches");
  if (!list.is_array()) rd.bad(where + ".mismatches", "an array");
  for (size_t k = 0; k < list.size(); ++k) {
    const std::string at = where + ".mismatches[" + std::to_string(k) + "]";
    CoverageStats::Pixel p;
    p.x = rd.integer(list[k], at, "x", 0);
    p.y = rd.integer(list[k], at, "y", 0);
    p.reference = rd.integer(list[k], at, "reference", -1);
    p.gl = rd.integer(list[k], at, "gl", -1);
    p.boundary = rd.boolean(list[k], at, "boundary");
    const std::string label = rd.str(list[k], at, "label");
    const auto known = from_name<CoverageStats::Label>(label);
    if (!known) rd.bad(at + ".label", "exact_tie, within_snapping, fill_rule, gap or double_hit");
    p.label = *known;
    c.mismatches.push_back(p);
  }
  return c;
}

ChannelStats read_channel(const Reader& rd, const json& j, const std::string& where) {
  ChannelStats ch;
  ch.name = rd.str(j, where, "name");
  ch.compared = rd.count(j, where, "compared");
  ch.over_tolerance = rd.count(j, where, "over_tolerance");
  ch.non_finite = rd.count(j, where, "non_finite");
  ch.differing = rd.count(j, where, "differing");
  ch.max_abs = rd.num(j, where, "max_abs");
  ch.max_ulps = rd.num(j, where, "max_ulps");
  ch.mean_ulps = rd.num(j, where, "mean_ulps");
  ch.rms_ulps = rd.num(j, where, "rms_ulps");
  ch.p99_ulps = rd.num(j, where, "p99_ulps");
  ch.tolerance_ulps = rd.num(j, where, "tolerance_ulps");
  ch.max_ratio = rd.num(j, where, "max_ratio");
  ch.p99_ratio = rd.num(j, where, "p99_ratio");
  const json& list = rd.field(j, where, "worst");
  if (!list.is_array()) rd.bad(where + ".worst", "an array");
  for (size_t k = 0; k < list.size(); ++k) {
    const std::string at = where + ".worst[" + std::to_string(k) + "]";
    WorstPixel w;
    w.x = rd.integer(list[k], at, "x", 0);
    w.y = rd.integer(list[k], at, "y", 0);
    w.reference = float(rd.num(list[k], at, "reference"));
    w.gl = float(rd.num(list[k], at, "gl"));
    w.abs_error = rd.num(list[k], at, "abs_error");
    w.ulps = rd.num(list[k], at, "ulps");
    w.allowed = rd.num(list[k], at, "allowed");
    w.ratio = rd.num(list[k], at, "ratio");
    ch.worst.push_back(w);
  }
  return ch;
}

ToleranceMode read_mode(const Reader& rd, const json& j, const std::string& where) {
  const std::string m = rd.str(j, where, "mode");
  for (auto mode : {ToleranceMode::spec, ToleranceMode::ulps, ToleranceMode::exact})
    if (m == to_string(mode)) return mode;
  rd.bad(where + ".mode", "spec, ulps or exact");
}

CaseResult read_case(const Reader& rd, const json& j, const std::string& where) {
  CaseResult r;
  r.name = rd.str(j, where, "name");
  r.description = rd.str(j, where, "description");
  r.status = rd.status(j, where, "status");
  if (j.contains("outcome")) {
    r.outcome = rd.status(j, where, "outcome");
  } else {  // written before outcomes were recorded
    r.outcome = r.status == Status::expected_fail     ? Status::fail
                : r.status == Status::unexpected_pass ? Status::pass
                                                      : r.status;
  }
  r.message = rd.str(j, where, "message");
  r.gl_digest = rd.str(j, where, "gl_digest", true);
  r.seconds = rd.num(j, where, "seconds");
  const json& t = rd.field(j, where, "tolerance");
  r.tolerance.mode = read_mode(rd, t, where + ".tolerance");
  r.tolerance.subpixel_bits = rd.integer(t, where + ".tolerance", "subpixel_bits", 4);
  r.tolerance.varying_ulps = rd.num(t, where + ".tolerance", "varying_ulps");
  r.tolerance.depth_ulps = rd.num(t, where + ".tolerance", "depth_ulps");
  r.tolerance.allow_boundary = rd.boolean(t, where + ".tolerance", "allow_boundary");
  r.coverage = read_coverage(rd, rd.field(j, where, "coverage"), where + ".coverage");
  const json& chs = rd.field(j, where, "channels");
  if (!chs.is_array()) rd.bad(where + ".channels", "an array");
  for (size_t k = 0; k < chs.size(); ++k)
    r.channels.push_back(read_channel(rd, chs[k], where + ".channels[" + std::to_string(k) + "]"));
  return r;
}

}  // namespace

namespace {

// `text` as JSON, or one line naming `source` and what it should have been.
// nlohmann's parse error for a one-line message: without its "[json.exception...]" tag, cut to
// 120 characters (it quotes what it read last, which can be anything).
std::string parse_error_text(const json::parse_error& e) {
  std::string t = e.what();
  if (const auto tag = t.find("] "); t.rfind("[json.exception", 0) == 0 && tag != t.npos)
    t = t.substr(tag + 2);
  std::string out;
  for (const char ch : t.substr(0, 120)) {
    const auto c = static_cast<unsigned char>(ch);
    out += c < 0x20 || c == 0x7f ? '?' : ch;
  }
  return "invalid JSON (" + out + (t.size() > 120 ? "...)" : ")");
}

json parsed(const std::string& text, const std::string& source, const char* what) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(source + ": expected " + what + " in JSON, got " +
                             parse_error_text(e));
  }
}

}  // namespace

std::string run_info_json(const RunInfo& run) {
  return run_json(run).dump(-1, ' ', false, json::error_handler_t::replace);
}

RunInfo run_info_from_json(const std::string& text, const std::string& source) {
  return read_run(Reader{std::filesystem::path(source)}, parsed(text, source, "a run description"));
}

void write_file_atomically(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path dir = file.has_parent_path() ? file.parent_path() : ".";
  // Dot-named, so nobody takes a leftover for a result; the pid keeps two writers apart.
  // Appended piece by piece: GCC 12's Release inlining of `"." + string` reports a false
  // -Wrestrict (tests/build/release_build.sh).
  std::string name = ".";
  name += file.filename().string();
  name += ".tmp-";
  name += std::to_string(getpid());
  const std::filesystem::path tmp = dir / name;
  const int fd = open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write " + file.string());
  bool ok = true;
  for (size_t done = 0; ok && done < text.size();) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) done += size_t(n);
  }
  const int error = ok ? 0 : errno;
  // fsync before rename: after a crash of the machine the name never points at a hole.
  ok = ok && fsync(fd) == 0;
  ok = close(fd) == 0 && ok;
  ok = ok && rename(tmp.c_str(), file.c_str()) == 0;
  if (!ok) {
    const int why = error ? error : errno;
    unlink(tmp.c_str());
    throw std::runtime_error("cannot write " + file.string() + " (" + strerror(why) + ")");
  }
}

std::string case_result_json(const CaseResult& r) {
  return case_json(r).dump(-1, ' ', false, json::error_handler_t::replace);
}

CaseResult case_result_from_json(const std::string& text, const std::string& source) {
  return read_case(Reader{std::filesystem::path(source)}, parsed(text, source, "a case result"),
                   "case");
}

std::filesystem::path run_folder(const std::filesystem::path& file_or_dir) {
  std::error_code ec;
  if (std::filesystem::is_directory(file_or_dir, ec)) return file_or_dir;
  return file_or_dir.has_parent_path() ? file_or_dir.parent_path() : ".";
}

RunResults read_results_json(const std::filesystem::path& file) {
  std::error_code ec;
  const auto st = std::filesystem::status(file, ec);
  if (std::filesystem::is_directory(st)) return read_results_json(file / "results.json");
  // Opening a FIFO would wait for a writer forever; a device is no results.json either.
  if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
    throw std::runtime_error(file.string() +
                             ": expected a results.json (or a folder holding one), got something "
                             "other than a regular file (not read)");
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error(
        file.string() + ": expected a results.json (or a folder holding one)" +
        (std::filesystem::exists(file, ec) ? ", cannot read it" : ", no such file"));
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(file.string() + ": expected JSON, got " + parse_error_text(e));
  }
  const Reader rd{file};
  RunResults out;
  out.run = read_run(rd, rd.field(doc, "results.json", "run"));
  const json& cases = rd.field(doc, "results.json", "cases");
  if (!cases.is_array()) rd.bad("cases", "an array");
  for (size_t k = 0; k < cases.size(); ++k)
    out.cases.push_back(read_case(rd, cases[k], "cases[" + std::to_string(k) + "]"));
  return out;
}

void write_results_json(const std::filesystem::path& file, const RunInfo& run,
                        const std::vector<CaseResult>& results) {
  json cases = json::array();
  for (const auto& r : results)
    cases.push_back(case_json(r));
  json doc = {{"run", run_json(run)}, {"summary", summary_json(results)}, {"cases", cases}};

  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  // Case names and messages come from files and drivers; replace bad UTF-8 rather than throw.
  write_file_atomically(file, doc.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
}

}  // namespace glrc::report
