// Nothing lost (issue 11): `run` and `merge` write only into folders glrefcheck owns, every
// finished case survives SIGINT, SIGTERM and kill -9, `run --resume` completes the run as an
// uninterrupted one would, workers die with their runner, and the options and case names that
// would break a run are refused up front with one line.
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "tests/support/glrefcheck_process.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using glrc::test::ended_within;
using glrc::test::glrefcheck;
using glrc::test::Outcome;
using glrc::test::parent_of;
using glrc::test::proxied_workers;
using glrc::test::wait_for_pid;

// Eight quick cases, in this order: attr_crossing_zero, attr_huge, attr_mixed_magnitudes,
// attr_offset_small_gradient, attr_tiny, viewport_guard_band, viewport_offset, viewport_tiny.
const std::string kCases = "--filter '^(viewport_(guard|offset|tiny)|attr)'";

std::string read(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

size_t lines(const std::string& s) {
  return size_t(std::count(s.begin(), s.end(), '\n'));
}

// Every file under `dir` with its contents: what must not change.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> m;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    m[fs::relative(e.path(), dir).string()] = e.is_regular_file() ? read(e.path()) : "<folder>";
  return m;
}

// results.json without what differs between two runs of the same cases by design: timings, and
// whether the model was identified now or found in the cache (the first run of a fresh cache
// identifies, the next finds it).
nlohmann::json comparable(nlohmann::json results) {
  results.erase("written_by");  // its stamp: of the file's text, timings included
  results["run"].erase("seconds");
  results["run"].erase("model_source");
  for (auto& c : results["cases"])
    c.erase("seconds");
  return results;
}

nlohmann::json results_of(const fs::path& dir) {
  return nlohmann::json::parse(read(dir / "results.json"));
}

int cores() {
  cpu_set_t set;
  return sched_getaffinity(0, sizeof set, &set) == 0 ? std::max(1, CPU_COUNT(&set)) : 1;
}

class RunFolder : public glrc::test::TempDirTest {};

// `glrefcheck run --out .` in a checkout deleted cases/ after loading it (issue 11): now the
// folder, which holds what glrefcheck did not write, is refused and nothing in it changes.
TEST_F(RunFolder, OutDotInACheckoutIsRefusedAndNothingIsDeleted) {
  const fs::path checkout = dir_ / "checkout";
  fs::create_directories(checkout / "cases");
  for (const char* c : {"face_on.json", "viewport_tiny.json"})
    fs::copy_file(fs::path(GLRC_SOURCE_DIR) / "cases" / c, checkout / "cases" / c);
  std::ofstream(checkout / "README.md") << "a checkout\n";
  const auto before = snapshot(checkout);
  const Outcome o = glrefcheck("run --jobs 1 --out .", "cd '" + checkout.string() + "' &&");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_EQ(o.out, "");
  EXPECT_EQ(lines(o.err), 1u) << o.err;
  EXPECT_NE(o.err.find("--out: expected a new or empty folder, or one glrefcheck made (it holds "
                       "a .glrefcheck file), got \".\", which holds \"README.md\" and 1 more"),
            std::string::npos)
      << o.err;
  EXPECT_EQ(snapshot(checkout), before);

  // The same for merge, into a folder with a file of the user's called cases/.
  const Outcome m =
      glrefcheck("merge '" + (dir_ / "no_shard").string() + "' --out '" + checkout.string() + "'");
  EXPECT_EQ(m.exit_code, 2) << m.out << m.err;
  EXPECT_EQ(lines(m.err), 1u) << m.err;
  EXPECT_EQ(snapshot(checkout), before);
}

