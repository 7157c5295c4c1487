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

#include <nlohmann/json.hpp>

#include "report/json_types.hpp"
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
  // -inf where a value may be negative (a reference value): a statistic may not be.
  ch.p99_ulps = 7.5, ch.max_ratio = std::numeric_limits<double>::infinity();
  ch.p99_ratio = 0.9, ch.tolerance_ulps = 64;
  ch.worst = {{3, 4, -HUGE_VALF, std::nanf(""), HUGE_VAL, HUGE_VAL, 1e-7, HUGE_VAL},
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
  EXPECT_TRUE(std::isinf(c.max_ratio) && c.max_ratio > 0);
  EXPECT_TRUE(std::isinf(c.worst[0].reference) && c.worst[0].reference < 0);
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

// nlohmann's ADL conversions, for every type: to JSON, back with get<T>(), and to JSON again
// gives the same text (NaN and the infinities as "nan", "inf", "-inf").
template <class T>
void expect_json_round_trip(const T& value) {
  const nlohmann::json j = value;
  const T back = j.get<T>();
  EXPECT_EQ(nlohmann::json(back).dump(), j.dump());
}

TEST(RoundTrip, EveryTypeThroughToJsonAndFromJson) {
  const CaseResult r = every_field_set();
  expect_json_round_trip(r);
  expect_json_round_trip(r.tolerance);
  expect_json_round_trip(r.coverage);
  expect_json_round_trip(r.coverage.mismatches[0]);
  expect_json_round_trip(r.channels[0]);
  expect_json_round_trip(r.channels[0].worst[0]);
  expect_json_round_trip(every_run_field_set());
  // The values JSON makes hard, by value.
  const CaseResult back = nlohmann::json(r).get<CaseResult>();
  EXPECT_TRUE(std::isnan(back.channels[0].max_ulps));
  EXPECT_TRUE(std::isinf(back.channels[0].max_abs) && back.channels[0].max_abs > 0);
  EXPECT_TRUE(std::isinf(back.channels[0].max_ratio) && back.channels[0].max_ratio > 0);
  EXPECT_TRUE(std::isinf(back.channels[0].worst[0].reference) &&
              back.channels[0].worst[0].reference < 0);
  EXPECT_TRUE(std::isnan(back.channels[0].worst[0].gl));
  EXPECT_EQ(back.channels[0].worst[1].gl, 0.33333334f);
  EXPECT_EQ(back.coverage.both, 4000000000ull);
  const nlohmann::json written = r;
  EXPECT_EQ(written["channels"][0]["max_ulps"], "nan");
  EXPECT_EQ(written["channels"][0]["max_abs"], "inf");
  EXPECT_EQ(written["channels"][0]["worst"][0]["reference"], "-inf");
}

// What results.json gained over time reads back as an old run meant it.
TEST(RoundTrip, FieldsAddedLaterHaveTheirDefaults) {
  nlohmann::json run = every_run_field_set();
  for (const char* key : {"model_source", "mesa_prefix", "gl_library", "gl_warnings",
                          "gl_primitive_id_from_geometry_shader", "jobs", "fraction",
                          "fraction_start", "total_cases", "interrupted", "gl_subpixel_bits"})
    run.erase(key);
  const RunInfo i = run.get<RunInfo>();
  EXPECT_EQ(i.model_source, "");
  EXPECT_TRUE(i.gl_warnings.empty());
  EXPECT_FALSE(i.gl_primitive_id_from_geometry_shader);
  EXPECT_FALSE(i.interrupted);
  EXPECT_EQ(i.jobs, 1);
  EXPECT_EQ(i.fraction, 1);
  EXPECT_EQ(i.fraction_start, 1);
  EXPECT_EQ(i.total_cases, 0u);
  EXPECT_EQ(i.subpixel_bits, 0);
  nlohmann::json c = every_field_set();
  c.erase("outcome");
  c.erase("gl_digest");
  c["tolerance"].erase("subpixel_bits");
  const CaseResult r = c.get<CaseResult>();
  EXPECT_EQ(r.outcome, Status::fail);  // from ExpectedFail
  EXPECT_EQ(r.gl_digest, "");
  EXPECT_EQ(r.tolerance.subpixel_bits, 4);
}

// A bad field is one line with its path: from read() with the source, from from_json without.
TEST(RoundTrip, ABadFieldNamesItsSourceAndPath) {
  nlohmann::json c = every_field_set();
  c["coverage"]["mismatches"][1]["label"] = "edge";
  CaseResult r;
  try {
    read(typed_json::Reader("shard/results.json", typed_json::Wording::brief), c, "cases[7]", r);
    ADD_FAILURE() << "no error";
  } catch (const typed_json::Error& e) {
    EXPECT_STREQ(e.what(),
                 "shard/results.json: cases[7].coverage.mismatches[1].label: expected exact_tie, "
                 "within_snapping, fill_rule, gap or double_hit");
  }
  nlohmann::json run = every_run_field_set();
  run["fraction_start"] = 9;
  try {
    run.get<RunInfo>();
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "fraction_start: expected an integer from 1 to 4, got 9");
  }
}

}  // namespace
}  // namespace glrc::report
