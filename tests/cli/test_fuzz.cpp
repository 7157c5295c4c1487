// glrefcheck fuzz as a user runs it, on the system's llvmpipe through OSMesa: a campaign finds
// Mesa 22.3.6's clipper NaN (a noperspective varying on a triangle with an edge on x = w_c cut
// by y = w_c, cases/known-failures.txt) and shrinks it; --replay --emit writes the very case the
// campaign drew; bad input is one line and exit 2. The campaign's logic without GL is in
// tests/campaign/.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <thread>
#include <utility>
#include <vector>

#include "campaign/generators.hpp"
#include "casefile/casefile.hpp"
#include "casefile/write.hpp"
#include "report/stamp.hpp"
#include "tests/support/glrefcheck_process.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

using glrc::test::glrefcheck;

class Fuzz : public glrc::test::TempDirTest {};

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST_F(Fuzz, FindsAndShrinksTheClipperNaN) {
  const auto out = dir_ / "campaign";
  const auto r =
      glrefcheck("fuzz --seed 1 --count 12 --generator clip --jobs 2 --out '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("new failure non_finite/noperspective in clip_1_7"), std::string::npos)
      << r.out;
  const auto file = out / "failures" / "non_finite_noperspective.json";
  ASSERT_TRUE(std::filesystem::exists(file)) << r.out;
  const glrc::Case minimal = glrc::casefile::load(file);
  EXPECT_LE(minimal.triangles.size(), 2u);
  ASSERT_EQ(minimal.varyings.size(), 1u);
  EXPECT_EQ(minimal.varyings[0].interpolation, glrc::Interpolation::noperspective);
  EXPECT_NE(minimal.description.find("--replay 1:7"), std::string::npos) << minimal.description;

  const auto results = nlohmann::json::parse(read(out / "results.json"));
  EXPECT_EQ(results["stats"]["cases"], 12);
  EXPECT_GT(results["stats"]["triangles"].get<int>(), 12);
  EXPECT_EQ(results["campaign"]["seed"], 1);
  EXPECT_EQ(results["run"]["driver"], "llvmpipe");
  bool listed = false;
  for (const auto& f : results["failures"])
    if (f["signature"] == "non_finite/noperspective") {
      listed = true;
      EXPECT_EQ(f["index"], 7);
      EXPECT_EQ(f["file"], "failures/non_finite_noperspective.json");
      EXPECT_EQ(f["replay"], "glrefcheck fuzz --generator clip --replay 1:7 --emit clip_1_7.json");
    }
  EXPECT_TRUE(listed) << results.dump(2);
  EXPECT_NE(read(out / "results.csv").find("non_finite_noperspective,Fail,"), std::string::npos);
  // The page of the minimal failures, with the heatmaps `run` would write for them.
  EXPECT_TRUE(std::filesystem::exists(out / "cases" / "non_finite_noperspective" / "coverage.png"));
  const std::string page = read(out / "report.html");
  EXPECT_NE(page.find("non_finite_noperspective"), std::string::npos);
  EXPECT_NE(page.find("data:image/png"), std::string::npos);

  // The minimal case fails `run` the same way: NaN where the reference has a value.
  const auto run =
      glrefcheck("run '" + file.string() + "' --jobs 1 --out '" + (dir_ / "run").string() + "'");
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  EXPECT_NE(run.out.find("NaN/Inf"), std::string::npos) << run.out;
}

// SIGINT while a worker hangs on case 21: exit 130, and the campaign's results.json, CSV and
// page are written, marked interrupted, with the cases checked before it; the worker is gone.
TEST_F(Fuzz, AnInterruptedCampaignWritesWhatItChecked) {
  const auto out = dir_ / "campaign", pidfile = dir_ / "worker.pid";
  glrc::test::Outcome o;
  std::thread campaign([&] {
    o = glrefcheck("fuzz --seed 2 --count 64 --generator sizes --jobs 1 --no-shrink --out '" +
                   out.string() + "'" +
                   glrc::test::proxied_workers("--stall-case fuzz_sizes_2_21 --pidfile '" +
                                               pidfile.string() + "'"));
  });
  const pid_t worker = glrc::test::wait_for_pid(pidfile);
  ASSERT_GT(worker, 0) << "no worker reached fuzz_sizes_2_21";
  const pid_t runner = glrc::test::parent_of(worker);
  ASSERT_GT(runner, 1);
  ASSERT_EQ(kill(runner, SIGINT), 0);
  campaign.join();
  EXPECT_TRUE(glrc::test::ended_within(worker, std::chrono::seconds(10)))
      << "the worker outlived its runner";
  EXPECT_EQ(o.exit_code, 130) << o.out << o.err;
  const auto results = nlohmann::json::parse(read(out / "results.json"));
  EXPECT_EQ(results["stats"]["interrupted"], true) << results.dump(2);
  // Batches of 8 with one worker: the first two finished, the third held at case 21.
  const int checked = results["stats"]["cases"].get<int>();
  EXPECT_GE(checked, 16) << results.dump(2);
  EXPECT_LT(checked, 64) << results.dump(2);
  EXPECT_TRUE(std::filesystem::exists(out / "results.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "report.html"));
  // Issue 45: a campaign stopped by a signal is a run stopped by one: recorded as such, said
  // so, and refused by merge.
  EXPECT_EQ(results["run"]["interrupted"], true) << results.dump(2);
  EXPECT_EQ(results["run"]["total_cases"], checked) << results.dump(2);
  EXPECT_NE(o.out.find("interrupted by SIGINT after " + std::to_string(checked) + " cases"),
            std::string::npos)
      << o.out;
  const auto merged =
      glrefcheck("merge '" + out.string() + "' --out '" + (dir_ / "merged").string() + "'");
  EXPECT_EQ(merged.exit_code, 2) << merged.out << merged.err;
  EXPECT_NE(merged.err.find("an interrupted campaign shard"), std::string::npos) << merged.err;
}

TEST_F(Fuzz, AFailureTheBaselineListsIsKnownAndDoesNotFailTheCampaign) {
  std::ofstream(dir_ / "known.txt") << "# Mesa's clipper NaN\nnon_finite_noperspective,Fail\n";
  const auto out = dir_ / "campaign";
  const auto r = glrefcheck("fuzz --seed 1 --count 12 --generator clip --jobs 2 --baseline '" +
                            (dir_ / "known.txt").string() + "' --out '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("known failure non_finite/noperspective in clip_1_7"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("1 distinct failure (0 new)"), std::string::npos) << r.out;
  EXPECT_EQ(read(out / "results.csv").substr(0, 38), "non_finite_noperspective,ExpectedFail,");
  const auto results = nlohmann::json::parse(read(out / "results.json"));
  EXPECT_EQ(results["failures"][0]["known"], true);
}

// A campaign's results.json without what depends on timing.
nlohmann::json untimed(const std::filesystem::path& file) {
  nlohmann::json j = nlohmann::json::parse(read(file));
  j.erase("written_by");  // its stamp: of the file's text, timings included
  for (const char* key : {"seconds", "checking_seconds", "triangles_per_second"})
    j["stats"].erase(key);
  j["run"].erase("seconds");
  j["campaign"].erase("merged_shards");
  for (auto& f : j["failures"]) {
    f.erase("found_after_seconds");
    f["shrink"].erase("seconds");
    f["result"].erase("seconds");
  }
  return j;
}

TEST_F(Fuzz, ShardsMergeIntoTheUnshardedCampaign) {
  // Both shards meet the clipper NaN first (the first at index 18, the second at 7): the merge
  // keeps index 7's, as the unsharded campaign does.
  const std::string campaign = "fuzz --seed 1 --count 40 --generator clip --jobs 2";
  const auto whole = dir_ / "whole", a = dir_ / "a", b = dir_ / "b", merged = dir_ / "merged";
  ASSERT_EQ(glrefcheck(campaign + " --out '" + whole.string() + "'").exit_code, 1);
  ASSERT_EQ(glrefcheck(campaign + " --fraction 2 --fraction-start 2 --out '" + b.string() + "'")
                .exit_code,
            1);
  ASSERT_EQ(glrefcheck(campaign + " --fraction 2 --fraction-start 1 --out '" + a.string() + "'")
                .exit_code,
            1);
  const auto r =
      glrefcheck("merge '" + a.string() + "' '" + b.string() + "' --out '" + merged.string() + "'");
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("merged 2 campaign shards: 40 cases"), std::string::npos) << r.out;
  EXPECT_EQ(untimed(merged / "results.json")["failures"][0]["index"], 7);
  EXPECT_EQ(untimed(merged / "results.json"), untimed(whole / "results.json"));
  for (const auto& f : std::filesystem::directory_iterator(whole / "failures"))
    EXPECT_EQ(read(merged / "failures" / f.path().filename()), read(f.path())) << f.path();
  EXPECT_TRUE(std::filesystem::exists(merged / "report.html"));

  // Shards of two campaigns, or one shard twice, are no campaign.
  const auto other = dir_ / "other";
  ASSERT_NE(glrefcheck("fuzz --seed 2 --count 40 --generator clip --jobs 2 --fraction 2 "
                       "--fraction-start 2 --out '" +
                       other.string() + "'")
                .exit_code,
            2);
  const auto mixed = glrefcheck("merge '" + a.string() + "' '" + other.string() + "' --out '" +
                                (dir_ / "m2").string() + "'");
  EXPECT_EQ(mixed.exit_code, 2);
  EXPECT_NE(mixed.err.find("campaign.seed: expected 1 as the first shard, got 2"),
            std::string::npos)
      << mixed.err;
  const auto twice = glrefcheck("merge '" + a.string() + "' '" + a.string() + "' --out '" +
                                (dir_ / "m3").string() + "'");
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.err.find("campaign.fraction_start: expected one of 1..2"), std::string::npos)
      << twice.err;
  // Shards judged otherwise (issue 45: --strict-coverage was recorded nowhere) are no campaign.
  const auto strict = dir_ / "strict";
  glrefcheck(campaign + " --strict-coverage --fraction 2 --fraction-start 2 --out '" +
             strict.string() + "'");
  const auto judged = glrefcheck("merge '" + a.string() + "' '" + strict.string() + "' --out '" +
                                 (dir_ / "m4").string() + "'");
  EXPECT_EQ(judged.exit_code, 2) << judged.out << judged.err;
  // By the input's name and both values (it printed the inputs' JSON, cut at 80 characters).
  EXPECT_NE(judged.err.find(strict.string() +
                            ": expected shards judged alike, got "
                            "strict_coverage true where " +
                            a.string() + " has false"),
            std::string::npos)
      << judged.err;
  // A shard shrunk otherwise (--no-shrink) has other minimal cases: refused too.
  const auto unshrunk = dir_ / "unshrunk";
  const auto not_shrunk = glrefcheck(
      campaign + " --no-shrink --fraction 2 --fraction-start 2 --out '" + unshrunk.string() + "'");
  // Its minimal case was never shrunk, and says so (it said "and shrunk").
  EXPECT_NE(not_shrunk.out.find("  not shrunk (--no-shrink): "), std::string::npos)
      << not_shrunk.out;
  EXPECT_NE(read(unshrunk / "failures/non_finite_noperspective.json")
                .find("), not shrunk (--no-shrink): "),
            std::string::npos);
  const auto shrink = glrefcheck("merge '" + a.string() + "' '" + unshrunk.string() + "' --out '" +
                                 (dir_ / "m5").string() + "'");
  EXPECT_EQ(shrink.exit_code, 2) << shrink.out << shrink.err;
  EXPECT_NE(shrink.err.find("campaign.shrink: expected true as the first shard, got false"),
            std::string::npos)
      << shrink.err;
  // Hand-edited stats (the hostile campaign's W4: a negative count, a sum that wraps, more
  // failing cases than cases were merged as given): one line each, and the last good merge stays.
  const std::string good = read(merged / "results.json");
  using Edit = std::function<void(nlohmann::json&)>;
  const std::vector<std::pair<Edit, std::string>> forgeries = {
      {[](nlohmann::json& j) { j["stats"]["cases"] = -5; },
       "stats.cases: expected a whole number, got -5"},
      {[](nlohmann::json& j) {
         j["stats"]["failing_cases"] = j["stats"]["cases"].get<uint64_t>() + 1;
       },
       "stats.failing_cases: expected at most stats.cases (20), got 21"},
      {[](nlohmann::json& j) { j["stats"]["triangles"] = UINT64_MAX; },
       "stats.triangles: expected a count the shards' sum can hold"},
      {[](nlohmann::json& j) { j["stats"]["seconds"] = -1.5; },
       "stats.seconds: expected a finite number of seconds, 0 or more, got -1.5"},
      {[](nlohmann::json& j) {
         j["stats"]["checking_seconds"] = j["stats"]["seconds"].get<double>() + 1;
       },
       "stats.checking_seconds: expected at most stats.seconds"},
      {[](nlohmann::json& j) { j["failures"][0]["cases"] = 0; },
       "failures[0].cases: expected 1 to stats.failing_cases"},
      {[](nlohmann::json& j) { j["failures"].push_back(j["failures"][0]); },
       ".signature: expected a failure no other of the shard's has"},
      {[](nlohmann::json& j) { j["failures"][0]["index"] = 8; },
       "failures[0].index: expected an index of shard 2 of 2, got 8"},
      // Every field fine, but a failure taken out by hand (the sixth hostile campaign): the
      // shard's stamp no longer holds.
      // A shard of a --count campaign holds every index of its shard (the seventh campaign:
      // one cut from 33 cases to 10 was merged as given).
      {[](nlohmann::json& j) { j["stats"]["cases"] = 21; },
       "stats.cases: expected 20 (shard 2 of 2 of a 40-case campaign), got 21"},
      {[](nlohmann::json& j) { j["failures"].erase(j["failures"].begin()); },
       "results.json: written_by: expected the stamp glrefcheck wrote to match the file's text"},
  };
  for (size_t k = 0; k < forgeries.size(); ++k) {
    const auto forged = dir_ / ("forged" + std::to_string(k));
    std::filesystem::copy(b, forged, std::filesystem::copy_options::recursive);
    auto j = nlohmann::json::parse(read(b / "results.json"));
    forgeries[k].first(j);
    std::ofstream(forged / "results.json") << j.dump(2);
    const auto o = glrefcheck("merge '" + a.string() + "' '" + forged.string() + "' --out '" +
                              merged.string() + "'");
    EXPECT_EQ(o.exit_code, 2) << k << o.out << o.err;
    EXPECT_NE(o.err.find(forgeries[k].second), std::string::npos) << k << ": " << o.err;
    EXPECT_EQ(read(merged / "results.json"), good) << k;
  }
  // A minimal case edited by hand in the shard the merge takes it from (the tenth campaign: it
  // was copied as the merged campaign's own, a case no campaign found): refused.
  {
    const auto edited = dir_ / "edited_case";
    std::filesystem::copy(b, edited, std::filesystem::copy_options::recursive);
    const auto file = edited / "failures/non_finite_noperspective.json";
    std::string text = read(file);
    ASSERT_NE(text.find("\"clip\": ["), std::string::npos) << text;
    EXPECT_EQ(glrefcheck("merge '" + a.string() + "' '" + edited.string() + "' --out '" +
                         merged.string() + "'")
                  .exit_code,
              1);
    text.replace(text.rfind("\"clip\": [") + 9, 1, "  ");
    std::ofstream(file) << text;
    const auto o = glrefcheck("merge '" + a.string() + "' '" + edited.string() + "' --out '" +
                              merged.string() + "'");
    EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
    EXPECT_NE(o.err.find("non_finite_noperspective.json: expected the failure's minimal case as "
                         "the shard's campaign wrote it"),
              std::string::npos)
        << o.err;
    EXPECT_EQ(read(merged / "results.json"), good);
  }
  // Without its stamp and its heatmaps (the seventh campaign): merged, and both said.
  {
    const auto bare = dir_ / "bare";
    std::filesystem::copy(b, bare, std::filesystem::copy_options::recursive);
    auto j = nlohmann::json::parse(read(bare / "results.json"));
    j.erase("written_by");
    std::ofstream(bare / "results.json") << j.dump(2);
    std::filesystem::remove_all(bare / "cases");
    const auto o = glrefcheck("merge '" + a.string() + "' '" + bare.string() + "' --out '" +
                              (dir_ / "merged_bare").string() + "'");
    EXPECT_EQ(o.exit_code, 1) << o.out << o.err;
    EXPECT_NE(o.err.find("holds no written_by stamp"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("the merged report.html shows none for it"), std::string::npos) << o.err;
  }
  // One case replayed is no shard (it recorded count 2 and passed for a campaign's).
  {
    const auto replay = glrefcheck("fuzz --generator clip --replay 1:1 --fraction 2 --out '" +
                                   (dir_ / "r").string() + "'");
    EXPECT_EQ(replay.exit_code, 2) << replay.out << replay.err;
    EXPECT_NE(replay.err.find("--replay: expected no --seed, --count, --time, --fraction"),
              std::string::npos)
        << replay.err;
    const auto one = dir_ / "one";
    ASSERT_LE(
        glrefcheck("fuzz --generator clip --replay 1:7 --out '" + one.string() + "'").exit_code, 1);
    const auto o =
        glrefcheck("merge '" + one.string() + "' --out '" + (dir_ / "m1").string() + "'");
    EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
    EXPECT_NE(o.err.find("campaign.replay: expected a campaign shard, got one case replayed"),
              std::string::npos)
        << o.err;
  }
  // A failure moved out of its shard ("ready for cases/"): refused before the last good merge
  // is cleared (the hostile campaign's D4).
  const auto kept = read(merged / "results.json");
  std::filesystem::rename(b / "failures/non_finite_noperspective.json", dir_ / "moved.json");
  const auto moved =
      glrefcheck("merge '" + a.string() + "' '" + b.string() + "' --out '" + merged.string() + "'");
  EXPECT_EQ(moved.exit_code, 2) << moved.out << moved.err;
  EXPECT_NE(moved.err.find("expected the failure's minimal case"), std::string::npos) << moved.err;
  EXPECT_EQ(read(merged / "results.json"), kept);
  EXPECT_TRUE(std::filesystem::exists(merged / "report.html"));
}

// A campaign judged by a driver model under the specification's allowance ran, every case an
// "error" failure; the rule is check::judging_problem's, said before any work as run says it.
TEST_F(Fuzz, OptionsThatCannotJudgeAreRefusedBeforeAnyWork) {
  const auto out = dir_ / "judged";
  auto o = glrefcheck("fuzz --model llvmpipe --count 2 --out '" + out.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_NE(o.err.find("--model llvmpipe: a driver model is judged bit for bit (exact) or by "
                       "fixed ULPs, not by the specification's allowance"),
            std::string::npos)
      << o.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  o = glrefcheck("fuzz --tolerance exact --tolerance-ulps 2 --count 2 --out '" + out.string() +
                 "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_NE(o.err.find("--tolerance exact: exact judges bit for bit"), std::string::npos) << o.err;
}

TEST_F(Fuzz, ReplayEmitsTheCaseTheCampaignDrew) {
  const auto file = dir_ / "clip_1_7.json";
  const auto r = glrefcheck("fuzz --generator clip --replay 1:7 --emit '" + file.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto* clip = glrc::campaign::find_generator("clip");
  const glrc::Case drawn = glrc::campaign::generate({clip}, 1, 7);
  // The case file, with its stamp first (written_by, which the case format ignores).
  const std::string text = read(file);
  const size_t eol = text.find('\n', 2);
  ASSERT_NE(eol, std::string::npos);
  EXPECT_EQ(text.substr(0, 2) + text.substr(eol + 1), glrc::casefile::to_case_file(drawn));
  EXPECT_EQ(text.find("  \"written_by\": \"glrefcheck fuzz glrefcheck-sha256:"), 2u) << text;
  EXPECT_TRUE(glrc::report::stamp_intact(text));
  EXPECT_EQ(glrc::casefile::to_case_file(glrc::casefile::load(file)),
            glrc::casefile::to_case_file(drawn));
  // Again over its own file; never over one it did not write, nor over one a person edited.
  EXPECT_EQ(
      glrefcheck("fuzz --generator clip --replay 1:8 --emit '" + file.string() + "'").exit_code, 0);
  std::ofstream(dir_ / "mine.json") << "{}";
  const auto refused =
      glrefcheck("fuzz --replay 1:8 --emit '" + (dir_ / "mine.json").string() + "'");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("--emit: expected a new file or one glrefcheck wrote"),
            std::string::npos)
      << refused.err;
  EXPECT_EQ(read(dir_ / "mine.json"), "{}");
  std::string edited = read(file);
  edited.replace(edited.find("\"description\": \"") + 16, 0, "Curated: ");
  std::ofstream(file) << edited;
  const auto after_edit =
      glrefcheck("fuzz --generator clip --replay 1:9 --emit '" + file.string() + "'");
  EXPECT_EQ(after_edit.exit_code, 2);
  EXPECT_NE(after_edit.err.find("which was changed since glrefcheck wrote it"), std::string::npos)
      << after_edit.err;
  EXPECT_EQ(read(file), edited);
  // A suite case whose hand-written description gives the command that made it (issue 45: the
  // words "glrefcheck fuzz" were taken for fuzz's own): kept.
  namespace fs = std::filesystem;
  const fs::path curated = dir_ / "steep_edge_interior.json";
  fs::copy_file(fs::path(GLRC_SOURCE_DIR) / "cases/steep_edge_interior.json", curated,
                fs::copy_options::overwrite_existing);
  const std::string before = read(curated);
  ASSERT_NE(before.find("glrefcheck fuzz"), std::string::npos);
  const auto suite =
      glrefcheck("fuzz --driver softpipe --generator mesh --replay 2027:2802 --emit '" +
                 curated.string() + "'");
  EXPECT_EQ(suite.exit_code, 2) << suite.out << suite.err;
  EXPECT_NE(suite.err.find("which glrefcheck did not write (it holds no stamp)"), std::string::npos)
      << suite.err;
  EXPECT_EQ(read(curated), before);
}

TEST_F(Fuzz, BadInputIsOneLineAndExit2) {
  const std::string out = " --out '" + (dir_ / "o").string() + "'";
  // Baselines whose lines would match nothing, or what they should not (issue 45).
  std::ofstream(dir_ / "crash.txt") << "gap,Crash\n";
  std::ofstream(dir_ / "signature.txt") << "non_finite/noperspective,Fail\n";
  std::ofstream(dir_ / "unknown.txt") << "value_bogus,Fail\n";
  const auto baseline = [&](const char* file) {
    return " --baseline '" + (dir_ / file).string() + "'";
  };
  const std::pair<std::string, std::string> cases[] = {
      {"fuzz --generator bogus" + out,
       "--generator: expected one of sizes, clip, mesh, attributes, states, dense, assembly, "
       "window, distances, depth, got "
       "\"bogus\""},
      {"fuzz --replay 12" + out, "--replay: expected SEED:INDEX"},
      {"fuzz --replay 1:x" + out, "--replay: expected SEED:INDEX"},
      {"fuzz --replay 1:2 --seed 3" + out,
       "--replay: expected no --seed, --count, --time, --fraction or --fraction-start"},
      {"fuzz --emit x.json" + out, "--emit: expected --replay SEED:INDEX with it"},
      {"fuzz --time nan" + out, "--time"},
      {"fuzz --fraction 2 --fraction-start 3" + out, "expected 1 <= fraction-start <= fraction"},
      // Issue 45: wrapped, clamped or empty, each once a silent campaign of another kind.
      {"fuzz --replay 3:18446744073709551615" + out,
       "--replay: expected an INDEX below 18446744073709551615"},
      {"fuzz --replay ''" + out, "--replay: expected SEED:INDEX"},
      {"fuzz --seed -1" + out,
       "expected a whole number from 0 to 18446744073709551615, got \"-1\""},
      {"fuzz --seed 18446744073709551616" + out,
       "expected a whole number from 0 to 18446744073709551615, got \"18446744073709551616\""},
      {"fuzz --count 0" + out, "expected a whole number from 1"},
      {"fuzz --count 1" + baseline("crash.txt") + out,
       "gap: expected the status Fail (a campaign failure is listed as `<failure>,Fail`), got "
       "Crash"},
      {"fuzz --count 1" + baseline("signature.txt") + out,
       "expected a failure's file name (non_finite_noperspective), not its signature, got "
       "\"non_finite/noperspective\""},
      {"fuzz --count 1" + baseline("unknown.txt") + out,
       "expected a campaign failure's name: crash, timeout"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = glrefcheck(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
  }
}

}  // namespace
