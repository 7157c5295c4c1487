// The worker pool (cli/workers/pool.*) on fake workers: tests/tools/fake_worker.py speaks the
// protocol without GL and fails where it is told to, so every way a worker can go wrong is
// checked here in milliseconds, apart from any driver. The real workers' crash, timeout and
// interrupt handling is tested end to end in test_workers.cpp and test_run_folder.cpp.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <stdexcept>

#include "cli/workers/pool.hpp"
#include "cli/workers/process.hpp"
#include "cli/workers/workers.hpp"
#include "report/report.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using glrc::Case;
using glrc::CaseResult;
using glrc::Status;
using glrc::cli::WorkerSettings;

const std::string kFake = std::string(GLRC_SOURCE_DIR) + "/tests/tools/fake_worker.py";

class WorkerPool : public glrc::test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    for (const char* name : {"alpha", "beta", "gamma", "delta", "epsilon"}) {
      Case c;
      c.name = name;
      cases_.push_back(c);
    }
    for (const Case& c : cases_)
      pointers_.push_back(&c);
    s_.jobs = 2;
    s_.timeout = 2;
    s_.log_dir = dir_ / "logs";
    s_.model = glrc::cli::ModelChoice{glrc::Model{}, "test"};
  }

  // Runs the cases on fake workers started with `flags`; the results by case name.
  std::map<std::string, CaseResult> run(const std::vector<std::string>& flags) {
    s_.command = {kFake};
    s_.command.insert(s_.command.end(), flags.begin(), flags.end());
    std::map<std::string, CaseResult> results;
    glrc::cli::run_in_workers(
        pointers_, options_, s_,
        [&](const glrc::gl::GlInfo& gl, const glrc::cli::ModelChoice& m) {
          renderer_ = gl.renderer;
          model_source_ = m.source;
          model_ = m.model;
        },
        [&](size_t k, CaseResult r) {
          EXPECT_EQ(r.name, cases_.at(k).name) << "a result reached the wrong case";
          EXPECT_TRUE(results.emplace(r.name, r).second) << r.name << " twice";
        });
    return results;
  }

  std::vector<Case> cases_;
  std::vector<const Case*> pointers_;
  glrc::cli::Options options_;
  WorkerSettings s_;
  std::string renderer_, model_source_;
  glrc::Model model_;
};

TEST_F(WorkerPool, EveryCaseGetsItsResult) {
  const auto r = run({});
  ASSERT_EQ(r.size(), 5u);
  for (const auto& [name, result] : r)
    EXPECT_EQ(result.status, Status::pass) << name;
  EXPECT_EQ(renderer_, "fake renderer");  // from the first hello
  EXPECT_EQ(model_source_, "test");
}

TEST_F(WorkerPool, ACrashIsThatCaseOnlyAndQuotesTheLog) {
  const auto r = run({"--crash-at", "gamma"});
  ASSERT_EQ(r.size(), 5u);
  EXPECT_EQ(r.at("gamma").status, Status::crash);
  EXPECT_EQ(r.at("gamma").outcome, Status::crash);
  EXPECT_NE(r.at("gamma").message.find("worker killed by signal 6"), std::string::npos)
      << r.at("gamma").message;
  EXPECT_NE(r.at("gamma").message.find("its log ends: "), std::string::npos);
  EXPECT_NE(r.at("gamma").message.find("fake worker: checking gamma"), std::string::npos)
      << r.at("gamma").message;
  for (const char* other : {"alpha", "beta", "delta", "epsilon"})
    EXPECT_EQ(r.at(other).status, Status::pass) << other;
}

TEST_F(WorkerPool, AHangIsATimeoutAfterTimeoutSeconds) {
  s_.timeout = 1;
  const auto start = glrc::cli::Clock::now();
  const auto r = run({"--hang-at", "beta"});
  ASSERT_EQ(r.size(), 5u);
  EXPECT_EQ(r.at("beta").status, Status::timeout);
  EXPECT_EQ(r.at("beta").message, "no result after 1 s (--timeout); worker killed");
  EXPECT_GE(r.at("beta").seconds, 1.0);
  EXPECT_GE(glrc::cli::seconds_since(start), 1.0);
  EXPECT_EQ(r.at("epsilon").status, Status::pass);
}

TEST_F(WorkerPool, NoContextStopsTheRunWithTheWorkersLine) {
  try {
    run({"--no-context"});
    FAIL() << "no error";
  } catch (const glrc::cli::InputError& e) {
    EXPECT_STREQ(e.what(), "fake: no GL context here");
  }
}

