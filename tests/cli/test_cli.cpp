// The glrefcheck command as a user runs it: exit codes, one-line errors, files written.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

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

// --threads changes how fast, never a bit: the committed digests on 1 and 3 threads.
TEST(Cli, DigestsAreTheSameOnAnyNumberOfThreads) {
  const Outcome one = glrefcheck("digest cases --threads 1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  std::ifstream committed(std::string(GLRC_SOURCE_DIR) + "/tests/digests.txt");
  EXPECT_EQ(one.out, std::string(std::istreambuf_iterator<char>(committed), {}));
  EXPECT_EQ(glrefcheck("digest cases --threads 3").out, one.out);
  const Outcome zero = glrefcheck("digest cases --threads 0");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_EQ(zero.err, "glrefcheck: --threads: expected a whole number >= 1, got 0 (see --help)\n");
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

// What a careless user types, each said as it is: an option given twice, a device that is no
// number, --resume on a file, a case path that is a link to itself or to nothing.
TEST(Cli, MisusesSayWhatTheyAre) {
  const fs::path d = temp_dir("misuses");
  std::ofstream(d / "afile") << "x";
  fs::create_symlink("self.json", d / "self.json");
  fs::create_symlink("nowhere.json", d / "dangling.json");
  const std::vector<std::pair<std::string, std::string>> said = {
      {"run --jobs 1 --jobs 2", "--jobs: expected once, given 2 times"},
      {"run --device -1", "--device: expected a whole number >= 0, got -1"},
      {"run --device abc", "--device: expected a whole number >= 0, got \"abc\""},
      {"run --resume '" + (d / "afile").string() + "'",
       "expected a run folder with a journal.jsonl, got a file, not a folder"},
      {"list '" + (d / "self.json").string() + "'",
       "got a symbolic link that leads to no file (Too many levels of symbolic links)"},
      {"list '" + (d / "dangling.json").string() + "'",
       "got a symbolic link that leads to no file (No such file or directory)"}};
  for (const auto& [args, message] : said) {
    const Outcome o = glrefcheck(args);
    EXPECT_EQ(o.exit_code, 2) << args << ": " << o.err;
    EXPECT_EQ(lines(o.err), 1u) << args << ": " << o.err;
    EXPECT_NE(o.err.find(message), std::string::npos) << args << ": " << o.err;
  }
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

// A driver whose first draw is wrong (GL_harness's probe: a triangle covering a 4x4
// framebuffer, one flat float of 1) is what glrefcheck is there to report, not a reason to stop:
// the run prints and records a warning naming the pixel, and every case passes or fails on its
// own. The fault is planted in the real driver, not in glrefcheck: Mesa's
// MESA_SHADER_READ_PATH replaces a shader whose SHA-1 names a file there, so the fragment shader
// of the probe's program (and of its geometry-shader variant) is swapped for one that adds 1 to
// the flat value. Its file name comes from MESA_SHADER_DUMP_PATH on a first, clean run.
std::string sha1_of(const std::string& text, const fs::path& scratch) {
  std::ofstream(scratch, std::ios::binary) << text;
  FILE* p = popen(("sha1sum '" + scratch.string() + "'").c_str(), "r");
  char hex[41] = {};
  const size_t n = fread(hex, 1, 40, p);
  pclose(p);
  return std::string(hex, n);
}

TEST(Cli, WrongFirstDrawIsAWarningAndEveryCaseStillRuns) {
  const fs::path d = temp_dir("first_draw");
  fs::create_directories(d / "cases");
  fs::create_directories(d / "dump");
  fs::create_directories(d / "read");
  fs::copy_file(fs::path(GLRC_SOURCE_DIR) / "cases/face_on.json", d / "cases/face_on.json");
  // The first draw's program: one flat float, so this case draws with the planted fault too.
  std::ofstream(d / "cases/flat_one.json") << R"({
    "description": "One flat float of 1 over a triangle.",
    "varyings": [{"name": "f", "size": 1, "interpolation": "flat"}],
    "vertices": [{"clip": [-0.8, -0.75, 0.1, 1], "f": [1]},
                 {"clip": [0.85, -0.6, -0.2, 1], "f": [1]},
                 {"clip": [0.05, 0.9, 0.4, 1], "f": [1]}]
  })";
  const std::string run = "run '" + (d / "cases").string() + "' --jobs 1 --out '";

  const Outcome clean = glrefcheck(run + (d / "clean").string() + "'",
                                   "MESA_SHADER_DUMP_PATH='" + (d / "dump").string() + "'");
  ASSERT_EQ(clean.exit_code, 0) << clean.out << clean.err;
  EXPECT_EQ(clean.out.find("warning:"), std::string::npos) << clean.out;
  fs::path shader;
  std::string source;
  for (const auto& f : fs::directory_iterator(d / "dump")) {
    std::ifstream in(f.path());
    std::string text((std::istreambuf_iterator<char>(in)), {});
    if (f.path().filename().string().rfind("FS_", 0) == 0 &&
        text.find("flat in float v0;") != std::string::npos)
      shader = f.path(), source = text;
  }
  ASSERT_FALSE(source.empty()) << "Mesa's MESA_SHADER_DUMP_PATH wrote no fragment shader of the "
                                  "first draw's program into "
                               << (d / "dump");
  ASSERT_EQ(shader.filename().string(), "FS_" + sha1_of(source, d / "scratch") + ".glsl");
  const auto plant = [](std::string text, const std::string& input) {
    const std::string assign = "o0 = vec4(" + input + "0, ";
    const size_t at = text.find(assign);
    EXPECT_NE(at, std::string::npos) << text;
    return text.replace(at, assign.size(), "o0 = vec4(" + input + "0 + 1.0, ");
  };
  std::ofstream(d / "read" / shader.filename()) << plant(source, "v");
  // The same program fed by the pass-through geometry shader reads g0 instead of v0.
  std::string gs_source = source;
  for (size_t at; (at = gs_source.find("v0")) != std::string::npos;)
    gs_source.replace(at, 2, "g0");
  std::ofstream(d / "read" / ("FS_" + sha1_of(gs_source, d / "scratch") + ".glsl"))
      << plant(gs_source, "g");

  const Outcome o = glrefcheck(run + (d / "faulty").string() + "'",
                               "MESA_SHADER_READ_PATH='" + (d / "read").string() + "'");
  std::cout << "[ run      ] with the planted fault, glrefcheck run printed:\n" << o.out;
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;  // a case fails; nothing is a usage error
  EXPECT_EQ(o.err, "");
  const std::string warning =
      "the first draw (one triangle covering a 4x4 framebuffer) is wrong: pixel (0, 0) expected "
      "primitive 0 and flat value 1, got primitive 0 and value 2 (16 of 16 pixels wrong); with "
      "a pass-through geometry shader for gl_PrimitiveID: pixel (0, 0) expected primitive 0 and "
      "flat value 1, got primitive 0 and value 2 (16 of 16 pixels wrong); cases are drawn "
      "without a geometry shader and each passes or fails on its own";
  EXPECT_NE(o.out.find("\nwarning: 'llvmpipe"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find(warning + "\n"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("\nPass           face_on "), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("\nFail           flat_one "), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("f.x: "), std::string::npos) << o.out;  // the value is what fails
  EXPECT_NE(o.out.find("\n2 cases: 1 pass, 1 fail,"), std::string::npos) << o.out;

  const auto json = nlohmann::json::parse(std::ifstream(d / "faulty" / "results.json"));
  ASSERT_EQ(json["run"]["gl_warnings"].size(), 1u) << json["run"];
  EXPECT_NE(json["run"]["gl_warnings"][0].get<std::string>().find(warning), std::string::npos);
  EXPECT_EQ(json["summary"]["pass"].get<int>(), 1);
  EXPECT_EQ(json["summary"]["fail"].get<int>(), 1);
  // The clean run records no warning.
  const auto clean_json = nlohmann::json::parse(std::ifstream(d / "clean" / "results.json"));
  EXPECT_EQ(clean_json["run"]["gl_warnings"], nlohmann::json::array());
}

TEST(Cli, ACaseBeyondTheSpecifiedRangeIsASkipWithTheReason) {
  const fs::path d = temp_dir("beyond_range");
  fs::create_directories(d / "cases");
  // Clip coordinates of FLT_MAX: Mesa draws nothing of this triangle, the reference all of it.
  std::ofstream(d / "cases/flt_max.json") << R"({
    "description": "Clip coordinates of FLT_MAX, beyond the 2^32 GL guarantees.",
    "varyings": [{"name": "c", "size": 1}],
    "vertices": [{"clip": [-0.5, -0.5, 0, 1], "c": [0]},
                 {"clip": ["0x1.fffffep127", -0.5, 0, 1], "c": [1]},
                 {"clip": [-0.5, "0x1.fffffep127", 0, 1], "c": [2]}]
  })";
  const Outcome o = glrefcheck("run '" + (d / "cases").string() + "' --jobs 1 --out '" +
                               (d / "out").string() + "'");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;  // not held against the implementation
  EXPECT_NE(o.out.find("Skip           flt_max"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("outside GL's specified range: vertices[1].clip[0] = 3.40282e+38 is "
                       "beyond 2^32"),
            std::string::npos)
      << o.out;
  std::ifstream csv(d / "out/results.csv");
  const std::string text((std::istreambuf_iterator<char>(csv)), {});
  EXPECT_NE(text.find("flt_max,Skip,"), std::string::npos) << text;
}

}  // namespace
