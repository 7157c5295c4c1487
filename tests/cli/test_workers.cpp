// `run` with worker processes, as CI uses it: a killed worker is a Crash and the run completes,
// a hung case is a Timeout, shards merge into the unsharded run, Mesa CI's files are read and
// written in their formats, --mesa takes GL from a prefix.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>

#include "tests/support/glrefcheck_process.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using glrc::test::glrefcheck;
using glrc::test::Outcome;
using glrc::test::proxied_workers;
using glrc::test::wait_for_pid;

// Eight quick cases on llvmpipe through OSMesa.
const std::string kCases =
    "--filter '^(viewport_(guard|offset|tiny)|attr)' --backend osmesa --driver llvmpipe";

std::string read(const fs::path& f) {
  std::ifstream in(f);
  return {std::istreambuf_iterator<char>(in), {}};
}

// case -> Status, from a results.csv.
std::map<std::string, std::string> statuses(const fs::path& csv) {
  std::map<std::string, std::string> m;
  std::ifstream in(csv);
  std::string line;
  const std::regex row(R"(([^,]+),([A-Za-z]+),([0-9]+\.[0-9]+))");
  std::smatch match;
  while (std::getline(in, line)) {
    EXPECT_TRUE(std::regex_match(line, match, row)) << "not `case,Status,seconds`: " << line;
    m[match[1]] = match[2];
  }
  return m;
}

class Workers : public glrc::test::TempDirTest {};

TEST_F(Workers, KilledWorkerIsACrashAndTheRunCompletes) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid";
  Outcome o;
  std::thread run([&] {
    o = glrefcheck(
        "run " + kCases + " --jobs 2 --out '" + out.string() + "'" +
        proxied_workers("--stall-case viewport_tiny --pidfile '" + pidfile.string() + "'"));
  });
  // The worker holding viewport_tiny writes its pid there and waits, as a hung driver would.
  const pid_t pid = wait_for_pid(pidfile);
  ASSERT_GT(pid, 0) << "no worker reached the stalled case";
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  run.join();

  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;  // a crash fails the run
  const auto s = statuses(out / "results.csv");
  ASSERT_EQ(s.size(), 8u) << read(out / "results.csv");
  EXPECT_EQ(s.at("viewport_tiny"), "Crash");
  for (const auto& [name, status] : s)
    if (name != "viewport_tiny") {
      EXPECT_EQ(status, "Pass") << name;
    }
  EXPECT_NE(o.out.find("killed by signal 9"), std::string::npos) << o.out;
  EXPECT_EQ(read(out / "failures.csv").rfind("viewport_tiny,Crash,", 0), 0u);
  const auto results = nlohmann::json::parse(read(out / "results.json"));
  EXPECT_EQ(results["summary"]["crash"], 1);
  EXPECT_EQ(results["summary"]["pass"], 7);
}

TEST_F(Workers, HungCaseIsATimeout) {
  const fs::path out = dir_ / "out";
  const Outcome o = glrefcheck("run " + kCases + " --jobs 1 --timeout 5 --out '" + out.string() +
                               "'" + proxied_workers("--stall-case attr_huge"));
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;
  const auto s = statuses(out / "results.csv");
  ASSERT_EQ(s.size(), 8u);
  EXPECT_EQ(s.at("attr_huge"), "Timeout");
  for (const auto& [name, status] : s)
    if (name != "attr_huge") {
      EXPECT_EQ(status, "Pass") << name;
    }
  EXPECT_NE(o.out.find("no result after 5 s (--timeout)"), std::string::npos) << o.out;
  // A Mesa-style fails file that expects it makes the run pass.
  std::ofstream(dir_ / "fails.txt") << "# hangs (see the test)\nattr_huge,Timeout\n";
  EXPECT_EQ(glrefcheck("run " + kCases + " --jobs 1 --timeout 5 --out '" + out.string() +
                       "' --baseline '" + (dir_ / "fails.txt").string() + "'" +
                       proxied_workers("--stall-case attr_huge"))
                .exit_code,
            0);
  EXPECT_EQ(statuses(out / "results.csv").at("attr_huge"), "ExpectedFail");
}

