// The terminal tables: what a person reads after `run` and `diff`.
#include "report/report.hpp"
#include "tests/report/test_helpers.hpp"

namespace glrc::report::test {
namespace {

TEST(CaseLine, ShowsStatusNameMaxUlpsCoverageAndTime) {
  const std::string line = case_line(passing_case());
  EXPECT_EQ(line.rfind("Pass ", 0), 0u) << line;
  EXPECT_NE(line.find(" face_on "), std::string::npos) << line;
  EXPECT_NE(line.find("max   3.1 ulp"), std::string::npos) << line;
  EXPECT_NE(line.find("coverage 0 bad, 2 at edges"), std::string::npos) << line;
  EXPECT_NE(line.find("0.012 s"), std::string::npos) << line;
  EXPECT_EQ(line.find('\n'), std::string::npos);
}

TEST(CaseLine, LinesUpAcrossStatuses) {
  // Names start in the same column whatever the status.
  const std::string a = case_line(passing_case());
  const std::string b = case_line(with_status(Status::unexpected_pass, "fixed", ""));
  EXPECT_EQ(a.find("face_on"), b.find("fixed"));
}

TEST(CaseLine, NonFiniteChannelShowsNaNAndTheMessage) {
  const std::string line = case_line(nan_case());
  EXPECT_EQ(line.rfind("Fail ", 0), 0u) << line;
  EXPECT_NE(line.find("max   NaN ulp"), std::string::npos) << line;
  EXPECT_NE(line.find("color.y: 1 non-finite value"), std::string::npos) << line;
}

TEST(CaseLine, LongMessagesAreCut) {
  const std::string line = case_line(with_status(Status::error, "broken", std::string(200, 'x')));
  EXPECT_EQ(line.rfind("Error ", 0), 0u) << line;
  EXPECT_NE(line.find(std::string(97, 'x') + "..."), std::string::npos) << line;
  EXPECT_EQ(line.find(std::string(98, 'x')), std::string::npos) << line;
}

TEST(StatsTable, HasOneRowPerChannelWithVerdictAndCoverage) {
  const std::string table = stats_table(nan_case());
  EXPECT_NE(table.find("channel"), std::string::npos);
  // The spec tolerance varies per pixel: its largest value and the share used are shown.
  EXPECT_NE(table.find("allow<=ulp"), std::string::npos) << table;
  EXPECT_NE(table.find("max/allow"), std::string::npos) << table;
  const auto row_of = [&](const std::string& name) {
    const size_t at = table.find("\n" + name + " ");
    EXPECT_NE(at, std::string::npos) << table;
    return table.substr(at + 1, table.find('\n', at + 1) - at - 1);
  };
  EXPECT_NE(row_of("depth").find(" ok"), std::string::npos) << table;
  const std::string bad = row_of("color.y");
  EXPECT_NE(bad.find("FAIL (1 non-finite)"), std::string::npos) << table;
  EXPECT_NE(bad.find(" inf "), std::string::npos) << table;
  EXPECT_NE(table.find("coverage: both 0, reference only 0"), std::string::npos) << table;
}

TEST(WorstPixelsTable, NonFiniteFirstThenLargestOverAllChannels) {
  CaseResult r;
  r.channels = {
      channel("depth", 50, 16, {{1, 1, 0.5f, 0.5f, 1e-6, 50}, {2, 2, 0.5f, 0.5f, 1e-7, 3}}),
      channel("color.x", 100, 64, {{3, 3, 1.0f, 1.5f, 0.5, 100}, {4, 4, 1.0f, kNaNf, kInf, kInf}})};
  const std::string table = worst_pixels_table(r, 3);
  const size_t nan_row = table.find("\n    4     4  color.x");
  const size_t hundred = table.find("\n    3     3  color.x");
  const size_t fifty = table.find("\n    1     1  depth");
  ASSERT_NE(nan_row, std::string::npos) << table;
  ASSERT_NE(hundred, std::string::npos) << table;
  ASSERT_NE(fifty, std::string::npos) << table;
  EXPECT_LT(nan_row, hundred);
  EXPECT_LT(hundred, fifty);
  // n = 3: the 3-ulp pixel is cut.
  EXPECT_EQ(table.find("\n    2     2"), std::string::npos) << table;
  EXPECT_NE(table.find("nan"), std::string::npos);
}

TEST(WorstPixelsTable, PrintsFloatsExactly) {
  CaseResult r;
  r.channels = {channel("color.x", 1, 64, {{0, 0, 0.1f, 0.100000024f, 2.2e-8, 1}})};
  const std::string table = worst_pixels_table(r, 10);
  EXPECT_NE(table.find("0.100000001"), std::string::npos) << table;  // 0.1f
  EXPECT_NE(table.find("0.100000024"), std::string::npos) << table;
}

TEST(WorstPixelsTable, EmptyWhenNoPixelWasCompared) {
  CaseResult r;
  r.channels = {channel("depth", 0, 16), channel("color.x", 0, 64)};
  EXPECT_EQ(worst_pixels_table(r, 10), "");
}

// A coverage-only failure: GL left out one pixel of a mesh (a gap on a shared edge) and
// covered one the reference does not (fill rule); a third mismatch is an allowed tie.
CaseResult coverage_case() {
  CaseResult r;
  r.name = "fan";
  r.status = Status::fail;
  r.coverage.failures = 2;
  r.coverage.boundary = 1;
  using Label = CoverageStats::Label;
  r.coverage.mismatches = {{1, 0, 0, Frame::kNoPrimitive, false, Label::gap},
                           {2, 1, 1, Frame::kNoPrimitive, true, Label::exact_tie},
                           {3, 2, Frame::kNoPrimitive, 1, false, Label::fill_rule}};
  r.channels = {channel("depth", 0, 16)};
  return r;
}

TEST(CoverageFailuresTable, ListsFailingPixelsWithPrimitivesFragmentsAndLabel) {
  Frame reference(4, 3, 0), gl(4, 3, 0);
  reference.fragments.assign(12, 1);
  gl.fragments.assign(12, 1);
  gl.fragments[gl.index(1, 0)] = 0;
  gl.fragments[gl.index(3, 2)] = 1;
  reference.fragments[reference.index(3, 2)] = 0;
  const std::string table = coverage_failures_table(coverage_case(), reference, gl, 20);
  EXPECT_EQ(table,
            "    x     y   ref prim    GL prim  ref frags   GL frags  coverage\n"
            "    1     0          0          -          1          0  gap on a shared edge\n"
            "    3     2          -          1          0          1  fill-rule error\n")
      << table;
}

TEST(CoverageFailuresTable, AllowedTiesAreListedOnlyWhereTheyFail) {
  CaseResult r = coverage_case();
  r.tolerance.allow_boundary = false;  // --strict-coverage
  r.coverage.failures = 3;
  const std::string table = coverage_failures_table(r, Frame(), Frame(), 20);
  EXPECT_NE(table.find("\n    2     1          1          -          -          -  exact tie\n"),
            std::string::npos)
      << table;
}

TEST(CoverageFailuresTable, SaysHowManyMoreFailAndIsEmptyWithoutFailures) {
  CaseResult r = coverage_case();
  r.coverage.failures = 40;  // compare keeps only the first mismatches
  const std::string table = coverage_failures_table(r, Frame(), Frame(), 1);
  EXPECT_EQ(table.find("fill-rule error"), std::string::npos) << table;  // n = 1
  EXPECT_NE(table.find("\n39 more failing pixels (coverage.png rings every failing pixel)\n"),
            std::string::npos)
      << table;
  r.coverage.failures = 2;
  EXPECT_NE(coverage_failures_table(r, Frame(), Frame(), 1).find("\n1 more failing pixel ("),
            std::string::npos);
  EXPECT_EQ(coverage_failures_table(passing_case(), Frame(), Frame(), 20), "");
}

}  // namespace
}  // namespace glrc::report::test
