// results.json: the fields a script reads, counts per status, and non-finite numbers written as
// strings so that the file stays valid JSON.
#include <nlohmann/json.hpp>

#include "report/report.hpp"
#include "tests/report/test_helpers.hpp"

namespace glrc::report::test {
namespace {

using nlohmann::json;

json written(const std::filesystem::path& file) {
  return json::parse(read_text(file));
}

TEST_F(ReportTest, ResultsJsonHoldsRunSummaryAndCases) {
  const auto file = dir_ / "nested" / "out" / "results.json";  // parents are created
  write_results_json(file, run_info(),
                     {passing_case(), nan_case(), with_status(Status::skip, "skipped", "no GL"),
                      with_status(Status::expected_fail, "known", "snapping differs")});
  const json doc = written(file);

  EXPECT_EQ(doc["run"]["backend"], "osmesa");
  EXPECT_EQ(doc["run"]["driver"], "llvmpipe");
  EXPECT_EQ(doc["run"]["gl_renderer"], "llvmpipe (LLVM 15.0.6, 256 bits)");
  EXPECT_EQ(doc["run"]["seconds"], 1.75);
  EXPECT_EQ(doc["run"]["model"], "subpixel_bits=8 planes=snapped tie=top_left");
  EXPECT_EQ(doc["run"]["model_source"], "identify (cached)");

  const json& summary = doc["summary"];
  EXPECT_EQ(summary["total"], 4);
  EXPECT_EQ(summary["pass"], 1);
  EXPECT_EQ(summary["fail"], 1);
  EXPECT_EQ(summary["skip"], 1);
  EXPECT_EQ(summary["expected_fail"], 1);
  EXPECT_EQ(summary["unexpected_pass"], 0);
  EXPECT_EQ(summary["error"], 0);

  ASSERT_EQ(doc["cases"].size(), 4u);
  const json& pass = doc["cases"][0];
  EXPECT_EQ(pass["name"], "face_on");
  EXPECT_EQ(pass["description"], "a triangle facing the viewer");
  EXPECT_EQ(pass["status"], "Pass");
  EXPECT_EQ(pass["seconds"], 0.012);
  EXPECT_EQ(pass["tolerance"]["varying_ulps"], 64.0);
  EXPECT_EQ(pass["tolerance"]["depth_ulps"], 16.0);
  EXPECT_EQ(pass["tolerance"]["allow_boundary"], true);
  EXPECT_EQ(pass["coverage"]["both"], 900);
  EXPECT_EQ(pass["coverage"]["reference_only"], 2);
  EXPECT_EQ(pass["coverage"]["boundary"], 2);
  ASSERT_EQ(pass["coverage"]["mismatches"].size(), 2u);
  EXPECT_EQ(pass["coverage"]["mismatches"][1]["x"], 11);
  EXPECT_EQ(pass["coverage"]["mismatches"][1]["gl"], -1);
  EXPECT_EQ(pass["coverage"]["mismatches"][1]["boundary"], true);

  ASSERT_EQ(pass["channels"].size(), 2u);
  const json& color = pass["channels"][1];
  EXPECT_EQ(color["name"], "color.x");
  EXPECT_EQ(color["max_ulps"], 3.1);
  EXPECT_EQ(color["tolerance_ulps"], 64.0);
  EXPECT_EQ(color["pass"], true);
  // Floats come back bit for bit.
  EXPECT_EQ(color["worst"][0]["reference"].get<float>(), 0.1f);
  EXPECT_EQ(color["worst"][0]["gl"].get<float>(), 0.100000024f);
  EXPECT_EQ(color["worst"][0]["x"], 5);

  EXPECT_EQ(doc["cases"][2]["status"], "Skip");
  EXPECT_EQ(doc["cases"][2]["message"], "no GL");
  EXPECT_EQ(doc["cases"][3]["status"], "ExpectedFail");
}

TEST_F(ReportTest, ResultsJsonKeepsGlWarnings) {
  RunInfo run = run_info();
  write_results_json(dir_ / "none" / "results.json", run, {passing_case()});
  EXPECT_EQ(written(dir_ / "none" / "results.json")["run"]["gl_warnings"], json::array());
  EXPECT_TRUE(read_results_json(dir_ / "none").run.gl_warnings.empty());

  run.gl_warnings = {"'llvmpipe' on OSMesa: the first draw (...) is wrong: pixel (0, 0) ..."};
  write_results_json(dir_ / "warned" / "results.json", run, {passing_case()});
  EXPECT_EQ(written(dir_ / "warned" / "results.json")["run"]["gl_warnings"][0], run.gl_warnings[0]);
  EXPECT_EQ(read_results_json(dir_ / "warned").run.gl_warnings, run.gl_warnings);

  // Optional (earlier runs have none), but when present a list of strings.
  json doc = written(dir_ / "warned" / "results.json");
  doc.erase("written_by");  // results before stamps: read as they stand
  doc["run"]["gl_warnings"] = "one string";
  std::ofstream(dir_ / "warned" / "results.json") << doc.dump();
  try {
    read_results_json(dir_ / "warned");
    FAIL() << "a string accepted for gl_warnings";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("run.gl_warnings"), std::string::npos) << e.what();
  }
  doc["run"].erase("gl_warnings");
  std::ofstream(dir_ / "warned" / "results.json") << doc.dump();
  EXPECT_TRUE(read_results_json(dir_ / "warned").run.gl_warnings.empty());
}

TEST_F(ReportTest, ResultsJsonWritesNonFiniteNumbersAsStrings) {
  const auto file = dir_ / "results.json";
  write_results_json(file, run_info(), {nan_case()});
  const json doc = written(file);  // parses: no bare NaN/Infinity in the text

  const json& bad = doc["cases"][0]["channels"][1];
  EXPECT_EQ(bad["name"], "color.y");
  EXPECT_EQ(bad["non_finite"], 1);
  EXPECT_EQ(bad["pass"], false);
  EXPECT_EQ(bad["max_ulps"], "inf");
  EXPECT_EQ(bad["mean_ulps"], "nan");
  EXPECT_EQ(bad["worst"][0]["gl"], "nan");
  EXPECT_EQ(bad["worst"][0]["reference"], 0.5);
  EXPECT_EQ(bad["worst"][0]["ulps"], "inf");
  EXPECT_EQ(doc["cases"][0]["status"], "Fail");
  EXPECT_EQ(read_text(file).find("null"), std::string::npos);
}

TEST_F(ReportTest, ResultsJsonOfNoCasesIsAnEmptyList) {
  const auto file = dir_ / "results.json";
  write_results_json(file, run_info(), {});
  const json doc = written(file);
  EXPECT_EQ(doc["summary"]["total"], 0);
  EXPECT_TRUE(doc["cases"].is_array());
  EXPECT_TRUE(doc["cases"].empty());
}

// Issue 45: a results.json whose verdict a person flipped, or whose case they renamed, was
// merged and compared as a run's. Stamped when written, it is refused once edited; one without
// a stamp (an older glrefcheck's) reads as it stands, and says so.
TEST_F(ReportTest, ResultsJsonEditedSinceWrittenIsRefused) {
  const auto file = dir_ / "stamped" / "results.json";
  write_results_json(file, run_info(), {passing_case()});
  const std::string text = read_text(file);
  ASSERT_TRUE(text.starts_with("{\n  \"written_by\": \"glrefcheck run glrefcheck-sha256:"))
      << text.substr(0, 120);
  EXPECT_EQ(read_results_json(file).stamp, JsonStamp::intact);
  for (const auto& [from, to] : {std::pair{"\"status\": \"Pass\"", "\"status\": \"Fail\""},
                                 {"\"name\": \"", "\"name\": \"x"},
                                 {"\"total_cases\": 0", "\"total_cases\": 1"}}) {
    SCOPED_TRACE(from);
    std::string edited = text;
    const size_t at = edited.find(from);
    ASSERT_NE(at, std::string::npos);
    edited.replace(at, std::string(from).size(), to);
    std::ofstream(file, std::ios::binary) << edited;
    try {
      read_results_json(file);
      FAIL() << "an edited results.json was read";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("written_by: expected the stamp glrefcheck wrote"),
                std::string::npos)
          << e.what();
    }
  }
  json doc = json::parse(text);
  doc.erase("written_by");
  std::ofstream(file, std::ios::binary) << doc.dump(2);
  EXPECT_EQ(read_results_json(file).stamp, JsonStamp::none);
}

}  // namespace
}  // namespace glrc::report::test