TEST_F(WorkerPool, AWorkerThatDiesStartingIsABrokenDriverNotACase) {
  try {
    run({"--die-at-start", "--log-at-start", "libEGL warning: no driver"});
    FAIL() << "no error";
  } catch (const glrc::cli::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "a GL worker exited with code 1 before it could make a GL context; its log ends: "
              "libEGL warning: no driver");
  }
}

TEST_F(WorkerPool, SomethingNotJsonStopsTheRunQuotingIt) {
  try {
    run({"--garbage-at", "alpha"});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "a worker sent something that is not JSON: this is not JSON");
  }
}

TEST_F(WorkerPool, AResultForACaseNotGivenIsRefused) {
  try {
    run({"--wrong-index-at", "delta"});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("a worker sent a result for a case it was not given: ", 0), 0u)
        << e.what();
  }
}

TEST_F(WorkerPool, HeatmapsNotWrittenKeepTheVerdict) {
  std::map<size_t, std::string> lost;
  s_.images_lost = [&](size_t k, const std::string& why) { lost[k] = why; };
  s_.images = [](const Case& c) { return c.name != "alpha"; };
  const auto r = run({"--images-fail", "beta"});
  EXPECT_EQ(r.at("beta").status, Status::fail);
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_EQ(lost.at(1), "heatmaps not written: fake: disk full");
  // A case whose heatmaps nobody wants is not asked for them.
  lost.clear();
  const auto again = run({"--images-fail", "alpha"});
  EXPECT_EQ(again.at("alpha").status, Status::fail);
  EXPECT_TRUE(lost.empty());
}

// Result lines as the real worker writes them (--compact), which the runner reads without
// parsing them whole: the same results, the same refusals, the same heatmap hand-off.
TEST_F(WorkerPool, CompactResultLinesAreReadAsTheOthers) {
  const auto plain = run({});
  const auto compact = run({"--compact"});
  ASSERT_EQ(compact.size(), cases_.size());
  for (const auto& [name, r] : compact) {
    EXPECT_EQ(r.status, Status::pass) << name;
    EXPECT_EQ(glrc::report::case_result_json(r), glrc::report::case_result_json(plain.at(name)));
  }
  try {
    run({"--compact", "--wrong-index-at", "gamma"});
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("a worker sent a result for a case it was not given: ", 0), 0u)
        << e.what();
  }
  std::map<size_t, std::string> lost;
  s_.images_lost = [&](size_t k, const std::string& why) { lost[k] = why; };
  s_.images = [](const Case&) { return true; };
  const auto r = run({"--compact", "--images-fail", "beta"});
  EXPECT_EQ(r.at("beta").status, Status::fail);
  EXPECT_EQ(lost, (std::map<size_t, std::string>{{1, "heatmaps not written: fake: disk full"}}));
}

TEST_F(WorkerPool, TheFirstWorkerIdentifiesAndTheModelIsCached) {
  s_.model.reset();
  setenv("XDG_CACHE_HOME", (dir_ / "cache").c_str(), 1);
  auto r = run({});
  EXPECT_EQ(model_source_, "identify");
  EXPECT_EQ(model_.subpixel_bits, 4);
  EXPECT_EQ(model_.planes, glrc::Planes::snapped);
  EXPECT_EQ(model_.tie_break, glrc::TieBreak::top_left);
  EXPECT_EQ(r.size(), 5u);
  r = run({"--identify-fails"});  // the cache answers: nobody is asked
  EXPECT_EQ(model_source_, "identify (cached)");
  EXPECT_EQ(model_.subpixel_bits, 4);
  unsetenv("XDG_CACHE_HOME");
}

TEST_F(WorkerPool, AFailedIdentificationFallsBackAndSaysWhy) {
  s_.model.reset();
  setenv("XDG_CACHE_HOME", (dir_ / "cache").c_str(), 1);
  const auto r = run({"--identify-fails"});
  unsetenv("XDG_CACHE_HOME");
  EXPECT_EQ(model_source_, "default (identify failed: fake: the probes drew nothing)");
  EXPECT_EQ(r.size(), 5u);
  EXPECT_FALSE(fs::exists(dir_ / "cache" / "glrefcheck" / "models.json"));
}