// A folder glrefcheck made is reused: the earlier run's files go (a report.html left from a run
// with --html would pass for this run's), the user's stay.
TEST_F(RunFolder, MarkedFolderIsReusedCleanly) {
  const fs::path out = dir_ / "out";
  const Outcome first = glrefcheck(
      "run --filter '^(face_on|clip_noperspective_x_plane)$' --jobs 1 "
      "--html --out '" +
      out.string() + "'");
  ASSERT_EQ(first.exit_code, 1) << first.out << first.err;  // the clipper's NaN fails
  ASSERT_TRUE(fs::exists(out / ".glrefcheck"));
  ASSERT_TRUE(fs::exists(out / "report.html"));
  ASSERT_TRUE(fs::exists(out / "cases/clip_noperspective_x_plane/n.x_error.png"));
  std::ofstream(out / "notes.txt") << "mine\n";

  const Outcome second = glrefcheck("run cases/face_on.json --jobs 1 --out '" + out.string() + "'");
  ASSERT_EQ(second.exit_code, 0) << second.out << second.err;
  EXPECT_FALSE(fs::exists(out / "report.html"));
  EXPECT_FALSE(fs::exists(out / "cases"));
  EXPECT_EQ(read(out / "notes.txt"), "mine\n");
  const auto results = results_of(out);
  ASSERT_EQ(results["cases"].size(), 1u);
  EXPECT_EQ(results["cases"][0]["name"], "face_on");
  EXPECT_EQ(results["run"]["interrupted"], false);
  EXPECT_EQ(read(out / "results.csv").rfind("face_on,Pass,", 0), 0u);
  for (const auto& e : fs::directory_iterator(out))  // atomic writes leave no temporary files
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();

  // Without the marker, a folder holding glrefcheck's results.json is refused all the same: the
  // results.json may be copied or forged, and the user's files in cases/ were deleted.
  fs::remove(out / ".glrefcheck");
  fs::create_directories(out / "cases");
  std::ofstream(out / "cases/precious.txt") << "mine\n";
  const Outcome unmarked =
      glrefcheck("run cases/face_on.json --jobs 1 --out '" + out.string() + "'");
  EXPECT_EQ(unmarked.exit_code, 2) << unmarked.out << unmarked.err;
  EXPECT_EQ(unmarked.err,
            "glrefcheck: --out: expected a new or empty folder, or one glrefcheck "
            "made (it holds a .glrefcheck file), got \"" +
                out.string() +
                "\", which holds glrefcheck's results but no marker (an older "
                "glrefcheck's, or copied): glrefcheck replaces nothing it did not "
                "mark; delete the folder or name another\n");
  EXPECT_FALSE(fs::exists(out / ".glrefcheck"));
  EXPECT_EQ(read(out / "cases/precious.txt"), "mine\n");
  EXPECT_EQ(read(out / "notes.txt"), "mine\n");
}