// A failing case's verdict comes before its heatmaps: a worker that hangs or dies writing them
// (as one writing ~200 maps of a 4096x4096 frame did, ending as Timeout) costs the maps, not the
// verdict. worker_proxy.py --stall-images stalls the worker after it sent the verdict.
const std::string kFailingCase =
    "--filter '^(viewport_tiny|clip_noperspective_x_plane|viewport_offset)$' --backend osmesa "
    "--driver llvmpipe";

TEST_F(Workers, HeatmapsThatHangCostTheHeatmapsNotTheVerdict) {
  const fs::path out = dir_ / "out";
  const Outcome o =
      glrefcheck("run " + kFailingCase + " --jobs 1 --timeout 5 --out '" + out.string() + "'" +
                 proxied_workers("--stall-images clip_noperspective_x_plane"));
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;
  const auto s = statuses(out / "results.csv");
  ASSERT_EQ(s.size(), 3u) << read(out / "results.csv");
  EXPECT_EQ(s.at("clip_noperspective_x_plane"), "Fail");  // not Timeout
  EXPECT_EQ(s.at("viewport_tiny"), "Pass");
  EXPECT_EQ(s.at("viewport_offset"), "Pass");
  const auto results = nlohmann::json::parse(read(out / "results.json"));
  for (const auto& c : results["cases"])
    if (c["name"] == "clip_noperspective_x_plane") {
      EXPECT_NE(c["message"].get<std::string>().find(
                    "heatmaps not written: not done after 5 s (--timeout); worker killed"),
                std::string::npos)
          << c;
      int non_finite = 0;  // the real verdict: NaN in the noperspective varying
      for (const auto& channel : c["channels"])
        if (channel["name"] == "n.x") non_finite = channel["non_finite"];
      EXPECT_GT(non_finite, 0) << c;
    }
  EXPECT_NE(o.out.find("clip_noperspective_x_plane: heatmaps not written"), std::string::npos)
      << o.out;
  // The journal's later line, with the note, is the one a resumed run reads.
  const std::string journal = read(out / "journal.jsonl");
  EXPECT_NE(journal.rfind("heatmaps not written"), std::string::npos);
}

TEST_F(Workers, AWorkerKilledWritingHeatmapsKeepsTheVerdict) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid";
  Outcome o;
  std::thread run([&] {
    o = glrefcheck("run " + kFailingCase + " --jobs 1 --out '" + out.string() + "'" +
                   proxied_workers("--stall-images clip_noperspective_x_plane --pidfile '" +
                                   pidfile.string() + "'"));
  });
  const pid_t pid = wait_for_pid(pidfile);
  ASSERT_GT(pid, 0) << "no worker reached the stalled heatmaps";
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  run.join();
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;
  const auto s = statuses(out / "results.csv");
  ASSERT_EQ(s.size(), 3u) << read(out / "results.csv");
  EXPECT_EQ(s.at("clip_noperspective_x_plane"), "Fail");  // not Crash
  EXPECT_EQ(s.at("viewport_tiny"), "Pass");
  EXPECT_EQ(s.at("viewport_offset"), "Pass");
  EXPECT_NE(o.out.find("heatmaps not written: the worker killed by signal 9"), std::string::npos)
      << o.out;
}

// Everything but the timings and the sharding fields, which differ by design.
nlohmann::json comparable(nlohmann::json results) {
  results.erase("written_by");  // its stamp: of the file's text, timings included
  for (const char* key : {"seconds", "jobs", "fraction", "fraction_start"})
    results["run"].erase(key);
  for (auto& c : results["cases"])
    c.erase("seconds");
  return results;
}

