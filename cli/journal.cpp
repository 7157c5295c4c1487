#include "cli/journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <fmt/core.h>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "cli/options_reader.hpp"
#include "cli/output_dir.hpp"
#include "core/text.hpp"
#include "identify/model_cache.hpp"
#include "report/report.hpp"

namespace glrc::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Every option of `run`: the worker's (to_json of Options) and the runner's own.
json all_options_json(const Options& o) {
  json j = o;
  j["paths"] = o.paths;
  j["filter"] = o.filter;
  j["baseline"] = o.baseline;
  j["flakes"] = o.flakes;
  j["skips"] = o.skips;
  j["mesa"] = o.gl.mesa;
  j["jobs"] = o.jobs;
  j["jobs_force"] = o.jobs_force;
  j["timeout"] = o.timeout;
  j["fraction"] = o.fraction;
  j["fraction_start"] = o.fraction_start;
  j["html"] = o.html;
  return j;
}

// The journal's options, each checked as the command line checks it: a damaged or hand-edited
// journal is one line naming the field, never a run with --fraction 0 or --timeout -5.
Options all_options_from_json(const json& j, const std::string& where) {
  namespace f = option_fields;
  const typed_json::Reader r = f::reader(where);
  const std::string path = "options";
  Options o;
  read(r, j, path, o);
  o.paths = f::texts(r, j, path, "paths");
  o.filter = f::text(r, j, path, "filter");
  o.baseline = f::text(r, j, path, "baseline");
  o.flakes = f::text(r, j, path, "flakes");
  o.skips = f::text(r, j, path, "skips");
  o.gl.mesa = f::text(r, j, path, "mesa");
  o.jobs = f::whole(r, j, path, "jobs", 0);
  o.jobs_force = f::flag(r, j, path, "jobs_force");
  o.timeout = f::number(r, j, path, "timeout", 0.001, 1e6);  // --timeout's own range
  o.fraction = f::whole(r, j, path, "fraction", 1);
  o.fraction_start = f::whole(r, j, path, "fraction_start", 1, o.fraction);
  o.html = f::flag(r, j, path, "html");
  return o;
}

// Each line ends in its own digest, `,"digest":"sha256:<hex>"}`: the SHA-256 of the previous
// line's digest (none for the first) followed by the line as it would be without that field. A
// line a person edited (a verdict flipped, an option changed, a model's rule) no longer matches
// it, nor does a line taken from another run's journal (its chain is that run's), and --resume
// refuses the journal instead of mixing either into the run's results.
constexpr std::string_view kDigestField = ",\"digest\":\"";

std::string with_digest(std::string line, const std::string& previous) {
  const std::string digest = report::content_digest(previous + line);
  line.pop_back();  // the object's closing brace, which follows the digest instead
  return line + std::string(kDigestField) + digest + "\"}";
}

// The digest a line ends in, or "" when it ends in none.
std::string digest_of(std::string_view line) {
  const size_t at = line.rfind(kDigestField);
  if (at == std::string_view::npos || !line.ends_with("\"}")) return "";
  const size_t from = at + kDigestField.size();
  return std::string(line.substr(from, line.size() - 2 - from));
}

bool digest_holds(std::string_view line, const std::string& previous) {
  const std::string digest = digest_of(line);
  return !digest.empty() &&
         report::content_digest(previous + std::string(line.substr(0, line.rfind(kDigestField))) +
                                "}") == digest;
}

int open_journal(const fs::path& file, int flags) {
  const int fd = open(file.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC | flags, 0644);
  if (fd < 0)
    throw InputError("cannot write the run journal " + file.string() + ": " + strerror(errno));
  return fd;
}

}  // namespace

Journal Journal::start(const fs::path& dir, const Options& o, const std::vector<std::string>& files,
                       const std::vector<std::string>& file_digests,
                       const std::map<std::string, std::string>& verdict_inputs) {
  const fs::path file = dir / kJournalFile;
  Journal j(open_journal(file, O_CREAT | O_TRUNC), file);
  j.append(json{{"glrefcheck_journal", kJournalVersion},
                {"options", all_options_json(o)},
                {"files", files},
                {"file_digests", file_digests},
                {"verdict_inputs", verdict_inputs}}
               .dump(-1, ' ', false, json::error_handler_t::replace));
  return j;
}