// A run whose case files lie where a run replaces its files (<out>/cases) is refused: reusing
// the folder would delete them.
TEST_F(RunFolder, CasesInsideTheRunsOwnFilesAreRefused) {
  const fs::path out = dir_ / "out";
  ASSERT_EQ(glrefcheck("run cases/face_on.json --jobs 1 --out '" + out.string() + "'").exit_code,
            0);
  fs::create_directories(out / "cases");
  fs::copy_file(fs::path(GLRC_SOURCE_DIR) / "cases/face_on.json", out / "cases/mine.json");
  const Outcome o =
      glrefcheck("run '" + (out / "cases").string() + "' --jobs 1 --out '" + out.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_EQ(lines(o.err), 1u) << o.err;
  EXPECT_NE(o.err.find("holds this run's case files"), std::string::npos) << o.err;
  EXPECT_TRUE(fs::exists(out / "cases/mine.json"));
}

// A moment to stop a run at: the case a worker stalls on (the cases before it, with --jobs 1,
// have finished), and the signal.
struct Moment {
  const char* stall;
  int signal;
};

// For the test's name in ctest's list: "SIGINT at attr_crossing_zero".
void PrintTo(const Moment& m, std::ostream* os) {
  *os << "SIG" << sigabbrev_np(m.signal) << " at " << m.stall;
}

class Interrupted : public glrc::test::TempDirTest, public ::testing::WithParamInterface<Moment> {};

// The run is stopped while a worker hangs on `stall`; what finished is on disk (results.json for
// SIGINT and SIGTERM, marked interrupted; the journal for kill -9), the worker is gone, and
// --resume ends with the results of an uninterrupted run.
TEST_P(Interrupted, ResumeGivesTheUninterruptedResults) {
  const Moment m = GetParam();
  const fs::path whole = dir_ / "whole", out = dir_ / "out", pidfile = dir_ / "worker.pid";
  ASSERT_EQ(glrefcheck("run " + kCases + " --jobs 1 --out '" + whole.string() + "'").exit_code, 0);

  Outcome o;
  std::thread run([&] {
    o = glrefcheck("run " + kCases + " --jobs 1 --out '" + out.string() + "'" +
                   proxied_workers(std::string("--stall-case ") + m.stall + " --pidfile '" +
                                   pidfile.string() + "'"));
  });
  const pid_t worker = wait_for_pid(pidfile);
  ASSERT_GT(worker, 0) << "no worker reached " << m.stall;
  const pid_t runner = parent_of(worker);
  ASSERT_GT(runner, 1);
  ASSERT_EQ(kill(runner, m.signal), 0);
  run.join();
  EXPECT_TRUE(ended_within(worker, std::chrono::seconds(10))) << "the worker outlived its runner";

  const std::string journal = read(out / "journal.jsonl");
  const size_t finished = lines(journal) - 2;  // the options line, the GL and model line
  const size_t before = std::string(m.stall) == "attr_crossing_zero" ? 0
                        : std::string(m.stall) == "viewport_tiny"    ? 7
                                                                     : 3;
  EXPECT_EQ(finished, before) << journal;
  if (m.signal == SIGKILL) {
    EXPECT_NE(o.exit_code, 0);
    EXPECT_FALSE(fs::exists(out / "results.json"));  // never an earlier run's
  } else {
    EXPECT_EQ(o.exit_code, 128 + m.signal) << o.out << o.err;
    EXPECT_NE(
        o.out.find("interrupted by " + std::string(m.signal == SIGINT ? "SIGINT" : "SIGTERM") +
                   " after " + std::to_string(before) + " of 8 cases"),
        std::string::npos)
        << o.out;
    const auto partial = results_of(out);
    EXPECT_EQ(partial["run"]["interrupted"], true);
    EXPECT_EQ(partial["summary"]["total"], before);
    EXPECT_EQ(partial["cases"].size(), before);
    EXPECT_EQ(lines(read(out / "results.csv")), before);
  }

  const Outcome resumed = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.out << resumed.err;
  EXPECT_NE(resumed.out.find(std::to_string(before) + " of 8 cases done before"), std::string::npos)
      << resumed.out;
  EXPECT_EQ(comparable(results_of(out)), comparable(results_of(whole)));
  EXPECT_EQ(results_of(out)["run"]["interrupted"], false);
}

INSTANTIATE_TEST_SUITE_P(Moments, Interrupted,
                         ::testing::Values(Moment{"attr_crossing_zero", SIGINT},
                                           Moment{"attr_offset_small_gradient", SIGTERM},
                                           Moment{"viewport_tiny", SIGKILL},
                                           Moment{"attr_crossing_zero", SIGKILL},
                                           Moment{"viewport_tiny", SIGINT}),
                         [](const auto& p) {
                           return std::string(p.param.signal == SIGINT    ? "sigint_"
                                              : p.param.signal == SIGTERM ? "sigterm_"
                                                                          : "sigkill_") +
                                  p.param.stall;
                         });

// The last run's failures.csv as the next run's --baseline: in the same folder, the run would
// replace the baseline with its own failures.csv, which lists no expected failure (the seventh
// hostile campaign of issue 45: a curated list lost): refused, the file as it was. Copied out,
// it may change while the run is stopped; --resume judges by the copy the run made when it
// began.
TEST_F(RunFolder, ResumeJudgesByTheBaselineTheRunBeganWith) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid", baseline = dir_ / "fails.csv";
  const std::string cases = "run --filter '^(clip_noperspective_x_plane|viewport_tiny)$' --jobs 1 ";
  ASSERT_EQ(glrefcheck(cases + "--out '" + out.string() + "'").exit_code, 1);
  const std::string failures = read(out / "failures.csv");
  ASSERT_EQ(failures.rfind("clip_noperspective_x_plane,Fail,", 0), 0u);
  const Outcome inside = glrefcheck(cases + "--out '" + out.string() + "' --baseline '" +
                                    (out / "failures.csv").string() + "'");
  EXPECT_EQ(inside.exit_code, 2) << inside.out << inside.err;
  EXPECT_NE(inside.err.find("holds this run's --baseline"), std::string::npos) << inside.err;
  EXPECT_EQ(read(out / "failures.csv"), failures);

  fs::copy_file(out / "failures.csv", baseline);
  Outcome o;
  std::thread run([&] {
    o = glrefcheck(cases + "--out '" + out.string() + "' --baseline '" + baseline.string() + "'" +
                   proxied_workers("--stall-case clip_noperspective_x_plane --pidfile '" +
                                   pidfile.string() + "'"));
  });
  const pid_t worker = wait_for_pid(pidfile);
  ASSERT_GT(worker, 0);
  ASSERT_EQ(kill(parent_of(worker), SIGINT), 0);
  run.join();
  EXPECT_EQ(o.exit_code, 130) << o.out << o.err;
  std::ofstream(baseline) << "";  // the list edited while the run is stopped
  // The copy edited (the tenth hostile campaign): the cases checked before were judged by the
  // baseline as it was, the rest would be by the edit. Refused, the journal as it was.
  const fs::path copy = out / ".glrefcheck-inputs/baseline";
  const std::string copied = read(copy), journal = read(out / "journal.jsonl");
  std::ofstream(copy, std::ios::app) << "viewport_tiny,Fail\n";
  const Outcome edited = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(edited.exit_code, 2) << edited.out << edited.err;
  EXPECT_NE(edited.err.find(copy.string() + " is not as the run began (edited since): start a "
                                            "new run"),
            std::string::npos)
      << edited.err;
  EXPECT_EQ(read(out / "journal.jsonl"), journal);
  std::ofstream(copy) << copied;

  const Outcome resumed = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.out << resumed.err;
  const auto results = results_of(out);
  ASSERT_EQ(results["cases"].size(), 2u);
  EXPECT_EQ(results["cases"][0]["status"], "ExpectedFail");
  EXPECT_EQ(results["cases"][1]["status"], "Pass");
}