TEST_F(Workers, MergedShardsEqualTheUnshardedRun) {
  const std::string cases =
      "--filter '^(viewport_(guard|offset|tiny)|attr|clip_noperspective)' --baseline "
      "cases/known-failures.txt --html";  // known failures get heatmaps too
  const fs::path whole = dir_ / "whole";
  ASSERT_EQ(glrefcheck("run " + cases + " --jobs 2 --out '" + whole.string() + "'").exit_code, 0);
  std::string shards;
  for (int k = 1; k <= 3; ++k) {
    const fs::path shard = dir_ / ("shard" + std::to_string(k));
    const Outcome o = glrefcheck("run " + cases + " --jobs 1 --fraction 3 --fraction-start " +
                                 std::to_string(k) + " --out '" + shard.string() + "'");
    ASSERT_EQ(o.exit_code, 0) << o.out << o.err;
    EXPECT_NE(o.out.find("shard " + std::to_string(k) + " of 3, 14 cases in all"),
              std::string::npos)
        << o.out;
    shards += " '" + shard.string() + "'";
  }
  const fs::path merged = dir_ / "merged";
  const Outcome m = glrefcheck("merge" + shards + " --out '" + merged.string() + "'");
  ASSERT_EQ(m.exit_code, 0) << m.out << m.err;

  const auto a = nlohmann::json::parse(read(whole / "results.json"));
  const auto b = nlohmann::json::parse(read(merged / "results.json"));
  ASSERT_EQ(a["cases"].size(), 14u);
  EXPECT_EQ(comparable(a), comparable(b));
  // The failing cases' heatmaps come along; the CSVs list the same statuses in the same order.
  EXPECT_TRUE(fs::exists(merged / "cases/clip_noperspective_x_plane/n.x_error.png"));
  EXPECT_TRUE(fs::exists(whole / "report.html"));
  EXPECT_TRUE(fs::exists(whole / "report.html"));
  auto csv_statuses = [](const fs::path& f) {
    std::string text;
    std::ifstream in(f);
    for (std::string line; std::getline(in, line);)
      text += line.substr(0, line.rfind(',')) + "\n";
    return text;
  };
  EXPECT_EQ(csv_statuses(whole / "results.csv"), csv_statuses(merged / "results.csv"));

  // A shard missing, or given twice, is bad input.
  const Outcome missing =
      glrefcheck("merge '" + (dir_ / "shard1").string() + "' '" + (dir_ / "shard2").string() +
                 "' --out '" + (dir_ / "m2").string() + "'");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("shard 3 of 3 is missing"), std::string::npos) << missing.err;
  EXPECT_EQ(glrefcheck("run " + cases + " --fraction 3 --fraction-start 4").exit_code, 2);
}

TEST_F(Workers, MesaCiFilesAreReadAndWritten) {
  // A fails file as Mesa CI keeps them: comments with the evidence, `case,Status` lines.
  std::ofstream(dir_ / "llvmpipe-fails.txt")
      << "# Mesa 22.3.6: the draw module's clipper gives NaN in noperspective varyings\n"
         "clip_noperspective_x_plane,Fail\n"
         "clip_noperspective_x_minus_plane,Fail\n"
         "\n"
         "clip_noperspective_x_plane_near,Fail\n";
  std::ofstream(dir_ / "llvmpipe-flakes.txt") << "# none known\n^viewport_tin.$\n";
  std::ofstream(dir_ / "llvmpipe-skips.txt") << "# too slow for this test\nattr_.*\n";
  const fs::path out = dir_ / "out";
  const std::string cases = "--filter '^(viewport_(guard|offset|tiny)|attr|clip_noperspective_x)'";
  const Outcome o = glrefcheck("run " + cases + " --out '" + out.string() + "' --baseline '" +
                               (dir_ / "llvmpipe-fails.txt").string() + "' --flakes '" +
                               (dir_ / "llvmpipe-flakes.txt").string() + "' --skips '" +
                               (dir_ / "llvmpipe-skips.txt").string() + "'");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  const auto s = statuses(out / "results.csv");
  EXPECT_EQ(s.at("clip_noperspective_x_plane"), "ExpectedFail");
  EXPECT_EQ(s.at("clip_noperspective_x_plane_near"), "ExpectedFail");
  EXPECT_EQ(s.at("attr_huge"), "Skip");
  EXPECT_EQ(s.at("viewport_tiny"), "Pass");
  EXPECT_EQ(read(out / "failures.csv"), "");  // nothing unexpected

  // Without the baseline the NaN cases fail, and that run's failures.csv, duration column
  // included, serves as the next run's baseline (as deqp-runner's --baseline does).
  const fs::path first = dir_ / "first";
  EXPECT_EQ(glrefcheck("run " + cases + " --out '" + first.string() + "'").exit_code, 1);
  EXPECT_EQ(statuses(first / "failures.csv").size(), 3u);
  EXPECT_EQ(glrefcheck("run " + cases + " --out '" + out.string() + "' --baseline '" +
                       (first / "failures.csv").string() + "'")
                .exit_code,
            0);
  // A failing case listed as flaky does not fail the run.
  std::ofstream(dir_ / "flakes.txt") << "clip_noperspective_x_.*\n";
  EXPECT_EQ(glrefcheck("run " + cases + " --out '" + out.string() + "' --flakes '" +
                       (dir_ / "flakes.txt").string() + "'")
                .exit_code,
            0);
  EXPECT_EQ(statuses(out / "results.csv").at("clip_noperspective_x_plane"), "Flake");
}