Journal Journal::reopen(const fs::path& dir) {
  const fs::path file = dir / kJournalFile;
  std::ifstream in(file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  // A line cut short by a kill (its case runs again) goes, so the next line starts clean.
  const size_t end = text.rfind('\n');
  const size_t keep = end == std::string::npos ? 0 : end + 1;
  std::error_code ec;
  if (keep < text.size()) fs::resize_file(file, keep, ec);
  if (ec) throw InputError("cannot write the run journal " + file.string() + ": " + ec.message());
  Journal j(open_journal(file, 0), file);
  // The chain goes on from the last whole line's digest.
  const std::string_view whole = std::string_view(text).substr(0, keep > 0 ? keep - 1 : 0);
  j.last_digest_ = digest_of(whole.substr(whole.rfind('\n') + 1));
  return j;
}

Journal::~Journal() {
  if (fd_ >= 0) close(fd_);
}

void Journal::record_start(const RunInfo& info, const ModelChoice& model) {
  append("{\"run\":" + report::run_info_json(info) +
         ",\"model\":" + identify::model_json(model.model).dump() + ",\"model_source\":" +
         json(model.source).dump(-1, ' ', false, json::error_handler_t::replace) + "}");
}

void Journal::record_result(size_t index, const CaseResult& r, double at, Heatmaps heatmaps) {
  append(fmt::format("{{\"index\":{},\"at\":{},{}\"result\":{}}}", index, json(at).dump(),
                     heatmaps == Heatmaps::follow ? "\"heatmaps\":\"follow\"," : "",
                     report::case_result_json(r)));
}

void Journal::record_heatmaps_written(size_t index) {
  append(fmt::format("{{\"index\":{},\"heatmaps\":\"written\"}}", index));
}

void Journal::append(std::string line) {
  line = with_digest(std::move(line), last_digest_);
  last_digest_ = digest_of(line);
  line += '\n';
  // One write per line (O_APPEND): a kill leaves whole lines, and at worst the last one cut.
  for (size_t done = 0; done < line.size();) {
    const ssize_t n = write(fd_, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error("cannot write " + file_.string() + ": " + strerror(errno));
    done += size_t(n);
  }
}

namespace {

// Line 1: the run's options, its case files and their digests.
void read_first_line(const json& j, const std::string& where, JournalContents& c) {
  if (const json version = j.value("glrefcheck_journal", json()); version != kJournalVersion)
    throw InputError(where +
                     fmt::format(": expected a run journal of this glrefcheck (version {}), got ",
                                 kJournalVersion) +
                     (version.is_number()
                          ? "version " + version.dump() +
                                ": the run began under another glrefcheck; start it "
                                "again without --resume"
                          : "no glrefcheck_journal version"));
  if (!j.contains("options")) throw InputError(where + ": expected the run's options");
  c.options = all_options_from_json(j["options"], where);
  c.files = option_fields::texts(option_fields::reader(where), j, "", "files");
  // Each case file's content as the run began (absent in journals before it).
  if (j.contains("file_digests"))
    c.file_digests = option_fields::texts(option_fields::reader(where), j, "", "file_digests");
  if (!c.file_digests.empty() && c.file_digests.size() != c.files.size())
    throw InputError(where + ": expected one file digest per case file");
  if (j.contains("verdict_inputs")) {
    const json& inputs = j["verdict_inputs"];
    if (!inputs.is_object())
      throw InputError(where + ": expected \"verdict_inputs\": an object of texts");
    for (const auto& [name, value] : inputs.items()) {
      if (!value.is_string())
        throw InputError(where + ": expected verdict_inputs." + printable(name, 40) +
                         ": a text, got " + printable(value.dump(), 40));
      c.verdict_inputs[name] = value.get<std::string>();
    }
  }
}

// A case's line: its result (with "heatmaps": "follow" when they were on their way), or its
// heatmaps written. `heatmaps_due`: the cases whose heatmaps followed, not yet written.
void read_case_line(const json& j, const std::string& where, JournalContents& c,
                    std::set<size_t>& heatmaps_due) {
  if (!j.contains("index") || !j["index"].is_number_unsigned())
    // A hand's 0.5 or 1e300 would be read as another case's index.
    throw InputError(where + ": expected \"index\": a whole number, got " +
                     (j.contains("index") ? printable(j["index"].dump(), 40) : "none"));
  const size_t index = j.at("index");
  if (!j.contains("result")) {
    if (j.at("heatmaps") != "written")
      throw InputError(where + ": expected \"heatmaps\": \"written\" in a line without a result");
    heatmaps_due.erase(index);
    return;
  }
  CaseResult r = report::case_result_from_json(j.at("result").dump(), where);
  if (j.contains("heatmaps") && j["heatmaps"] != "follow")
    throw InputError(where +
                     ": expected \"heatmaps\": \"follow\", or no \"heatmaps\" field, in a line "
                     "with a result, got " +
                     printable(j["heatmaps"].dump(), 40));
  // A later line for a case is its heatmaps lost (the same verdict, its message saying so), or
  // the case checked again by a resume because its heatmaps never came; one with another name
  // or verdict otherwise is another run's, or a hand's: refused.
  const bool checked_again = heatmaps_due.erase(index) > 0;
  if (j.value("heatmaps", "") == "follow") heatmaps_due.insert(index);
  if (const auto earlier = c.results.find(index);
      earlier != c.results.end() && (earlier->second.name != r.name ||
                                     (!checked_again && (earlier->second.status != r.status ||
                                                         earlier->second.outcome != r.outcome))))
    throw InputError(fmt::format(
        "{}: expected case {} (\"{}\", {}) as an earlier line gives it, got \"{}\", {}: two "
        "results for one case (a line of another run's journal, or one edited by hand): start a "
        "new run",
        where, index, printable(earlier->second.name, 80), to_string(earlier->second.outcome),
        printable(r.name, 80), to_string(r.outcome)));
  c.results[index] = std::move(r);
  c.elapsed = std::max(c.elapsed, j.at("at").get<double>());
}

// Line `n` (1-based) into `c`, each field checked, then its digest (last, so that a malformed
// field is named first).
void read_line(const std::string& line, int n, const std::string& where, JournalContents& c,
               std::set<size_t>& heatmaps_due, std::string& previous) {
  json j;
  try {
    j = json::parse(line);
  } catch (const json::parse_error& e) {
    throw InputError(where +
                     ": expected a journal line of glrefcheck's, got invalid JSON at byte " +
                     std::to_string(e.byte));
  }
  if (!j.is_object()) throw InputError(where + ": expected a journal line of glrefcheck's");
  if (n == 1) {
    read_first_line(j, where, c);
  } else if (j.contains("run")) {
    c.run = report::run_info_from_json(j["run"].dump(), where);
    const auto model = identify::model_from_json(j.at("model"));
    if (!model) throw InputError(where + ": expected a model");
    c.model = ModelChoice{*model, j.at("model_source").get<std::string>()};
  } else {
    read_case_line(j, where, c, heatmaps_due);
  }
  if (!digest_holds(line, previous))
    throw InputError(
        where + ": expected the line as glrefcheck wrote it after the line before, got " +
        (j.contains("digest") ? "one its digest no longer matches (edited since, or another run's)"
                              : "one without its digest (edited since)") +
        ": start a new run");
  previous = digest_of(line);
}

}  // namespace

JournalContents read_journal(const fs::path& dir) {
  const fs::path file = dir / kJournalFile;
  const std::string name = printable(file.string());
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw InputError("--resume " + printable(dir.string()) + ": expected a run folder with a " +
                     kJournalFile + ", got " +
                     (fs::exists(fs::symlink_status(file, ec))  ? "one that is not a regular file"
                      : fs::is_directory(dir, ec)               ? "none in it"
                      : fs::exists(fs::symlink_status(dir, ec)) ? "a file, not a folder"
                                                                : "no such folder"));
  if (!is_marked(dir))
    throw InputError("--resume " + printable(dir.string()) +
                     ": expected a folder glrefcheck made (with a " + kMarkerFile + " file)");
  std::ifstream in(file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  JournalContents c;
  std::set<size_t> heatmaps_due;  // cases whose heatmaps followed their verdict, not yet written
  std::string previous;           // the last line's digest, which the next line's chains on
  size_t at = 0;
  for (int n = 1; at < text.size(); ++n) {
    const size_t eol = text.find('\n', at);
    if (eol == std::string::npos) break;  // cut short by a kill: that case runs again
    const std::string line = text.substr(at, eol - at);
    at = eol + 1;
    if (line.empty()) continue;  // where a reopened journal ended a cut line
    const std::string where = fmt::format("{}:{}", name, n);
    try {
      read_line(line, n, where, c, heatmaps_due, previous);
    } catch (const InputError&) {
      throw;
    } catch (const json::exception& e) {
      // A field of the wrong type past the checks above: say which kind, not nlohmann's words.
      throw InputError(where +
                       ": expected a journal line of glrefcheck's (a field of the wrong "
                       "type or missing, error " +
                       std::to_string(e.id) + ")");
    } catch (const std::exception& e) {
      throw InputError(where + ": expected a journal line of glrefcheck's (" +
                       printable(e.what(), 200) + ")");
    }
  }
  if (c.files.empty()) throw InputError(name + ": expected the run's first line, got none");
  for (const size_t index : heatmaps_due)
    c.heatmaps_cut += c.results.erase(index);
  return c;
}

}  // namespace glrc::cli
