// Every serialized type read back is what was written: each field is set to a value other than
// its default (so a field the reader dropped would come back different), written, read and
// written again; the two texts must be equal, and the fields that JSON makes hard (NaN,
// infinities, floats widened to double, large counts, non-ASCII text) are checked by value.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>

#include "report/report.hpp"

namespace glrc::report {
namespace {

CaseResult every_field_set() {
  CaseResult r;
  r.name = "clip_near";
  r.description = "near plane, ünïcode and a \"quote\"";
  r.status = Status::expected_fail;
  r.outcome = Status::fail;
  r.message = "color.x: 3 pixels over the allowance";
  r.tolerance = {ToleranceMode::ulps, 6, 12.5, 3.25, false};
  CoverageStats& c = r.coverage;
  c.both = 4000000000ull, c.neither = 2, c.reference_only = 3, c.gl_only = 4;
  c.other_primitive = 5, c.exact_tie = 6, c.within_snapping = 7, c.fill_rule = 8;
  c.boundary = 13, c.gaps = 9, c.double_hits = 10, c.fragments_checked = true, c.failures = 11;
  c.mismatches = {{1, 2, 3, -1, true, CoverageStats::Label::within_snapping},
                  {7, 8, -1, 4, false, CoverageStats::Label::double_hit}};
  ChannelStats ch;
  ch.name = "color.x";
  ch.compared = 100, ch.over_tolerance = 3, ch.non_finite = 1, ch.differing = 40;
  ch.max_abs = std::numeric_limits<double>::infinity();
  ch.max_ulps = std::nan(""), ch.mean_ulps = 1.0 / 3, ch.rms_ulps = 0.1;
  ch.p99_ulps = 7.5, ch.max_ratio = -std::numeric_limits<double>::infinity();
  ch.p99_ratio = 0.9, ch.tolerance_ulps = 64;
  ch.worst = {{3, 4, 0.1f, std::nanf(""), HUGE_VAL, HUGE_VAL, 1e-7, HUGE_VAL},
              {5, 6, 1.0f / 3, 0.33333334f, 1e-8, 0.5, 2e-8, 0.5}};
  r.channels = {ch, ch};
  r.channels[1].name = "depth";
  r.gl_digest = std::string(64, 'a');
  r.seconds = 0.125;
  return r;
}

RunInfo every_run_field_set() {
  RunInfo i;
  i.backend = "egl", i.driver = "softpipe";
  i.model = "subpixel_bits=8 planes=unsnapped tie=bottom-right";
  i.model_source = "identify (cached)";
  i.tolerance = "spec (subpixel bits 8)";
  i.subpixel_bits = 8;
  i.gl_vendor = "Mesa", i.gl_renderer = "softpipe", i.gl_version = "4.5 (Core Profile) Mesa";
  i.mesa_prefix = ".mesa/23.2.1", i.gl_library = "libEGL_mesa.so.0";
  i.gl_warnings = {"first draw: pixel (1, 2) expected 3, got 4", "second"};
  i.gl_primitive_id_from_geometry_shader = true;
  i.jobs = 3, i.fraction = 4, i.fraction_start = 2, i.total_cases = 61;
  i.seconds = 12.75;
  i.interrupted = true;
  return i;
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
}

TEST(RoundTrip, CaseResult) {
  const CaseResult r = every_field_set();
  const std::string text = case_result_json(r);
  const CaseResult back = case_result_from_json(text, "test");
  EXPECT_EQ(case_result_json(back), text);
  EXPECT_EQ(back.description, r.description);
  EXPECT_EQ(back.status, Status::expected_fail);
  EXPECT_EQ(back.outcome, Status::fail);
  EXPECT_EQ(back.coverage.both, 4000000000ull);
  ASSERT_EQ(back.coverage.mismatches.size(), 2u);
  EXPECT_EQ(back.coverage.mismatches[1].label, CoverageStats::Label::double_hit);
  EXPECT_EQ(back.coverage.mismatches[0].gl, -1);
  ASSERT_EQ(back.channels.size(), 2u);
  const ChannelStats& c = back.channels[0];
  EXPECT_TRUE(std::isinf(c.max_abs) && c.max_abs > 0);
  EXPECT_TRUE(std::isnan(c.max_ulps));
  EXPECT_TRUE(std::isinf(c.max_ratio) && c.max_ratio < 0);
  EXPECT_TRUE(same_bits(c.mean_ulps, 1.0 / 3));
  ASSERT_EQ(c.worst.size(), 2u);
  EXPECT_TRUE(std::isnan(c.worst[0].gl));
  EXPECT_EQ(c.worst[1].reference, 1.0f / 3);  // a float read back bit for bit
  EXPECT_EQ(back.tolerance.mode, ToleranceMode::ulps);
  EXPECT_FALSE(back.tolerance.allow_boundary);
  EXPECT_EQ(back.gl_digest, r.gl_digest);
}

TEST(RoundTrip, RunInfo) {
  const RunInfo i = every_run_field_set();
  const std::string text = run_info_json(i);
  const RunInfo back = run_info_from_json(text, "test");
  EXPECT_EQ(run_info_json(back), text);
  EXPECT_TRUE(back.gl_primitive_id_from_geometry_shader);
  EXPECT_TRUE(back.interrupted);
  EXPECT_EQ(back.gl_warnings, i.gl_warnings);
  EXPECT_EQ(back.fraction_start, 2);
  EXPECT_EQ(back.total_cases, 61u);
}

TEST(RoundTrip, ResultsJson) {
  const auto dir =
      std::filesystem::temp_directory_path() /
      ("glrc_round_trip_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  const RunInfo i = every_run_field_set();
  std::vector<CaseResult> cases = {every_field_set(), every_field_set()};
  cases[1].name = "other";
  write_results_json(dir / "results.json", i, cases);
  const RunResults back = read_results_json(dir);
  EXPECT_EQ(run_info_json(back.run), run_info_json(i));
  ASSERT_EQ(back.cases.size(), 2u);
  for (size_t k = 0; k < cases.size(); ++k)
    EXPECT_EQ(case_result_json(back.cases[k]), case_result_json(cases[k]));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace glrc::report
