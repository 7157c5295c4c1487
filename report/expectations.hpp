// Expected results, in Mesa CI's formats:
// - a baseline (*-fails.txt, or a previous run's failures.csv): `case,Status` lines, optionally
//   with a third field (results.csv's seconds); `#` comments and blank lines ignored (the
//   evidence for each entry goes in the comment above it);
// - flakes and skips files (*-flakes.txt, *-skips.txt): one regular expression per line (RE2
//   syntax), matched against the whole case name.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace glrc::report {

struct Baseline {
  std::map<std::string, std::string> expected;  // case name -> status as written ("Fail")
  // Lines that say Skip or Flake: a baseline expects no skip or flake of them (--skips and
  // --flakes do), so a person who wrote one is told (ignored_note). How many, and the first.
  size_t skip_or_flake_lines = 0;
  std::string first_skip_or_flake;  // "file:line: case,Status"
};

// One line for a baseline that holds Skip or Flake lines, which it ignores; "" for none.
std::string ignored_note(const Baseline& b);

// Throws std::runtime_error with "<file>:<line>: expected `case,Status`, got ..." on bad input.
// Statuses Fail, Crash, Timeout and Error are expectations; Pass, Skip, Flake and UnexpectedPass
// (lines of a results.csv or failures.csv) expect nothing and are ignored (Skip and Flake lines
// counted in Baseline::skip_or_flake_lines).
Baseline read_baseline(const std::filesystem::path& file);

// Applies the baseline to a result: a listed case with the listed status becomes ExpectedFail, a
// listed case that passes UnexpectedPass (the list needs updating, as in Mesa CI); one that fails
// with another status keeps it, with the expectation in its message.
void apply(const Baseline& b, CaseResult& r);

// A user's regular expression (--filter, flakes and skips files), in RE2's syntax (Debian's
// libre2): matching takes time linear in the name and no recursion, whatever the pattern.
// std::regex, used before, backtracks: `^(a|aa)*b$` on a long name never ended, and 24,000
// nested groups overflowed its stack.
class Regex {
 public:
  // Throws std::runtime_error with RE2's reason ("missing ): (a") for a pattern it refuses.
  explicit Regex(const std::string& pattern);
  ~Regex();
  Regex(Regex&&) noexcept;
  Regex& operator=(Regex&&) noexcept;
  bool search(const std::string& text) const;      // somewhere in text
  bool full_match(const std::string& text) const;  // all of text

 private:
  struct Compiled;
  std::unique_ptr<Compiled> re_;
};

struct Patterns {
  std::vector<std::pair<std::string, Regex>> list;  // as written, compiled
  // The first pattern matching all of `name`, or nullptr.
  const std::string* match(const std::string& name) const;
};
// Throws std::runtime_error "<file>:<line>: expected a regular expression, got ..." on bad input.
Patterns read_patterns(const std::filesystem::path& file);

// The result of a case a skips file leaves out: Skip, naming the pattern and the file.
CaseResult skipped_result(const std::string& name, const std::string& description,
                          const std::string& pattern, const std::string& file);
// A result that fails the run and matches a pattern of the flakes file `file` becomes Flake,
// its message naming the pattern and the status it had; any other result is left as it is.
void apply_flakes(const Patterns& flakes, const std::string& file, CaseResult& r);

}  // namespace glrc::report
