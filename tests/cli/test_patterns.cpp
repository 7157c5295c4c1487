// Users' regular expressions (--filter, --flakes, --skips) through RE2: linear time, no stack
// overflow, and one line naming the file and line or the option for a bad one (issue 11).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "cli/session.hpp"
#include "report/expectations.hpp"
#include "tests/support/glrefcheck_process.hpp"

namespace glrc::cli {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("glrc_patterns_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

const char* kCase = R"({"description": "d", "vertices": [{"clip": [-1, -1, 0, 1]},
  {"clip": [1, -1, 0, 1]}, {"clip": [0, 1, 0, 1]}]})";

TEST(Patterns, FilterSearchesAndFlakesMatchTheWholeName) {
  EXPECT_TRUE(Regex("on").search("face_on"));
  EXPECT_FALSE(Regex("on").full_match("face_on"));
  EXPECT_TRUE(Regex("face.*").full_match("face_on"));
  EXPECT_TRUE(Regex(R"(^face_\w+$)").search("face_on"));
  const fs::path d = temp_dir("match");
  std::ofstream(d / "flakes.txt") << "# comment\n\nface\nattr_.*\n";
  const Patterns p = report::read_patterns(d / "flakes.txt");
  EXPECT_EQ(p.match("face_on"), nullptr);
  ASSERT_NE(p.match("attr_huge"), nullptr);
  EXPECT_EQ(*p.match("attr_huge"), "attr_.*");
  fs::remove_all(d);
}

// std::regex backtracked: `^(a|aa)*b$` over a 100-letter name ran for longer than the universe.
TEST(Patterns, BacktrackingPatternReturnsAtOnce) {
  const std::string name(100, 'a');
  EXPECT_FALSE(Regex("^(a|aa)*b$").search(name));
  EXPECT_TRUE(Regex("^(a|aa)*$").full_match(name));
  const fs::path d = temp_dir("backtrack");
  std::ofstream(d / (name + ".json")) << kCase;
  Options o;
  o.paths = {d.string()};
  o.filter = "^(a|aa)*b$";
  try {
    load_cases(o);
    FAIL() << "a case matched";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "no case matches in " + d.string() +
                                         ": 1 case file, none matching --filter ^(a|aa)*b$");
  }
  o.filter = "^(a|aa)*$";
  EXPECT_EQ(load_cases(o).size(), 1u);
  fs::remove_all(d);
}

// 24,000 nested groups overflowed std::regex's stack (SIGSEGV). RE2 parses without recursion
// and takes it; were it over RE2's memory limit it would be one line and exit 2.
TEST(Patterns, DeeplyNestedGroupsAreNoCrash) {
  const std::string nested = std::string(24000, '(') + "a" + std::string(24000, ')');
  EXPECT_TRUE(Regex(nested).search("xay"));
  EXPECT_FALSE(Regex(nested).search("xyz"));
  Options o;
  o.paths = {GLRC_SOURCE_DIR "/cases"};
  o.filter = "a";
  const size_t with_a = load_cases(o).size();
  o.filter = nested;
  EXPECT_EQ(load_cases(o).size(), with_a);
  // A pattern beyond RE2's memory budget is refused with one line, not a crash.
  try {
    Regex(std::string(50, '(') + "a{1000}" + std::string(50, ')') + "{1000}");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("expected a regular expression (RE2 syntax), got \"(((", 0), 0u)
        << e.what();
  }
}

TEST(Patterns, BadPatternInAFileNamesFileAndLine) {
  const fs::path d = temp_dir("bad");
  std::ofstream(d / "skips.txt") << "face_on\n# fine\n(a\n";
  try {
    report::read_patterns(d / "skips.txt");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              (d / "skips.txt").string() +
                  ":3: expected a regular expression (RE2 syntax), got \"(a\" (missing ): (a)");
  }
  // Through the command line: one line, exit 2.
  const auto o = test::glrefcheck("run cases/face_on.json --skips '" + (d / "skips.txt").string() +
                                  "' --out '" + (d / "out").string() + "'");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "glrefcheck: --skips: " + (d / "skips.txt").string() +
                       ":3: expected a regular expression (RE2 syntax), got \"(a\" (missing ): "
                       "(a)\n");
  fs::remove_all(d);
}