// A kill while the journal's last line was being written leaves it cut: that case runs again,
// and the lines written after it on --resume are read as whole lines.
TEST_F(RunFolder, JournalLineCutByAKillIsCheckedAgain) {
  const fs::path out = dir_ / "out";
  ASSERT_EQ(glrefcheck("run " + kCases + " --jobs 1 --out '" + out.string() + "'").exit_code, 0);
  const auto whole = results_of(out);
  const std::string journal = read(out / "journal.jsonl");
  std::ofstream(out / "journal.jsonl", std::ios::binary) << journal.substr(0, journal.size() - 40);
  fs::remove(out / "results.json");
  const Outcome first = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(first.exit_code, 0) << first.out << first.err;
  EXPECT_NE(first.out.find("7 of 8 cases done before"), std::string::npos) << first.out;
  EXPECT_NE(first.out.find("\nPass           viewport_tiny "), std::string::npos) << first.out;
  // Resumed once more, the journal reads whole: nothing is left to check.
  const Outcome again = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(again.exit_code, 0) << again.out << again.err;
  EXPECT_NE(again.out.find("8 of 8 cases done before"), std::string::npos) << again.out;
  EXPECT_EQ(comparable(results_of(out)), comparable(whole));
}

TEST_F(RunFolder, ResumeTakesNoOtherOptions) {
  const Outcome cases = glrefcheck("run --resume '" + dir_.string() + "' cases/face_on.json");
  EXPECT_EQ(cases.exit_code, 2);
  EXPECT_EQ(lines(cases.err), 1u) << cases.err;
  EXPECT_NE(cases.err.find("--resume: expected no other option than --jobs"), std::string::npos)
      << cases.err;
  const Outcome none = glrefcheck("run --resume '" + dir_.string() + "'");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_EQ(lines(none.err), 1u) << none.err;
  EXPECT_NE(none.err.find("expected a run folder with a journal.jsonl"), std::string::npos)
      << none.err;
}