TEST_F(WorkerPool, AWrapperRunsTheWorkerAsTypedOnAShell) {
  s_.wrapper = "env GLRC_UNUSED='a b'";
  WorkerSettings wrapped;
  wrapped.command = {"/bin/w", "x y"};
  EXPECT_EQ(glrc::cli::worker_argv(wrapped), (std::vector<std::string>{"/bin/w", "x y"}));
  wrapped.wrapper = "valgrind -q";
  EXPECT_EQ(glrc::cli::worker_argv(wrapped),
            (std::vector<std::string>{"/bin/sh", "-c", "exec valgrind -q \"$@\"",
                                      "glrefcheck-worker", "/bin/w", "x y"}));
  const auto r = run({"--crash-at", "alpha"});
  EXPECT_EQ(r.at("alpha").status, Status::crash);
  EXPECT_EQ(r.at("beta").status, Status::pass);
}

}  // namespace

namespace {

// GL workers get glibc's huge-page malloc, added to what the user's GLIBC_TUNABLES already says
// and never overriding a hugetlb setting of theirs.
TEST(WorkerEnvironment, HugePageMallocIsAddedToTheUsersTunables) {
  const char* before = std::getenv("GLIBC_TUNABLES");
  const std::string saved = before ? before : "";
  using glrc::cli::huge_page_malloc_tunable;
  unsetenv("GLIBC_TUNABLES");
  EXPECT_EQ(huge_page_malloc_tunable().first, "GLIBC_TUNABLES");
  EXPECT_EQ(huge_page_malloc_tunable().second, "glibc.malloc.hugetlb=1");
  setenv("GLIBC_TUNABLES", "glibc.malloc.arena_max=2", 1);
  EXPECT_EQ(huge_page_malloc_tunable().second, "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
  setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=0", 1);
  EXPECT_EQ(huge_page_malloc_tunable().second, "glibc.malloc.hugetlb=0");
  if (before)
    setenv("GLIBC_TUNABLES", saved.c_str(), 1);
  else
    unsetenv("GLIBC_TUNABLES");
}

// And jemalloc's (the programs' allocator where linked): thp:always added to the user's
// MALLOC_CONF, never overriding a thp setting of theirs.
TEST(WorkerEnvironment, HugePageJemallocConfIsAddedToTheUsersConf) {
  const char* before = std::getenv("MALLOC_CONF");
  const std::string saved = before ? before : "";
  using glrc::cli::huge_page_jemalloc_conf;
  unsetenv("MALLOC_CONF");
  EXPECT_EQ(huge_page_jemalloc_conf().first, "MALLOC_CONF");
  EXPECT_EQ(huge_page_jemalloc_conf().second, "thp:always");
  setenv("MALLOC_CONF", "narenas:2", 1);
  EXPECT_EQ(huge_page_jemalloc_conf().second, "narenas:2,thp:always");
  setenv("MALLOC_CONF", "thp:never", 1);
  EXPECT_EQ(huge_page_jemalloc_conf().second, "thp:never");
  if (before)
    setenv("MALLOC_CONF", saved.c_str(), 1);
  else
    unsetenv("MALLOC_CONF");
}
}  // namespace

namespace {

// fuzz's pool: workers kept between batches. Each batch gets its own results, in order; the
// workers of one batch check the next (no worker starts again unless one died); a crash is that
// case's, and the next batch goes on.
TEST_F(WorkerPool, ASessionChecksBatchAfterBatchOnTheSameWorkers) {
  s_.command = {kFake, "--crash-at", "beta", "--log-at-start", "worker started"};
  int starts = 0;
  glrc::cli::WorkerSession session(
      options_, s_, [&](const glrc::gl::GlInfo&, const glrc::cli::ModelChoice&) { ++starts; });
  const auto names = [](const std::vector<CaseResult>& results) {
    std::string out;
    for (const CaseResult& r : results)
      out += r.name + ":" + std::string(glrc::to_string(r.status)) + " ";
    return out;
  };
  EXPECT_EQ(names(session.check({&cases_[0], &cases_[2], &cases_[3]})),
            "alpha:Pass gamma:Pass delta:Pass ");
  EXPECT_EQ(names(session.check({&cases_[4], &cases_[3], &cases_[0]})),
            "epsilon:Pass delta:Pass alpha:Pass ");
  // Two workers at most were started for both batches: none again for the second.
  int started = 0;
  for (const auto& log : fs::directory_iterator(dir_ / "logs")) {
    std::ifstream in(log.path());
    for (std::string line; std::getline(in, line);)
      started += line == "worker started";
  }
  EXPECT_GE(started, 1);
  EXPECT_LE(started, 2);
  EXPECT_EQ(names(session.check({&cases_[1], &cases_[4]})), "beta:Crash epsilon:Pass ");
  EXPECT_EQ(names(session.check({&cases_[2]})), "gamma:Pass ");
  EXPECT_EQ(starts, 1);  // the model is chosen once, for every batch
  EXPECT_FALSE(session.interrupted());
}

}  // namespace
