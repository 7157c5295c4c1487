// compare_runs and its three reports: which case changes count as regressions, when a grown
// error is flagged, and what the text, Markdown and JSON say about it.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "report/report.hpp"
#include "report/run_compare.hpp"
#include "tests/report/test_helpers.hpp"

namespace glrc::report::test {
namespace {

using Kind = CaseChange::Kind;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

CaseResult result(const std::string& name, Status outcome, std::vector<ChannelStats> channels = {},
                  const std::string& message = "") {
  CaseResult r;
  r.name = name;
  r.status = r.outcome = outcome;
  r.message = message;
  r.channels = std::move(channels);
  return r;
}

// A channel with the given max and p99 errors in ULPs and share of the allowance.
ChannelStats stats(const std::string& name, double max_ulps, double p99_ulps,
                   double max_ratio = 0.01, uint64_t compared = 100) {
  ChannelStats ch;
  ch.name = name;
  ch.compared = compared;
  ch.max_ulps = max_ulps;
  ch.p99_ulps = p99_ulps;
  ch.max_ratio = max_ratio;
  return ch;
}

RunResults run(std::vector<CaseResult> cases, const std::string& renderer = "llvmpipe") {
  RunResults r;
  r.run = run_info();
  r.run.gl_renderer = renderer;
  r.cases = std::move(cases);
  return r;
}

// One case from base to current, compared.
CaseChange change(const CaseResult& base, const CaseResult& current, double factor = 2,
                  double min_ulps = 1) {
  const RunComparison c = compare_runs(run({base}), run({current}), factor, min_ulps);
  EXPECT_EQ(c.cases.size(), 1u);
  return c.cases.at(0);
}

// One channel's growth from `base` to `current` max ULPs (p99 unchanged at 0).
ChannelChange growth(double base, double current, double factor = 2, double min_ulps = 1) {
  const CaseChange c =
      change(result("c", Status::pass, {stats("color.x", base, 0)}),
             result("c", Status::pass, {stats("color.x", current, 0)}), factor, min_ulps);
  EXPECT_EQ(c.channels.size(), 1u);
  return c.channels.at(0);
}

TEST(RunCompare, PassToFailIsARegression) {
  const RunComparison c =
      compare_runs(run({result("a", Status::pass)}),
                   run({result("a", Status::fail, {}, "color.x: 3 px over the allowance")}));
  ASSERT_EQ(c.cases.size(), 1u);
  EXPECT_EQ(c.cases[0].kind, Kind::regression);
  EXPECT_EQ(c.cases[0].base, Status::pass);
  EXPECT_EQ(c.cases[0].current, Status::fail);
  EXPECT_EQ(c.cases[0].message, "color.x: 3 px over the allowance");
  EXPECT_EQ(c.count(Kind::regression), 1u);
  EXPECT_TRUE(c.has_regression());
}

TEST(RunCompare, EveryFailingOutcomeAfterAPassIsARegression) {
  for (const Status s : {Status::fail, Status::crash, Status::timeout, Status::error})
    EXPECT_EQ(change(result("a", Status::pass), result("a", s)).kind, Kind::regression)
        << to_string(s);
}

TEST(RunCompare, FailToPassIsAFix) {
  const RunComparison c =
      compare_runs(run({result("a", Status::fail)}), run({result("a", Status::pass)}));
  EXPECT_EQ(c.cases.at(0).kind, Kind::fix);
  EXPECT_FALSE(c.has_regression());
  EXPECT_EQ(change(result("a", Status::crash), result("a", Status::pass)).kind, Kind::fix);
}

TEST(RunCompare, FailToCrashOrTimeoutIsARegression) {
  EXPECT_EQ(change(result("a", Status::fail), result("a", Status::crash)).kind, Kind::regression);
  EXPECT_EQ(change(result("a", Status::fail), result("a", Status::timeout)).kind, Kind::regression);
  EXPECT_EQ(change(result("a", Status::error), result("a", Status::crash)).kind, Kind::regression);
}

TEST(RunCompare, FailingDifferentlyIsChanged) {
  EXPECT_EQ(change(result("a", Status::crash), result("a", Status::fail)).kind, Kind::changed);
  EXPECT_EQ(change(result("a", Status::crash), result("a", Status::timeout)).kind, Kind::changed);
  EXPECT_EQ(change(result("a", Status::fail), result("a", Status::error)).kind, Kind::changed);
  const RunComparison c =
      compare_runs(run({result("a", Status::crash)}), run({result("a", Status::fail)}));
  EXPECT_FALSE(c.has_regression());
}

TEST(RunCompare, OutcomesNotExpectationsAreCompared) {
  // Base expected the failure (ExpectedFail), current's baseline did not: the case did the same.
  CaseResult base = result("a", Status::fail), current = result("a", Status::fail);
  base.status = Status::expected_fail;
  EXPECT_EQ(change(base, current).kind, Kind::unchanged);
}

TEST(RunCompare, AddedAndRemovedCasesComeAfterInOrder) {
  const RunComparison c = compare_runs(
      run({result("kept", Status::pass), result("gone", Status::fail, {}, "was failing")}),
      run({result("new", Status::fail, {}, "fails"), result("kept", Status::pass)}));
  ASSERT_EQ(c.cases.size(), 3u);
  EXPECT_EQ(c.cases[0].name, "new");
  EXPECT_EQ(c.cases[0].kind, Kind::added);
  EXPECT_EQ(c.cases[0].base, std::nullopt);
  EXPECT_EQ(c.cases[0].current, Status::fail);
  EXPECT_EQ(c.cases[1].name, "kept");
  EXPECT_EQ(c.cases[1].kind, Kind::unchanged);
  EXPECT_EQ(c.cases[2].name, "gone");
  EXPECT_EQ(c.cases[2].kind, Kind::removed);
  EXPECT_EQ(c.cases[2].base, Status::fail);
  EXPECT_EQ(c.cases[2].current, std::nullopt);
  EXPECT_EQ(c.cases[2].message, "was failing");
  // A new failing case is not a regression of anything.
  EXPECT_FALSE(c.has_regression());
}

TEST(RunCompare, SkipInEitherRunIsSkippedNotARegression) {
  const RunComparison c = compare_runs(
      run({result("a", Status::pass), result("b", Status::skip), result("c", Status::skip)}),
      run({result("a", Status::skip, {}, "no EGL device"), result("b", Status::fail),
           result("c", Status::skip)}));
  EXPECT_EQ(c.count(Kind::skipped), 3u);
  EXPECT_FALSE(c.has_regression());
  const std::string text = comparison_text(c);
  EXPECT_NE(text.find("\n3 skipped (in one run or both):\n  Pass -> Skip  a     no EGL device\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("Skip -> Fail  b"), std::string::npos) << text;
  EXPECT_NE(text.find("(1 skipped in both runs)"), std::string::npos) << text;
  EXPECT_EQ(text.find("no change"), std::string::npos) << text;
}

TEST(RunCompare, SkippedInBothIsNoChange) {
  const RunComparison c = compare_runs(run({result("a", Status::skip), result("b", Status::pass)}),
                                       run({result("a", Status::skip), result("b", Status::pass)}));
  EXPECT_EQ(c.count(Kind::skipped), 1u);
  EXPECT_NE(comparison_text(c).find("\nno change\n"), std::string::npos) << comparison_text(c);
}

TEST(RunCompare, MaxGrownThreefoldIsAPrecisionChange) {
  const CaseChange c =
      change(result("a", Status::pass, {stats("depth", 1, 1), stats("color.x", 2, 1, 0.01)}),
             result("a", Status::pass, {stats("depth", 1, 1), stats("color.x", 6, 1.5, 0.03)}));
  EXPECT_EQ(c.kind, Kind::precision);
  ASSERT_EQ(c.channels.size(), 2u);
  EXPECT_EQ(c.channels[0].channel, "depth");
  EXPECT_FALSE(c.channels[0].max_grew);
  const ChannelChange& ch = c.channels[1];
  EXPECT_EQ(ch.channel, "color.x");
  EXPECT_EQ(ch.base_max_ulps, 2);
  EXPECT_EQ(ch.current_max_ulps, 6);
  EXPECT_EQ(ch.base_p99_ulps, 1);
  EXPECT_EQ(ch.current_p99_ulps, 1.5);
  EXPECT_EQ(ch.base_max_ratio, 0.01);
  EXPECT_EQ(ch.current_max_ratio, 0.03);
  EXPECT_TRUE(ch.max_grew);
  EXPECT_FALSE(ch.p99_grew);
}

TEST(RunCompare, GrowthWithinTheFactorIsNotFlagged) {
  const ChannelChange ch = growth(4, 6);  // x1.5
  EXPECT_FALSE(ch.max_grew);
  EXPECT_FALSE(growth(4, 8).max_grew);  // exactly the factor is within it
  EXPECT_EQ(change(result("a", Status::pass, {stats("c.x", 4, 2)}),
                   result("a", Status::pass, {stats("c.x", 6, 3)}))
                .kind,
            Kind::unchanged);
}

TEST(RunCompare, GrowthBelowTheUlpFloorIsNotFlagged) {
  EXPECT_FALSE(growth(0, 0.5).max_grew);
  EXPECT_FALSE(growth(0, 2).max_grew);  // 2 = 2 x max(0, 1)
  EXPECT_TRUE(growth(0, 2.5).max_grew);
  // Without a floor every growth from 0 counts.
  EXPECT_TRUE(growth(0, 0.5, 2, 0).max_grew);
}

TEST(RunCompare, FactorIsTheCallers) {
  EXPECT_FALSE(growth(2, 6, 4).max_grew);
  EXPECT_TRUE(growth(2, 9, 4).max_grew);
}

TEST(RunCompare, NaNIsNeverWithinTheFactor) {
  EXPECT_TRUE(growth(1, kNaN).max_grew);
  EXPECT_TRUE(growth(kNaN, kNaN).max_grew);
  EXPECT_TRUE(growth(1, kInf).max_grew);
  EXPECT_FALSE(growth(kNaN, 1).max_grew);     // better than before
  EXPECT_FALSE(growth(kInf, kInf).max_grew);  // as bad as before
  const CaseChange c = change(result("a", Status::pass, {stats("c.x", 1, 1)}),
                              result("a", Status::pass, {stats("c.x", 1, kNaN)}));
  EXPECT_EQ(c.kind, Kind::precision);
  EXPECT_TRUE(c.channels.at(0).p99_grew);
}

TEST(RunCompare, OnlyChannelsComparedInBothRunsCount) {
  const CaseChange c = change(
      result("a", Status::pass,
             {stats("depth", 1, 1, 0.01, 0), stats("color.x", 1, 1), stats("color.y", 1, 1)}),
      result("a", Status::pass, {stats("depth", 50, 50), stats("color.x", 1, 1)}));
  EXPECT_EQ(c.kind, Kind::unchanged);
  ASSERT_EQ(c.channels.size(), 1u);
  EXPECT_EQ(c.channels[0].channel, "color.x");
}

TEST(RunCompare, StatusChangesOutrankPrecision) {
  // The channels are still filled in, for the JSON, but the case is a regression.
  const CaseChange c = change(result("a", Status::pass, {stats("c.x", 1, 1)}),
                              result("a", Status::fail, {stats("c.x", 90, 90)}));
  EXPECT_EQ(c.kind, Kind::regression);
  ASSERT_EQ(c.channels.size(), 1u);
  EXPECT_TRUE(c.channels[0].max_grew);
  // A failure that got worse without changing its outcome is a precision change.
  EXPECT_EQ(change(result("a", Status::fail, {stats("c.x", 100, 1)}),
                   result("a", Status::fail, {stats("c.x", 300, 1)}))
                .kind,
            Kind::precision);
}

TEST(RunCompare, IdenticalRunsAreUnchangedAndSayNoChange) {
  CaseResult a = passing_case(), b = nan_case();
  a.outcome = Status::pass, b.outcome = Status::fail;
  const RunResults r = run({a, b});
  const RunComparison c = compare_runs(r, r);
  EXPECT_EQ(c.count(Kind::unchanged), 2u);
  EXPECT_FALSE(c.has_regression());
  const std::string text = comparison_text(c);
  EXPECT_NE(text.find("2 cases: 0 regressions, 0 fixes, 0 changed, 0 added, 0 removed, 0 skipped, "
                      "0 precision changes, 2 unchanged\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\nno change\n"), std::string::npos) << text;
  EXPECT_NE(comparison_markdown(c).find("No change."), std::string::npos);
}

TEST(RunCompare, TextNamesBothRunsCountsAndChanges) {
  RunResults base =
      run({result("a", Status::pass), result("b", Status::pass, {stats("t.x", 1.5, 1)}),
           result("c", Status::fail)},
          "llvmpipe (LLVM 15.0.6, 256 bits)");
  RunResults current =
      run({result("a", Status::fail, {}, std::string(150, 'm') + "\nsecond line"),
           result("b", Status::pass, {stats("t.x", 9, 4)}), result("c", Status::pass)},
          "softpipe");
  current.run.gl_version = "3.3 (Core Profile) Mesa 24.1.0";
  current.run.mesa_prefix = "/opt/mesa-main";
  const std::string text = comparison_text(compare_runs(base, current));
  EXPECT_NE(text.find("base:    llvmpipe (LLVM 15.0.6, 256 bits) | GL 4.5 (Compatibility Profile) "
                      "Mesa 22.3.6 | osmesa, llvmpipe"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("current: softpipe | GL 3.3 (Core Profile) Mesa 24.1.0 | osmesa, llvmpipe"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("| Mesa /opt/mesa-main\n"), std::string::npos) << text;
  // Nothing about a prefix for the run without one.
  EXPECT_NE(text.find(" | osmesa, llvmpipe\ncurrent: "), std::string::npos) << text;
  EXPECT_NE(text.find("3 cases: 1 regression, 1 fix, 0 changed, 0 added, 0 removed, 0 skipped, "
                      "1 precision change, 0 unchanged\n"),
            std::string::npos)
      << text;
  // The message's first line, cut to 100 characters.
  EXPECT_NE(text.find("\n1 regression:\n  Pass -> Fail  a     " + std::string(97, 'm') + "...\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\n1 fix:\n  Fail -> Pass  c\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n1 precision change:\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  b     t.x       max 1.5 -> 9 ulp (x6)"), std::string::npos) << text;
  EXPECT_NE(text.find("p99 1 -> 4 ulp (x4)"), std::string::npos) << text;
  EXPECT_NE(text.find("allowance used 0.01 -> 0.01\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("no change"), std::string::npos) << text;
}

TEST(RunCompare, MarkdownHasTablesWithEscapedCells) {
  const RunComparison c = compare_runs(
      run({result("a|b", Status::pass), result("p", Status::pass, {stats("c.x", 1, 1)})}),
      run({result("a|b", Status::fail, {}, "x | y"),
           result("p", Status::pass, {stats("c.x", 3, 1, 0.02)})}));
  const std::string md = comparison_markdown(c);
  EXPECT_EQ(md.rfind("## glrefcheck compare\n", 0), 0u) << md;
  EXPECT_NE(md.find("| GL_VERSION | 4.5 (Compatibility Profile) Mesa 22.3.6 | 4.5 (Compatibility "
                    "Profile) Mesa 22.3.6 |\n"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| driver | llvmpipe | llvmpipe |\n"), std::string::npos) << md;
  EXPECT_EQ(md.find("Mesa prefix"), std::string::npos) << md;
  EXPECT_NE(md.find("**2 cases: 1 regression,"), std::string::npos) << md;
  EXPECT_NE(md.find("### 1 regression\n\n| case | base | current | message |\n|---|---|---|---|\n"
                    "| a\\|b | Pass | Fail | x \\| y |\n"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| p | c.x | 1 -> 3 ulp (x3) | 1 -> 1 ulp (x1) | 0.01 -> 0.02 |\n"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("No change"), std::string::npos) << md;
}

TEST(RunCompare, JsonHasRunsSummaryAndCases) {
  RunResults base = run({result("a", Status::pass, {stats("c.x", 1, 1)}), result("b", Status::pass),
                         result("gone", Status::pass)});
  RunResults current = run({result("a", Status::pass, {stats("c.x", kNaN, kInf)}),
                            result("b", Status::crash, {}, "SIGSEGV"), result("new", Status::skip)},
                           "softpipe");
  current.run.mesa_prefix = "/opt/mesa";
  const auto j = nlohmann::json::parse(comparison_json(compare_runs(base, current, 3, 0.5)));

  EXPECT_EQ(j["base"]["gl_renderer"], "llvmpipe");
  EXPECT_EQ(j["current"]["gl_renderer"], "softpipe");
  EXPECT_EQ(j["current"]["gl_version"], "4.5 (Compatibility Profile) Mesa 22.3.6");
  EXPECT_EQ(j["current"]["gl_vendor"], "Mesa");
  EXPECT_EQ(j["current"]["mesa_prefix"], "/opt/mesa");
  EXPECT_EQ(j["current"]["backend"], "osmesa");
  EXPECT_EQ(j["current"]["driver"], "llvmpipe");
  EXPECT_TRUE(j["current"].contains("model"));
  EXPECT_TRUE(j["current"].contains("tolerance"));
  EXPECT_EQ(j["factor"], 3.0);
  EXPECT_EQ(j["min_ulps"], 0.5);
  EXPECT_EQ(j["summary"], (nlohmann::json{{"regression", 1},
                                          {"fix", 0},
                                          {"changed", 0},
                                          {"added", 1},
                                          {"removed", 1},
                                          {"skipped", 0},
                                          {"precision", 1},
                                          {"unchanged", 0}}));
  EXPECT_EQ(j["regressions"], true);

  const auto& cases = j["cases"];
  ASSERT_EQ(cases.size(), 4u);
  EXPECT_EQ(cases[0]["name"], "a");
  EXPECT_EQ(cases[0]["kind"], "precision");
  EXPECT_EQ(cases[0]["base"], "Pass");
  EXPECT_EQ(cases[0]["current"], "Pass");
  ASSERT_EQ(cases[0]["channels"].size(), 1u);
  const auto& ch = cases[0]["channels"][0];
  EXPECT_EQ(ch["channel"], "c.x");
  EXPECT_EQ(ch["base_max_ulps"], 1.0);
  EXPECT_EQ(ch["current_max_ulps"], "nan");
  EXPECT_EQ(ch["base_p99_ulps"], 1.0);
  EXPECT_EQ(ch["current_p99_ulps"], "inf");
  EXPECT_EQ(ch["base_max_ratio"], 0.01);
  EXPECT_EQ(ch["current_max_ratio"], 0.01);
  EXPECT_EQ(ch["max_grew"], true);
  EXPECT_EQ(ch["p99_grew"], true);
  EXPECT_EQ(cases[1]["kind"], "regression");
  EXPECT_EQ(cases[1]["current"], "Crash");
  EXPECT_EQ(cases[1]["message"], "SIGSEGV");
  EXPECT_EQ(cases[2]["name"], "new");
  EXPECT_EQ(cases[2]["kind"], "added");
  EXPECT_TRUE(cases[2]["base"].is_null());
  EXPECT_EQ(cases[2]["current"], "Skip");
  EXPECT_EQ(cases[3]["name"], "gone");
  EXPECT_EQ(cases[3]["kind"], "removed");
  EXPECT_TRUE(cases[3]["current"].is_null());
}

TEST(RunCompare, KindNames) {
  EXPECT_STREQ(to_string(Kind::regression), "regression");
  EXPECT_STREQ(to_string(Kind::precision), "precision");
  EXPECT_STREQ(to_string(Kind::unchanged), "unchanged");
}

// The same through results.json files, as `glrefcheck compare` reads them.
using RunCompareFiles = ReportTest;

TEST_F(RunCompareFiles, ComparesRunsReadBackFromResultsJson) {
  CaseResult a = passing_case(), b = nan_case();
  a.outcome = Status::pass, b.outcome = Status::fail;
  b.status = Status::expected_fail;
  write_results_json(dir_ / "base" / "results.json", run_info(), {a, b});
  CaseResult worse = a;
  worse.channels.at(1).max_ulps = 31;  // color.x: 3.1 -> 31
  CaseResult fixed = b;
  fixed.outcome = fixed.status = Status::pass;
  write_results_json(dir_ / "current" / "results.json", run_info(), {worse, fixed});

  const RunComparison c =
      compare_runs(read_results_json(dir_ / "base"), read_results_json(dir_ / "current"));
  ASSERT_EQ(c.cases.size(), 2u);
  EXPECT_EQ(c.cases[0].kind, Kind::precision);
  EXPECT_EQ(c.cases[0].channels.at(1).channel, "color.x");
  EXPECT_TRUE(c.cases[0].channels.at(1).max_grew);
  EXPECT_EQ(c.cases[1].kind, Kind::fix);
  EXPECT_EQ(c.cases[1].base, Status::fail);
  EXPECT_EQ(c.base.gl_renderer, "llvmpipe (LLVM 15.0.6, 256 bits)");
  EXPECT_EQ(c.base.model_source, "identify (cached)");

  // results.json written before model_source existed still reads, with none.
  auto old = nlohmann::json::parse(read_text(dir_ / "base" / "results.json"));
  old["run"].erase("model_source");
  old.erase("written_by");  // nor a stamp
  std::ofstream(dir_ / "base" / "results.json") << old.dump();
  EXPECT_EQ(read_results_json(dir_ / "base").run.model_source, "");
}

// Frame digests tell bit-identical frames from frames whose statistics merely agree.
TEST(RunCompare, FrameDigestsSayWhetherTheBitsChanged) {
  auto with_digest = [](const std::string& name, const std::string& digest) {
    CaseResult r = result(name, Status::pass, {stats("color.x", 2, 1)});
    r.gl_digest = digest;
    return r;
  };
  const RunComparison c = compare_runs(
      run({with_digest("same", "aa"), with_digest("other", "bb"), with_digest("unknown", "")}),
      run({with_digest("same", "aa"), with_digest("other", "cc"), with_digest("unknown", "dd")}));
  ASSERT_EQ(c.cases.size(), 3u);
  EXPECT_EQ(c.cases[0].same_bits, std::optional<bool>(true));
  EXPECT_EQ(c.cases[1].same_bits, std::optional<bool>(false));
  EXPECT_EQ(c.cases[2].same_bits, std::nullopt);
  EXPECT_EQ(c.bits_compared(), 2u);
  EXPECT_EQ(c.bits_identical(), 1u);
  // Same statistics, other bits: still no finding by the factor, but named in the text.
  EXPECT_EQ(c.cases[1].kind, Kind::unchanged);
  const std::string text = comparison_text(c);
  EXPECT_NE(text.find("GL frames: 1 of 2 bit-identical to base, 1 with other bits"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("frames with other bits"), std::string::npos) << text;
  EXPECT_NE(text.find("  other "), std::string::npos) << text;
  const auto j = nlohmann::json::parse(comparison_json(c));
  EXPECT_EQ(j["bits_identical"], 1);
  EXPECT_EQ(j["cases"][1]["same_bits"], false);
  EXPECT_TRUE(j["cases"][2]["same_bits"].is_null());
}

}  // namespace
}  // namespace glrc::report::test