TEST(Patterns, BadFilterOnTheCommandLineIsOneLine) {
  const auto o = test::glrefcheck("list --filter '(?<name>x)'");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err.rfind("glrefcheck: --filter: expected a regular expression (RE2 syntax), got "
                        "\"(?<name>x)\" (",
                        0),
            0u)
      << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1);
}

// A bad 100 KB --filter was echoed whole, twice (RE2's error repeats the pattern); a baseline's
// 100 KB line whole: every quoted text is cut to 80 characters.
TEST(Patterns, QuotedTextIsCutToEightyCharacters) {
  try {
    Regex(std::string(100000, 'a') + "(");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    const std::string a80(80, 'a');
    EXPECT_EQ(std::string(e.what()), "expected a regular expression (RE2 syntax), got \"" + a80 +
                                         "... (100001 bytes)\" (missing ): " +
                                         std::string(69, 'a') + "... (100012 bytes))");
  }
  const fs::path d = temp_dir("long");
  std::ofstream(d / "fails.txt") << std::string(100000, 'x') << "\x1b[2J\n";
  try {
    report::read_baseline(d / "fails.txt");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (d / "fails.txt").string() +
                                         ":1: expected `case,Status` (or `case,Status,seconds`), "
                                         "got \"" +
                                         std::string(80, 'x') + "... (100004 bytes)\"");
  }
  fs::remove_all(d);
}

// `--backend egl --driver bogus` said only that eglInitialize failed.
// Issue 45's hostile campaign: an editor's byte-order mark joined the first case's name, and
// that line matched nothing, silently.
TEST(Patterns, ABaselinesByteOrderMarkIsNoPartOfTheFirstName) {
  const fs::path d = temp_dir("bom");
  std::ofstream(d / "known.txt") << "\xEF\xBB\xBF"
                                 << "clip_noperspective_x_plane,Fail\nb,Crash\n";
  const report::Baseline b = report::read_baseline(d / "known.txt");
  EXPECT_EQ(b.expected, (std::map<std::string, std::string>{{"clip_noperspective_x_plane", "Fail"},
                                                            {"b", "Crash"}}));
  fs::remove_all(d);
}

// The tenth hostile campaign (issue 45): a byte-order mark made a --flakes or --skips file's
// first pattern match nothing, silently (the baseline's reader dropped it; these did not). Run
// as a user runs it: `.*` first, after the mark, skips or excuses every case.
TEST(Patterns, AFlakesOrSkipsFilesByteOrderMarkIsNoPartOfTheFirstPattern) {
  const fs::path d = temp_dir("bom_patterns");
  std::ofstream(d / "all.txt") << "\xEF\xBB\xBF"
                               << "clip_noperspective.*\r\nface_on\n";
  const Patterns p = report::read_patterns(d / "all.txt");
  ASSERT_EQ(p.list.size(), 2u);
  EXPECT_EQ(p.list[0].first, "clip_noperspective.*");
  ASSERT_NE(p.match("clip_noperspective_x_plane"), nullptr);
  const auto skipped =
      test::glrefcheck("run --filter 'clip_noperspective_x_plane$' --jobs 1 --skips '" +
                       (d / "all.txt").string() + "' --out '" + (d / "out").string() + "'");
  EXPECT_EQ(skipped.exit_code, 0) << skipped.out << skipped.err;
  EXPECT_NE(skipped.out.find("1 skip"), std::string::npos) << skipped.out;
  fs::remove_all(d);
}