TEST_F(Workers, BadExpectationFilesAreOneLineAndExitTwo) {
  std::ofstream(dir_ / "bad-fails.txt") << "clip_near,Fail\nclip_far,Broken\n";
  std::ofstream(dir_ / "bad-skips.txt") << "attr_(\n";
  for (const auto& [option, file, expected] :
       {std::tuple{"--baseline", "bad-fails.txt", "bad-fails.txt:2: expected a status of Fail"},
        {"--skips", "bad-skips.txt", "bad-skips.txt:1: expected a regular expression"},
        {"--flakes", "missing.txt", "missing.txt: expected a file of regular expressions"}}) {
    const Outcome o = glrefcheck("run " + kCases + " --out '" + (dir_ / "out").string() + "' " +
                                 option + " '" + (dir_ / file).string() + "'");
    EXPECT_EQ(o.exit_code, 2) << option;
    EXPECT_NE(o.err.find(expected), std::string::npos) << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  }
}

TEST_F(Workers, MesaPrefixRunsTheLibrariesInIt) {
  // A prefix holding (links to) the system's Mesa: GL must come from the prefix's path, and the
  // results say so.
  const fs::path system_osmesa = "/usr/lib/x86_64-linux-gnu/libOSMesa.so.8";
  if (!fs::exists(system_osmesa)) GTEST_SKIP() << "no " << system_osmesa;
  const fs::path lib = dir_ / "prefix/usr/lib/x86_64-linux-gnu";
  fs::create_directories(lib);
  fs::create_symlink(fs::canonical(system_osmesa), lib / "libOSMesa.so.8");
  const fs::path out = dir_ / "out";
  const Outcome o = glrefcheck("run " + kCases + " --mesa '" + (dir_ / "prefix").string() +
                               "' --out '" + out.string() + "'");
  ASSERT_EQ(o.exit_code, 0) << o.out << o.err;
  const auto run = nlohmann::json::parse(read(out / "results.json"))["run"];
  EXPECT_EQ(run["gl_library"], (lib / "libOSMesa.so.8").string());
  EXPECT_NE(run["mesa_prefix"].get<std::string>().find("prefix"), std::string::npos);
  EXPECT_NE(run["gl_version"].get<std::string>().find("Mesa"), std::string::npos);

  // A folder without Mesa, and an OSMesa-less prefix for --backend osmesa, are bad input.
  const Outcome none = glrefcheck("run " + kCases + " --mesa '" + dir_.string() + "/out'");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("expected libEGL_mesa.so.0 or libOSMesa.so.8"), std::string::npos)
      << none.err;
  const Outcome egl = glrefcheck("run --filter viewport_tiny --backend egl --mesa '" +
                                 (dir_ / "prefix").string() + "' --out '" + out.string() + "'");
  EXPECT_EQ(egl.exit_code, 2);
  EXPECT_NE(egl.err.find("no libEGL_mesa.so.0"), std::string::npos) << egl.err;
}

}  // namespace