class RunOptions : public glrc::test::TempDirTest {};

// `--timeout nan` was accepted and made every case a Timeout.
TEST_F(RunOptions, TimeoutMustBeAFiniteNumberOfSeconds) {
  for (const char* t : {"nan", "inf", "-1", "0", "1e400", "5s"}) {
    const Outcome o = glrefcheck(std::string("run cases/face_on.json --timeout ") + t + " --out '" +
                                 (dir_ / "out").string() + "'");
    EXPECT_EQ(o.exit_code, 2) << t << ": " << o.out << o.err;
    EXPECT_EQ(o.out, "") << t;
    EXPECT_EQ(lines(o.err), 1u) << t << ": " << o.err;
    EXPECT_NE(o.err.find("--timeout: expected a"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("number from 0.001 to 1000000, got"), std::string::npos) << o.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// CLI11's range for --jobs 0 printed 300 digits; --jobs 100000 started one worker per case.
TEST_F(RunOptions, JobsArePlainAndCappedAtTheCores) {
  for (const auto& [args, expected] :
       {std::pair{"--jobs 0", "glrefcheck: --jobs: expected a whole number >= 1, got 0"},
        {"--jobs -3", "glrefcheck: --jobs: expected a whole number >= 1, got -3"},
        {"--fraction 0", "glrefcheck: --fraction: expected a whole number >= 1, got 0"},
        {"--jobs 99999999999",
         "glrefcheck: --jobs: expected a whole number >= 1 (at most "
         "2147483647), got 99999999999"},
        {"--jobs 1e400", "glrefcheck: --jobs: expected a whole number >= 1, got \"1e400\""}}) {
    const Outcome o = glrefcheck(std::string("run cases/face_on.json ") + args);
    EXPECT_EQ(o.exit_code, 2) << args;
    EXPECT_EQ(o.err, std::string(expected) + " (see --help)\n");
  }
  const std::string two = "run cases/face_on.json cases/viewport_tiny.json --out '";
  const Outcome capped = glrefcheck(two + (dir_ / "capped").string() + "' --jobs 100000");
  ASSERT_EQ(capped.exit_code, 0) << capped.out << capped.err;
  EXPECT_NE(capped.out.find("note: --jobs 100000: " + std::to_string(cores()) + " worker"),
            std::string::npos)
      << capped.out;
  EXPECT_EQ(results_of(dir_ / "capped")["run"]["jobs"], cores());
  // Never more workers than cases: one log per worker slot.
  size_t logs = 0;
  for (const auto& e : fs::directory_iterator(dir_ / "capped/logs"))
    logs += e.path().filename().string().starts_with("worker-");
  EXPECT_LE(logs, 2u);

  const Outcome forced = glrefcheck(two + (dir_ / "forced").string() + "' --jobs " +
                                    std::to_string(cores() + 1) + " --jobs-force");
  ASSERT_EQ(forced.exit_code, 0) << forced.out << forced.err;
  EXPECT_EQ(forced.out.find("note: --jobs"), std::string::npos) << forced.out;
  EXPECT_EQ(results_of(dir_ / "forced")["run"]["jobs"], cores() + 1);
  EXPECT_NE(forced.out.find("| 2 workers\n"), std::string::npos) << forced.out;
}

// A comma in a case file's stem broke results.csv and failures.csv (and with them the next
// --baseline); such names are refused before anything runs, and so are other CSV-breaking ones.
TEST_F(RunOptions, CaseNamesThatBreakTheCsvAreRefused) {
  for (const std::string name : {"a,Fail", "say \"hi\"", "tab\there", "new\nline"}) {
    const fs::path cases = dir_ / "cases";
    fs::remove_all(cases);
    fs::create_directories(cases);
    fs::copy_file(fs::path(GLRC_SOURCE_DIR) / "cases/face_on.json", cases / (name + ".json"));
    const Outcome o =
        glrefcheck("run '" + cases.string() + "' --jobs 1 --out '" + (dir_ / "out").string() + "'");
    EXPECT_EQ(o.exit_code, 2) << name << ": " << o.out << o.err;
    EXPECT_EQ(o.out, "") << name;
    EXPECT_EQ(lines(o.err), 1u) << name << ": " << o.err;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << name;
  }
  // The comma, which nothing else refuses, by name.
  const fs::path cases = dir_ / "comma";
  fs::create_directories(cases);
  fs::copy_file(fs::path(GLRC_SOURCE_DIR) / "cases/face_on.json", cases / "a,Fail.json");
  const Outcome o =
      glrefcheck("run '" + cases.string() + "' --out '" + (dir_ / "out").string() + "'");
  EXPECT_NE(o.err.find("a,Fail.json: expected a case name fit for results.csv, got \"a,Fail\", "
                       "which holds a comma"),
            std::string::npos)
      << o.err;
}

// A path that is not UTF-8 aborted the run mid-way with a raw JSON library message; results.json
// and the journal cannot hold it, so it is refused before the run starts.
TEST_F(RunOptions, PathsThatAreNotUtf8AreRefusedUpFront) {
  const Outcome out =
      glrefcheck("run cases/face_on.json --out '" + (dir_ / "o\xff").string() + "'");
  EXPECT_EQ(out.exit_code, 2) << out.out << out.err;
  EXPECT_EQ(out.out, "");
  EXPECT_EQ(lines(out.err), 1u) << out.err;
  EXPECT_NE(out.err.find("--out: expected UTF-8 text, got \"" + dir_.string() + "/o\\xff\""),
            std::string::npos)
      << out.err;
  EXPECT_FALSE(fs::exists(dir_ / "o\xff"));

  const fs::path cases = dir_ / "cases";
  fs::create_directories(cases);
  fs::copy_file(fs::path(GLRC_SOURCE_DIR) / "cases/face_on.json", cases / "x\xff.json");
  const Outcome c =
      glrefcheck("run '" + cases.string() + "' --out '" + (dir_ / "out").string() + "'");
  EXPECT_EQ(c.exit_code, 2) << c.out << c.err;
  EXPECT_EQ(c.out, "");  // nothing ran
  EXPECT_EQ(lines(c.err), 1u) << c.err;
  // Case search refuses it, naming the byte.
  EXPECT_NE(c.err.find("expected a path in UTF-8"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("0xFF"), std::string::npos) << c.err;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

}  // namespace

namespace {

// Issue 45: two glrefchecks writing into one folder at once. The first holds it (a worker
// stalled mid-run); a second run, fuzz, merge, diff or identify into it, and a resume of it, is
// refused with one line naming the holder, and nothing of the first's is touched. Once the
// first is killed (SIGKILL: no chance to let go), its lock is free, and a resume finishes the run.
TEST_F(RunFolder, ASecondGlrefcheckIntoAHeldFolderIsRefused) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid";
  Outcome first;
  std::thread run([&] {
    first =
        glrefcheck("run " + kCases + " --jobs 1 --out '" + out.string() + "'" +
                   proxied_workers("--stall-case attr_tiny --pidfile '" + pidfile.string() + "'"));
  });
  const pid_t worker = wait_for_pid(pidfile);
  ASSERT_GT(worker, 0);
  const pid_t runner = parent_of(worker);
  ASSERT_GT(runner, 1);
  const auto before = snapshot(out);
  const std::string holder = "is in use by another glrefcheck (pid " + std::to_string(runner) +
                             ": glrefcheck run --filter";
  for (const std::string& second :
       {"run " + kCases + " --jobs 1 --out '" + out.string() + "'",
        "run --resume '" + out.string() + "'", "fuzz --count 1 --out '" + out.string() + "'",
        "diff cases/face_on.json --out '" + out.string() + "'",
        "identify --out '" + out.string() + "'"}) {
    SCOPED_TRACE(second);
    const Outcome o = glrefcheck(second);
    EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
    EXPECT_EQ(lines(o.err), 1u) << o.err;
    EXPECT_NE(o.err.find(holder), std::string::npos) << o.err;
  }
  EXPECT_EQ(snapshot(out), before);
  ASSERT_EQ(kill(runner, SIGKILL), 0);
  run.join();
  EXPECT_TRUE(glrc::test::ended_within(worker, std::chrono::seconds(10)));
  const Outcome resumed = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.out << resumed.err;
  EXPECT_EQ(results_of(out)["summary"]["total"], 8);
}

// Two resumes of one interrupted run at once: the second is refused, the first checks the rest
// once (one journal line per case).
TEST_F(RunFolder, TwoResumesAtOnceCheckTheRestOnce) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid", pidfile2 = dir_ / "w2.pid";
  std::thread run([&] {
    glrefcheck("run " + kCases + " --jobs 1 --out '" + out.string() + "'" +
               proxied_workers("--stall-case attr_offset_small_gradient --pidfile '" +
                               pidfile.string() + "'"));
  });
  pid_t worker = wait_for_pid(pidfile);
  ASSERT_GT(worker, 0);
  ASSERT_EQ(kill(parent_of(worker), SIGINT), 0);
  run.join();
  Outcome resumed;
  std::thread resume([&] {
    resumed = glrefcheck(
        "run --resume '" + out.string() + "'" +
        proxied_workers("--stall-case viewport_offset --pidfile '" + pidfile2.string() + "'"));
  });
  worker = wait_for_pid(pidfile2);
  ASSERT_GT(worker, 0);
  const Outcome second = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(second.exit_code, 2) << second.out << second.err;
  EXPECT_NE(second.err.find("--resume " + out.string() + ": \"" + out.string() +
                            "\" is in use by another glrefcheck"),
            std::string::npos)
      << second.err;
  ASSERT_EQ(kill(parent_of(worker), SIGINT), 0);
  resume.join();
  const Outcome last = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(last.exit_code, 0) << last.out << last.err;
  // The options line, a GL line per start, and each case once.
  std::map<std::string, int> seen;
  std::istringstream journal(read(out / "journal.jsonl"));
  size_t results = 0;
  for (std::string line; std::getline(journal, line);) {
    const auto j = nlohmann::json::parse(line);
    if (j.contains("result")) ++results, ++seen[j["result"]["name"].get<std::string>()];
  }
  EXPECT_EQ(results, 8u);
  EXPECT_EQ(seen.size(), 8u);
}

// `--out proj/o1` made proj/ on the way: not an output the user named, so not marked, and a later
// run into proj/ leaves the cases/ a person put there alone (it is refused).
TEST_F(RunFolder, AParentMadeOnTheWayIsNotMarked) {
  const fs::path proj = dir_ / "proj";
  ASSERT_EQ(glrefcheck("run cases/face_on.json --jobs 1 --out '" + (proj / "o1").string() + "'")
                .exit_code,
            0);
  EXPECT_TRUE(fs::exists(proj / "o1" / ".glrefcheck"));
  EXPECT_FALSE(fs::exists(proj / ".glrefcheck"));
  fs::create_directories(proj / "cases");
  std::ofstream(proj / "cases" / "mine.json") << "{}";
  const Outcome o = glrefcheck("run cases/face_on.json --jobs 1 --out '" + proj.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_EQ(read(proj / "cases" / "mine.json"), "{}");
}

// A second diff into one folder: the first case's images are gone, the second's are all there.
TEST_F(RunFolder, DiffClearsItsEarlierImages) {
  const fs::path out = dir_ / "d";
  ASSERT_LE(
      glrefcheck("diff cases/attr_mixed_magnitudes.json --out '" + out.string() + "'").exit_code,
      1);
  const auto first = snapshot(out);
  ASSERT_GT(first.size(), 3u);
  std::ofstream(out / "notes.txt") << "mine";  // not diff's: stays
  ASSERT_LE(glrefcheck("diff cases/face_on.json --out '" + out.string() + "'").exit_code, 1);
  const auto second = snapshot(out);
  // The list: a stamped header, then "<digest> <name>" per image.
  std::ifstream manifest(out / ".glrefcheck-diff-images");
  std::string line;
  ASSERT_TRUE(std::getline(manifest, line));
  EXPECT_TRUE(line.starts_with("# glrefcheck diff glrefcheck-sha256:")) << line;
  size_t listed = 0;
  for (; std::getline(manifest, line); ++listed) {
    EXPECT_TRUE(line.starts_with("sha256:")) << line;
    EXPECT_TRUE(fs::exists(out / line.substr(line.find(' ') + 1))) << line;
  }
  EXPECT_GT(listed, 0u);
  // Every image there is the second diff's (attr_mixed_magnitudes has channels face_on has not).
  const std::string listed_names = read(out / ".glrefcheck-diff-images");
  size_t images = 0;
  for (const auto& [name, text] : second)
    if (name.ends_with(".png") || name.ends_with(".exr")) {
      ++images;
      EXPECT_NE(listed_names.find(name + "\n"), std::string::npos)
          << name << " is the first diff's, left beside the second's";
    }
  EXPECT_EQ(images, listed);
  // The first case's varying (m) is not the second's (color): its images were all deleted.
  size_t gone = 0;
  for (const auto& [name, text] : first)
    gone += name.starts_with("m.") && !second.count(name);
  EXPECT_GT(gone, 0u);
  EXPECT_EQ(read(out / "notes.txt"), "mine");
}

// Issue 45: --resume mixed in case files edited after the interrupt (a git pull is enough), and
// kept the later of two journal lines for one case with different verdicts, silently.
TEST_F(RunFolder, ResumeRefusesEditedCasesAndConflictingJournalLines) {
  const fs::path cases = dir_ / "cases", out = dir_ / "out", pidfile = dir_ / "worker.pid";
  fs::create_directories(cases);
  for (const char* name : {"face_on", "viewport_tiny", "attr_tiny"})
    fs::copy_file(fs::path(GLRC_SOURCE_DIR) / "cases" / (std::string(name) + ".json"),
                  cases / (std::string(name) + ".json"));
  std::thread run([&] {
    glrefcheck("run '" + cases.string() + "' --jobs 1 --out '" + out.string() + "'" +
               proxied_workers("--stall-case viewport_tiny --pidfile '" + pidfile.string() + "'"));
  });
  const pid_t worker = wait_for_pid(pidfile);
  ASSERT_GT(worker, 0);
  ASSERT_EQ(kill(parent_of(worker), SIGINT), 0);
  run.join();
  const std::string journal = read(out / "journal.jsonl");
  // attr_tiny was checked: edit it, as a pull would.
  std::string text = read(cases / "attr_tiny.json");
  text.insert(text.find("\"description\": \"") + 16, "Edited: ");
  std::ofstream(cases / "attr_tiny.json") << text;
  Outcome o = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_EQ(lines(o.err), 1u) << o.err;
  EXPECT_NE(o.err.find("1 case file changed since the run began (" +
                       (cases / "attr_tiny.json").string() + "): start a new run"),
            std::string::npos)
      << o.err;
  EXPECT_EQ(read(out / "journal.jsonl"), journal);
  // Back as it was, but a second line for the first case with another verdict.
  fs::copy_file(fs::path(GLRC_SOURCE_DIR) / "cases/attr_tiny.json", cases / "attr_tiny.json",
                fs::copy_options::overwrite_existing);
  std::istringstream in(journal);
  std::string line, first_result;
  while (std::getline(in, line) && first_result.empty())
    if (line.find("\"result\"") != std::string::npos) first_result = line;
  ASSERT_FALSE(first_result.empty()) << journal;
  auto conflicting = nlohmann::json::parse(first_result);
  conflicting["result"]["status"] = "Fail", conflicting["result"]["outcome"] = "Fail";
  std::ofstream(out / "journal.jsonl", std::ios::app) << conflicting.dump() << "\n";
  o = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_NE(o.err.find("two results for one case"), std::string::npos) << o.err;
}

}  // namespace
