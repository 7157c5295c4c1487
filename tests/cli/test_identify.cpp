// glrefcheck identify on Mesa's software drivers: the model it finds for each, from the summary
// line tools parse, and the same findings in identify.json.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "identify/known_models.hpp"
#include "tests/support/glrefcheck_process.hpp"

namespace {

namespace fs = std::filesystem;

using glrc::test::glrefcheck;
using glrc::test::Outcome;

struct Identified {
  Outcome outcome;
  std::map<std::string, std::string> summary;  // key=value pairs of the "identify:" line
  nlohmann::json json;
};

Identified identify(const std::string& args) {
  const fs::path out =
      fs::temp_directory_path() / ("glrc_identify_" + std::to_string(getpid()) + "_" +
                                   std::to_string(std::hash<std::string>{}(args)));
  fs::remove_all(out);
  Identified r;
  r.outcome = glrefcheck("identify " + args + " --out '" + out.string() + "'");
  std::istringstream lines(r.outcome.out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("identify: ", 0) != 0) continue;
    std::istringstream words(line.substr(10));
    for (std::string word; words >> word;)
      if (const size_t eq = word.find('='); eq != std::string::npos)
        r.summary[word.substr(0, eq)] = word.substr(eq + 1);
  }
  std::ifstream file(out / "identify.json");
  if (file) r.json = nlohmann::json::parse(file);
  fs::remove_all(out);
  return r;
}

TEST(Identify, LlvmpipeOsmesa) {
  const Identified r = identify("--backend osmesa --driver llvmpipe");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.err;
  EXPECT_EQ(r.summary.size(), 5u) << r.outcome.out;
  EXPECT_EQ(r.summary.at("subpixel_bits"), "8") << r.outcome.out;
  EXPECT_EQ(r.summary.at("planes"), "unsnapped") << r.outcome.out;
  EXPECT_EQ(r.summary.at("tie"), "bottom-left") << r.outcome.out;  // a user FBO: y up
  EXPECT_EQ(r.summary.at("provoking_default"), "last") << r.outcome.out;
  EXPECT_EQ(r.summary.at("depth24"), "round") << r.outcome.out;
  // The evidence: 8 bits explains every probe pixel, reported as 8; the ties all fit.
  ASSERT_TRUE(r.json.is_object()) << "no identify.json";
  EXPECT_EQ(r.json["subpixel_bits"]["reported"], 8);
  EXPECT_EQ(r.json["subpixel_bits"]["agrees_with_reported"], true);
  EXPECT_EQ(r.json["subpixel_bits"]["candidates"].size(), 14u);  // none, 4..16
  for (const auto& c : r.json["subpixel_bits"]["candidates"]) {
    if (c["bits"] == 8) {
      EXPECT_EQ(c["mismatches"], 0);
    } else {
      EXPECT_GT(c["mismatches"].get<int>(), 0) << c;
    }
  }
  EXPECT_EQ(r.json["tie_break"]["explains_all"], true);
  EXPECT_EQ(r.json["summary"],
            "identify: subpixel_bits=8 planes=unsnapped tie=bottom-left "
            "provoking_default=last depth24=round");
  // Snapped planes are far off on llvmpipe, unsnapped ones within a few ULPs.
  const auto& planes = r.json["planes"]["candidates"];
  EXPECT_LT(planes[0]["max_ulps"].get<double>(), 64);
  EXPECT_GT(planes[1]["max_ulps"].get<double>(), 1000);
  EXPECT_NE(r.outcome.out.find("GL_SUBPIXEL_BITS reports 8: agrees"), std::string::npos);
}

TEST(Identify, SoftpipeOsmesa) {
  const Identified r = identify("--backend osmesa --driver softpipe");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.err;
  EXPECT_EQ(r.summary.at("subpixel_bits"), "0") << r.outcome.out;  // no snapping
  EXPECT_EQ(r.summary.at("planes"), "unsnapped") << r.outcome.out;
  // Left edges excluded, right edges and bottom edges included.
  EXPECT_EQ(r.summary.at("tie"), "bottom-right") << r.outcome.out;
  EXPECT_EQ(r.summary.at("provoking_default"), "last") << r.outcome.out;
  EXPECT_EQ(r.summary.at("depth24"), "truncate") << r.outcome.out;
  // softpipe reports 4 subpixel bits but does not snap: said in so many words.
  ASSERT_TRUE(r.json.is_object()) << "no identify.json";
  EXPECT_EQ(r.json["subpixel_bits"]["reported"], 4);
  EXPECT_EQ(r.json["subpixel_bits"]["agrees_with_reported"], false);
  EXPECT_EQ(r.json["planes"]["distinguishable"], false);
  EXPECT_NE(r.outcome.out.find("the report and the behaviour disagree"), std::string::npos)
      << r.outcome.out;
  const auto& depth = r.json["depth24"]["probes"][0];  // constant depth: no plane error
  EXPECT_EQ(depth["truncate"], depth["informative"]);
  EXPECT_EQ(depth["round"], 0);
}

TEST(Identify, EglAgreesWithOsmesa) {
  for (const std::string driver : {"llvmpipe", "softpipe"}) {
    const Identified osmesa = identify("--backend osmesa --driver " + driver);
    const Identified egl = identify("--backend egl --driver " + driver);
    ASSERT_EQ(egl.outcome.exit_code, 0) << egl.outcome.err;
    EXPECT_EQ(egl.summary, osmesa.summary) << driver << "\n" << egl.outcome.out;
    ASSERT_TRUE(egl.json.is_object());
    // The evidence too, count for count.
    for (const char* key : {"subpixel_bits", "planes", "tie_break", "depth24"})
      EXPECT_EQ(egl.json[key], osmesa.json[key]) << driver << " " << key;
  }
}

// The table export --driver judges by (identify/known_models.hpp) is what identify finds, and
// the subpixel bits each driver reports, on every driver it names.
TEST(Identify, KnownModelsAreWhatIdentifyFinds) {
  for (const glrc::identify::KnownModel& k : glrc::identify::known_models()) {
    const std::string driver(k.driver);
    SCOPED_TRACE(driver);
    const Identified r = identify(std::string("--backend ") +
                                  (driver == "zink" ? "egl" : "osmesa") + " --driver " + driver);
    ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.err;
    EXPECT_EQ(r.summary.at("subpixel_bits"), std::to_string(k.model.subpixel_bits));
    EXPECT_EQ(r.summary.at("planes"), glrc::to_string(k.model.planes));
    EXPECT_EQ(r.summary.at("tie"), glrc::to_string(k.model.tie_break));
    ASSERT_TRUE(r.json.is_object());
    EXPECT_EQ(r.json["subpixel_bits"]["reported"], k.reported_subpixel_bits);
  }
  EXPECT_EQ(glrc::identify::known_model("i965"), nullptr);
}

TEST(Identify, BadInputIsOneLineAndExitTwo) {
  for (const char* args : {"identify --driver no_such_driver", "identify --out /proc/no/such",
                           "identify --backend vulkan"}) {
    const Outcome o = glrefcheck(args);
    EXPECT_EQ(o.exit_code, 2) << args << ": " << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << args << ": " << o.err;
    EXPECT_EQ(o.out, "") << args;
  }
}

}  // namespace