// The ninth hostile campaign (issue 45): `fan,Fail` then `fan,Pass` was read as an expected
// failure, the Pass line ignored (only expectations were checked for a second line). Either order
// is refused, naming the second line; two lines of one case with one status too.
TEST(Patterns, ABaselineNamesEachCaseOnceWhateverItsStatus) {
  const fs::path d = temp_dir("twice");
  for (const char* lines : {"a,Pass\nfan,Fail\nfan,Pass\n", "a,Pass\nfan,Pass\nfan,Fail\n",
                            "a,Pass\nfan,Skip\nfan,Skip\n"}) {
    std::ofstream(d / "known.txt") << lines;
    try {
      report::read_baseline(d / "known.txt");
      ADD_FAILURE() << "accepted: " << lines;
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()),
                (d / "known.txt").string() + ":3: expected each case once, got fan again");
    }
  }
  std::ofstream(d / "known.txt") << "a,Pass\nfan,Fail\nb,Skip\n";
  EXPECT_EQ(report::read_baseline(d / "known.txt").expected,
            (std::map<std::string, std::string>{{"fan", "Fail"}}));
  fs::remove_all(d);
}

TEST(EglDriver, AnUnknownDriverIsNamed) {
  const auto o =
      test::glrefcheck("run cases/face_on.json --backend egl --driver bogus --jobs 1 --out '" +
                       temp_dir("bogus").string() + "'");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.err.find("driver \"bogus\" (GALLIUM_DRIVER) could not start"), std::string::npos)
      << o.err;
  // Mesa's own "libEGL warning: ..." line came first: now it is inside glrefcheck's one line.
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  EXPECT_EQ(o.err.find("libEGL warning"), std::string::npos) << o.err;
  fs::remove_all(temp_dir("bogus"));
}

// The twelfth hostile campaign (issue 45): `case,Skip` in a baseline was accepted and did
// nothing, without a word, and an unknown status was refused naming only the four expected
// failures. Skip and Flake lines now get one note (run, selftest and fuzz print it); Pass and
// UnexpectedPass lines (a results.csv as a baseline) none; the refusal names every status.
TEST(Patterns, ABaselinesSkipOrFlakeLinesAreIgnoredWithANote) {
  const fs::path d = temp_dir("skip_lines");
  const std::string file = (d / "known.txt").string();
  std::ofstream(file) << "a,Pass\nb,UnexpectedPass\nc,Fail\n";
  EXPECT_EQ(report::ignored_note(report::read_baseline(file)), "");
  std::ofstream(file) << "a,Pass\nclip_noperspective_x_plane,Skip\nc,Fail\nd,Flake\ne,Flake\n";
  const report::Baseline b = report::read_baseline(file);
  EXPECT_EQ(b.expected, (std::map<std::string, std::string>{{"c", "Fail"}}));
  EXPECT_EQ(report::ignored_note(b),
            "note: " + file +
                ":2: clip_noperspective_x_plane,Skip (and 2 more Skip or Flake lines): a baseline "
                "lists expected failures; it expects no skip or flake and ignores such lines "
                "(--skips and --flakes take patterns of cases to skip or to let flake)");
  std::ofstream(file) << "a,Skipped\n";
  try {
    report::read_baseline(file);
    ADD_FAILURE() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              file +
                  ":1: expected a status of Fail, Crash, Timeout or Error (or Pass, Skip, Flake "
                  "or UnexpectedPass, as a results.csv has them, which expect nothing), got "
                  "\"Skipped\"");
  }
  // As a user meets it: the run says so, and the case still fails.
  std::ofstream(file) << "clip_noperspective_x_plane,Skip\n";
  const auto r =
      test::glrefcheck("run --filter 'clip_noperspective_x_plane$' --jobs 1 --baseline '" + file +
                       "' --out '" + (d / "out").string() + "'");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("note: " + file + ":1: clip_noperspective_x_plane,Skip: a baseline lists"),
            std::string::npos)
      << r.out;
  fs::remove_all(d);
}

}  // namespace
}  // namespace glrc::cli
