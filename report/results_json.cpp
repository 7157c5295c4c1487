// results.json: everything a CaseResult holds, for scripts and later comparison between runs.
// The types' own JSON is report/json_types.cpp; this is the files and lines made of them.
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "report/json_types.hpp"
#include "report/report.hpp"

namespace glrc::report {
namespace {

using nlohmann::json;
using typed_json::Reader;
using typed_json::Wording;

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
  return json(run).dump(-1, ' ', false, json::error_handler_t::replace);
}

RunInfo run_info_from_json(const std::string& text, const std::string& source) {
  RunInfo run;
  read(Reader(source, Wording::brief), parsed(text, source, "a run description"), "run", run);
  return run;
}

namespace {

// SIGINT and SIGTERM held back on this thread while a temporary file exists: delivered once it
// is renamed or removed, so that Ctrl-C in the middle of a large write (export's reproducer of
// megabytes) leaves the old file or the new one, and no temporary beside them.
class InterruptsHeld {
 public:
  InterruptsHeld() {
    sigset_t held;
    sigemptyset(&held);
    sigaddset(&held, SIGINT);
    sigaddset(&held, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &held, &before_);
  }
  ~InterruptsHeld() { pthread_sigmask(SIG_SETMASK, &before_, nullptr); }
  InterruptsHeld(const InterruptsHeld&) = delete;
  InterruptsHeld& operator=(const InterruptsHeld&) = delete;

 private:
  sigset_t before_;
};

}  // namespace

void write_file_atomically(const std::filesystem::path& file, const std::string& text) {
  const InterruptsHeld held;
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
  if (fd < 0)
    throw std::runtime_error("cannot write " + file.string() + " (" + strerror(errno) + ")");
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
  return json(r).dump(-1, ' ', false, json::error_handler_t::replace);
}

CaseResult case_result_from_json(const std::string& text, const std::string& source) {
  CaseResult r;
  read(Reader(source, Wording::brief), parsed(text, source, "a case result"), "case", r);
  return r;
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
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw std::runtime_error(
        file.string() + ": expected a results.json (or a folder holding one)" +
        (std::filesystem::exists(file, ec) ? ", cannot read it" : ", no such file"));
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(file.string() + ": expected JSON, got " + parse_error_text(e));
  }
  const Reader r(file.string(), Wording::brief);
  if (doc.is_object() && doc.contains("campaign") && !doc.contains("cases"))
    throw std::runtime_error(file.string() +
                             ": expected a run's results.json, got a fuzz campaign's (its "
                             "failures/ and report.html are the campaign's report; merge joins "
                             "campaign shards)");
  RunResults out;
  read(r, r.required(doc, "results.json", "run"), "run", out.run);
  std::unordered_map<std::string, size_t> named;
  r.elements(
      r.required(doc, "results.json", "cases"), "cases", "an array",
      [&](const json& c, const std::string& path) {
        read(r, c, path, out.cases.emplace_back());
        // A name run refuses (report::csv_breaking) is no case of a run: a hand's edit.
        if (const char* what = csv_breaking(out.cases.back().name))
          r.fail(path + ".name",
                 std::string("a case name fit for results.csv (it holds ") + what + ")",
                 Reader::describe(c.at("name")));
        // One result per case: a name twice (a hand edit, two files pasted together)
        // would be counted twice by whoever reads it.
        const auto [it, added] = named.emplace(out.cases.back().name, out.cases.size() - 1);
        if (!added)
          r.fail(path + ".name",
                 "a name no other case has (cases[" + std::to_string(it->second) + "] has it too)",
                 Reader::describe(c.at("name")));
      });
  // A run's cases are at most its suite's (a shard's fewer).
  if (out.run.total_cases > 0 && out.cases.size() > out.run.total_cases)
    r.fail("run.total_cases",
           "at least the cases results.json holds (" + std::to_string(out.cases.size()) + ")",
           std::to_string(out.run.total_cases));
  // Last, so that a malformed field is named first: a results.json that glrefcheck stamped and
  // a person then edited (a verdict flipped, a case renamed) is no run's results.
  out.stamp = json_stamp(doc.contains("written_by"), text);
  if (out.stamp == JsonStamp::edited) throw std::runtime_error(edited_stamp_message(file.string()));
  return out;
}

void write_results_json(const std::filesystem::path& file, const RunInfo& run,
                        const std::vector<CaseResult>& results) {
  const json doc = {{"run", run}, {"summary", summary_json(results)}, {"cases", results}};

  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  // Case names and messages come from files and drivers; replace bad UTF-8 rather than throw.
  // Stamped (report/stamp.hpp): whoever reads it back notices a hand's edit.
  write_file_atomically(
      file, stamped_json("run", doc.dump(2, ' ', false, json::error_handler_t::replace) + "\n"));
}

}  // namespace glrc::report
