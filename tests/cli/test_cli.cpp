// The glrefcheck command as a user runs it: exit codes, one-line errors, files written.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/glrefcheck_process.hpp"

namespace {

namespace fs = std::filesystem;

using glrc::test::glrefcheck;
using glrc::test::Outcome;

fs::path temp_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("glrc_cli_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

size_t lines(const std::string& s) {
  return size_t(std::count(s.begin(), s.end(), '\n'));
}

TEST(Cli, ListsTheSuite) {
  const Outcome o = glrefcheck("list");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_GE(lines(o.out), 30u);
}

TEST(Cli, DigestPrintsOneHashPerCase) {
  const Outcome o = glrefcheck("digest --filter '^face_on'");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  ASSERT_GE(o.out.size(), 66u);
  EXPECT_EQ(o.out.find_first_not_of("0123456789abcdef"), 64u);
  EXPECT_EQ(glrefcheck("digest --filter '^face_on'").out, o.out);  // deterministic
}

TEST(Cli, MalformedCaseIsOneLineAndExitTwo) {
  const fs::path d = temp_dir("malformed");
  std::ofstream(d / "broken.json") << R"({"description": "x", "vertices": [{"clip": [0, 0, 0]}]})";
  const Outcome o = glrefcheck("list '" + d.string() + "'");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(lines(o.err), 1u) << o.err;
  EXPECT_NE(o.err.find("broken.json"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("vertices[0].clip"), std::string::npos) << o.err;
}

TEST(Cli, BadInputsExitTwo) {
  EXPECT_EQ(glrefcheck("list no/such/folder").exit_code, 2);
  EXPECT_EQ(glrefcheck("run --backend vulkan").exit_code, 2);
  EXPECT_EQ(glrefcheck("run --filter '('").exit_code, 2);
  EXPECT_EQ(glrefcheck("digest --subpixel-bits 40").exit_code, 2);
  EXPECT_EQ(glrefcheck("list --filter '^no_case_has_this_name$'").exit_code, 2);
  // Each of these is one line on stderr and exit 2, before any case runs.
  for (const char* args :
       {"run --out /proc/no/such/folder", "run --tolerance-ulps inf", "run --tolerance-ulps nan",
        "run --depth-tolerance-ulps -1", "run --driver no_such_driver", "run --baseline cases",
        "diff cases --out /proc/no/such/folder"}) {
    const Outcome bad = glrefcheck(args);
    EXPECT_EQ(bad.exit_code, 2) << args << ": " << bad.err;
    EXPECT_EQ(lines(bad.err), 1u) << args << ": " << bad.err;
    EXPECT_EQ(bad.out, "") << args;
  }
  const fs::path d = temp_dir("baseline");
  std::ofstream(d / "fails.txt") << "# a comment\njust_a_name_without_status\n";
  const Outcome o =
      glrefcheck("run --filter '^face_on' --baseline '" + (d / "fails.txt").string() + "'");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.err.find("fails.txt:2"), std::string::npos) << o.err;
}

TEST(Cli, RunWritesResultsAndHonoursTheBaseline) {
  const fs::path d = temp_dir("run");
  const std::string filter = "--filter '^face_on' --out '" + d.string() + "'";
  const Outcome pass = glrefcheck("run " + filter);
  ASSERT_EQ(pass.exit_code, 0) << pass.out << pass.err;
  const auto json = nlohmann::json::parse(std::ifstream(d / "results.json"));
  EXPECT_EQ(json["run"]["backend"], "osmesa");
  EXPECT_NE(json["run"]["gl_renderer"].get<std::string>().find("llvmpipe"), std::string::npos);
  EXPECT_EQ(json["summary"]["pass"].get<int>(), json["summary"]["total"].get<int>());
  EXPECT_TRUE(fs::exists(d / "junit.xml"));

  // A passing case listed as failing is an unexpected pass: the list needs updating.
  std::ofstream(d / "fails.txt") << "# evidence would go here\nface_on,Fail\n";
  const Outcome listed =
      glrefcheck("run " + filter + " --baseline '" + (d / "fails.txt").string() + "'");
  EXPECT_EQ(listed.exit_code, 1);
  EXPECT_NE(listed.out.find("UnexpectedPass"), std::string::npos) << listed.out;
}

// A confirmed driver bug: fails with a message that says NaN, and the repository's baseline
// turns it into an expected failure.
TEST(Cli, KnownDriverBugIsAnExpectedFailure) {
  const fs::path d = temp_dir("known");
  const std::string filter = "--filter '^clip_noperspective_x_plane$' --out '" + d.string() + "'";
  const Outcome bare = glrefcheck("run " + filter);
  EXPECT_EQ(bare.exit_code, 1) << bare.out << bare.err;
  EXPECT_NE(bare.out.find("NaN"), std::string::npos) << bare.out;
  const Outcome known =
      glrefcheck("run " + filter + " --baseline '" GLRC_SOURCE_DIR "/cases/known-failures.txt'");
  EXPECT_EQ(known.exit_code, 0) << known.out << known.err;
  EXPECT_NE(known.out.find("ExpectedFail"), std::string::npos) << known.out;
  const auto json = nlohmann::json::parse(std::ifstream(d / "results.json"));
  EXPECT_EQ(json["summary"]["expected_fail"].get<int>(), 1);
  EXPECT_EQ(json["cases"][0]["status"], "ExpectedFail");

  std::ofstream(d / "bad.txt") << "clip_noperspective_x_plane,Broken\n";
  const Outcome bad =
      glrefcheck("run " + filter + " --baseline '" + (d / "bad.txt").string() + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.txt:1: expected a status of Fail"), std::string::npos) << bad.err;
}

}  // namespace
