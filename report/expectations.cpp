#include "report/expectations.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>
#include <set>
#include <stdexcept>

#include <re2/re2.h>

#include "core/text.hpp"

namespace glrc::report {

namespace {
// Text from a file or the command line, for a one-line message: control characters escaped,
// at most 80 characters (a 100 KB line is not echoed whole).
std::string shown(const std::string& s) {
  return printable(s, 80);
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// Line n (1-based) of a baseline, flakes or skips file as meant: without the UTF-8 byte-order
// mark an editor may put first (it would join the first case's name or pattern, which would
// then match nothing), blanks and a CRLF's CR.
std::string line_content(std::string line, int n) {
  if (n == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);
  return trim(line);
}
}  // namespace

Baseline read_baseline(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error(file.string() +
                             ": expected a baseline file of `case,Status` lines, got " +
                             file_kind(file) + " (not read)");
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the baseline file");
  Baseline b;
  // Every line's case, expectation or not: `fan,Fail` then `fan,Pass` says two things of one case.
  std::set<std::string> listed;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = line_content(std::move(line), n);
    if (line.empty() || line[0] == '#') continue;
    // `case,Status` or `case,Status,seconds`
    std::vector<std::string> fields;
    for (size_t at = 0;;) {
      const auto comma = line.find(',', at);
      fields.push_back(trim(line.substr(at, comma == std::string::npos ? comma : comma - at)));
      if (comma == std::string::npos) break;
      at = comma + 1;
    }
    const auto where = file.string() + ":" + std::to_string(n) + ": ";
    if (fields.size() < 2 || fields.size() > 3 || fields[0].empty() || fields[1].empty())
      throw std::runtime_error(where + "expected `case,Status` (or `case,Status,seconds`), got \"" +
                               shown(line) + "\"");
    const std::string& name = fields[0];
    const std::string& status = fields[1];
    if (fields.size() == 3) {
      char* end = nullptr;
      std::strtod(fields[2].c_str(), &end);
      if (fields[2].empty() || *end != '\0')
        throw std::runtime_error(where + "expected seconds as the third field, got \"" +
                                 shown(fields[2]) + "\"");
    }
    // The failing statuses of Mesa CI's fails files; Crash and Timeout come from worker processes,
    // Error from a case the GL side could not render.
    if (!listed.insert(name).second)
      throw std::runtime_error(where + "expected each case once, got " + shown(name) + " again");
    constexpr std::array<const char*, 4> kExpectations = {"Fail", "Crash", "Timeout", "Error"};
    constexpr std::array<const char*, 4> kNoExpectation = {"Pass", "Skip", "Flake",
                                                           "UnexpectedPass"};
    if (std::find(kNoExpectation.begin(), kNoExpectation.end(), status) != kNoExpectation.end()) {
      if ((status == "Skip" || status == "Flake") && b.skip_or_flake_lines++ == 0)
        b.first_skip_or_flake = where + shown(name) + "," + status;
      continue;
    }
    if (std::find(kExpectations.begin(), kExpectations.end(), status) == kExpectations.end())
      throw std::runtime_error(
          where +
          "expected a status of Fail, Crash, Timeout or Error (or Pass, Skip, Flake or "
          "UnexpectedPass, as a results.csv has them, which expect nothing), got \"" +
          shown(status) + "\"" +
          (status == "ExpectedFail" ? " (ExpectedFail says that a case failed, not how: write "
                                      "its outcome)"
                                    : ""));
    b.expected.emplace(name, status);
  }
  if (in.bad()) throw std::runtime_error(file.string() + ": cannot read the baseline file");
  return b;
}

std::string ignored_note(const Baseline& b) {
  if (b.skip_or_flake_lines == 0) return "";
  const size_t more = b.skip_or_flake_lines - 1;
  return "note: " + b.first_skip_or_flake +
         (more ? " (and " + std::to_string(more) + " more Skip or Flake line" +
                     (more == 1 ? "" : "s") + ")"
               : "") +
         ": a baseline lists expected failures; it expects no skip or flake and ignores such "
         "lines (--skips and --flakes take patterns of cases to skip or to let flake)";
}

void apply(const Baseline& b, CaseResult& r) {
  const auto it = b.expected.find(r.name);
  if (it == b.expected.end()) return;
  if (it->second == to_string(r.status)) {
    r.message = "expected " + it->second + ": " + r.message;
    r.status = Status::expected_fail;
  } else if (fails_run(r.status)) {
    // Failing in another way than the baseline says is a change someone must look at.
    r.message = "expected " + it->second + ", got " + to_string(r.status) + ": " + r.message;
  } else if (r.status == Status::pass) {
    r.message = "listed as " + it->second + " in the baseline, but passes";
    r.status = Status::unexpected_pass;
  }
}

struct Regex::Compiled {
  re2::RE2 re;
  explicit Compiled(const std::string& pattern, const re2::RE2::Options& o) : re(pattern, o) {}
};

Regex::Regex(const std::string& pattern) {
  re2::RE2::Options o;
  o.set_log_errors(false);  // the error comes back as one line, not on stderr
  re_ = std::make_unique<Compiled>(pattern, o);
  if (!re_->re.ok())
    throw std::runtime_error("expected a regular expression (RE2 syntax), got \"" + shown(pattern) +
                             "\" (" + shown(re_->re.error()) + ")");
}
Regex::~Regex() = default;
Regex::Regex(Regex&&) noexcept = default;
Regex& Regex::operator=(Regex&&) noexcept = default;

bool Regex::search(const std::string& text) const {
  return re2::RE2::PartialMatch(text, re_->re);
}
bool Regex::full_match(const std::string& text) const {
  return re2::RE2::FullMatch(text, re_->re);
}

const std::string* Patterns::match(const std::string& name) const {
  for (const auto& [text, re] : list)
    if (re.full_match(name)) return &text;
  return nullptr;
}

Patterns read_patterns(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error(file.string() +
                             ": expected a file of regular expressions, one per line, got " +
                             file_kind(file) + " (not read)");
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot read it");
  Patterns p;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = line_content(std::move(line), n);
    if (line.empty() || line[0] == '#') continue;
    try {
      p.list.emplace_back(line, Regex(line));
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(file.string() + ":" + std::to_string(n) + ": " + e.what());
    }
  }
  return p;
}

CaseResult skipped_result(const std::string& name, const std::string& description,
                          const std::string& pattern, const std::string& file) {
  CaseResult r;
  r.name = name, r.description = description;
  r.status = r.outcome = Status::skip;
  r.message = "skipped: matches \"" + pattern + "\" in " + file;
  return r;
}

void apply_flakes(const Patterns& flakes, const std::string& file, CaseResult& r) {
  if (!fails_run(r.status)) return;
  if (const std::string* pattern = flakes.match(r.name)) {
    r.message = "known flake (\"" + *pattern + "\" in " + file + "), was " + to_string(r.status) +
                ": " + r.message;
    r.status = Status::flake;
  }
}

}  // namespace glrc::report
