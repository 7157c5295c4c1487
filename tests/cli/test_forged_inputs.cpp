// What glrefcheck reads back from its own files (results.json for merge, compare and report; the
// journal for run --resume) may be damaged, hand-edited or forged: each bad field is one line
// and exit 2, never a crash, a hang, a raw library message or a run with impossible options
// (issue 11, the hostile-user campaign).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "report/stamp.hpp"
#include "tests/support/glrefcheck_process.hpp"

namespace glrc::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::glrefcheck;
using test::Outcome;

size_t lines(const std::string& s) {
  return size_t(std::count(s.begin(), s.end(), '\n'));
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

// One run of face_on, made once for all the tests here: the thing to forge.
class Forged : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("glrc_forged_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    const Outcome o =
        glrefcheck("run cases/face_on.json --jobs 1 --out '" + (dir_ / "run").string() + "'");
    ASSERT_EQ(o.exit_code, 0) << o.out << o.err;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  // A copy of the run folder with `edit` applied to its results.json, stamped again as
  // glrefcheck stamps it: each field's own check is what these tests try (an edit under the
  // stamp is refused before any, tests/report/test_results_json.cpp).
  static fs::path forged_results(const std::string& name, const std::function<void(json&)>& edit) {
    const fs::path d = dir_ / name;
    fs::remove_all(d);
    fs::create_directories(d);
    json j = json::parse(read(dir_ / "run/results.json"));
    edit(j);
    write_restamped(d / "results.json", j);
    return d;
  }

  // A fresh copy of the run folder, named `name`.
  static fs::path copied_run(const std::string& name) {
    const fs::path d = dir_ / name;
    fs::remove_all(d);
    fs::copy(dir_ / "run", d, fs::copy_options::recursive);
    return d;
  }

  static void write_restamped(const fs::path& file, json j) {
    j.erase("written_by");
    std::ofstream(file, std::ios::binary) << report::stamped_json("run", j.dump(2) + "\n");
  }

  // A copy of the run folder with `edit` applied to the options on its journal's first line.
  static fs::path forged_journal(const std::string& name, const std::function<void(json&)>& edit) {
    const fs::path d = copied_run(name);
    std::string text = read(d / "journal.jsonl");
    const size_t eol = text.find('\n');
    json first = json::parse(text.substr(0, eol));
    edit(first["options"]);
    std::ofstream(d / "journal.jsonl") << first.dump() << text.substr(eol);
    return d;
  }

  static void expect_one_line(const Outcome& o, const std::string& says) {
    EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
    EXPECT_EQ(lines(o.err), 1u) << o.err;
    EXPECT_NE(o.err.find(says), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find("json.exception"), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find("max_size"), std::string::npos) << o.err;
  }

  static fs::path dir_;
};
fs::path Forged::dir_;

// fraction_start 2147483647 or fraction -1 indexed merge's shard table out of bounds (SIGSEGV);
// fraction_start 3 of 2 read past it and claimed a duplicate shard; fraction 2^32 + 1 was read as
// 1; total_cases 2^62 asked for a vector of that size.
TEST_F(Forged, ShardFieldsOutOfRangeAreOneLineInMerge) {
  const std::vector<std::tuple<std::string, std::function<void(json&)>, std::string>> forgeries = {
      {"fs_huge", [](json& j) { j["run"]["fraction_start"] = 2147483647; },
       "run.fraction_start: expected an integer from 1 to 1, got 2147483647"},
      {"frac_neg", [](json& j) { j["run"]["fraction"] = -1; },
       "run.fraction: expected an integer >= 1, got -1"},
      {"frac_0", [](json& j) { j["run"]["fraction"] = 0; },
       "run.fraction: expected an integer >= 1, got 0"},
      {"fs_3_of_2",
       [](json& j) {
         j["run"]["fraction"] = 2;
         j["run"]["fraction_start"] = 3;
       },
       "run.fraction_start: expected an integer from 1 to 2, got 3"},
      {"frac_2p32p1", [](json& j) { j["run"]["fraction"] = 4294967297ull; },
       "run.fraction: expected an integer >= 1, got 4294967297"},
      {"total_huge", [](json& j) { j["run"]["total_cases"] = 1ull << 62; },
       "shard 1 of 1 of a 4611686018427387904-case suite: expected 4611686018427387904 cases, "
       "got 1"},
      {"two_of_3",
       [](json& j) {
         j["run"]["fraction"] = 3;
         j["run"]["fraction_start"] = 2;
       },
       "shard 1 of 3 is missing"},
  };
  for (const auto& [name, edit, says] : forgeries) {
    SCOPED_TRACE(name);
    const fs::path shard = forged_results(name, edit);
    expect_one_line(glrefcheck("merge '" + shard.string() + "' --out '" +
                               (dir_ / ("merged_" + name)).string() + "'"),
                    says);
    EXPECT_FALSE(fs::exists(dir_ / ("merged_" + name) / "results.json"));
  }
}

// A truncated results.json quoted nlohmann's "[json.exception.parse_error.101] ..." whole.
TEST_F(Forged, ATruncatedResultsJsonIsOneLineInTheToolsWords) {
  const fs::path d = dir_ / "truncated";
  fs::create_directories(d);
  std::ofstream(d / "results.json") << "{\"run\": ";
  const Outcome o = glrefcheck("compare '" + d.string() + "' '" + (dir_ / "run").string() + "'");
  expect_one_line(o, (d / "results.json").string() + ": expected JSON, got invalid JSON (");
}

// Opening a FIFO named results.json waited for a writer forever: compare and report hung.
TEST_F(Forged, AResultsJsonThatIsAFifoIsRefusedNotWaitedFor) {
  const fs::path d = dir_ / "fifo";
  fs::create_directories(d);
  ASSERT_EQ(mkfifo((d / "results.json").c_str(), 0600), 0);
  const std::string says = (d / "results.json").string() +
                           ": expected a results.json (or a folder holding one), got something "
                           "other than a regular file (not read)";
  expect_one_line(
      glrefcheck("compare '" + d.string() + "' '" + (dir_ / "run").string() + "'", "timeout 30"),
      says);
  expect_one_line(glrefcheck("report '" + d.string() + "'", "timeout 30"), says);
}

// The journal's options were taken as written: fraction 0 grew memory without bound, timeout -5
// and subpixel bits 99 ran, a model of no name ran as the default, and a string for a number
// quoted nlohmann's type_error.
TEST_F(Forged, AResumedJournalsOptionsAreCheckedAsTheCommandLineChecksThem) {
  const std::vector<std::tuple<std::string, std::function<void(json&)>, std::string>> forgeries = {
      {"frac0", [](json& o) { o["fraction"] = 0; },
       "options.fraction: expected a whole number from 1 to 2147483647, got 0"},
      {"fstart9",
       [](json& o) {
         o["fraction"] = 2;
         o["fraction_start"] = 9;
       },
       "options.fraction_start: expected a whole number from 1 to 2, got 9"},
      {"tneg", [](json& o) { o["timeout"] = -5; },
       "options.timeout: expected a number from 0.001 to 1e+06, got -5"},
      {"spb99", [](json& o) { o["subpixel_bits"] = 99; },
       "options.subpixel_bits: expected a whole number from 0 to 16, got 99"},
      {"modelx", [](json& o) { o["model"] = "bogus"; },
       "options.model: expected one of identified, ideal, llvmpipe, softpipe, got \"bogus\""},
      {"jobsstr", [](json& o) { o["jobs"] = "four"; },
       "options.jobs: expected a whole number from 0 to 2147483647, got \"four\""},
      {"nopaths", [](json& o) { o.erase("paths"); }, "options.paths: expected a field \"paths\""},
  };
  for (const auto& [name, edit, says] : forgeries) {
    SCOPED_TRACE(name);
    const fs::path d = forged_journal(name, edit);
    const std::string before = read(d / "results.json");
    expect_one_line(glrefcheck("run --resume '" + d.string() + "'", "timeout 60"),
                    (d / "journal.jsonl").string() + ":1: " + says);
    EXPECT_EQ(read(d / "results.json"), before);
  }
  // A line that is not JSON at all.
  const fs::path d = dir_ / "garbage";
  fs::remove_all(d);
  fs::copy(dir_ / "run", d, fs::copy_options::recursive);
  std::ofstream(d / "journal.jsonl") << "this is not json\n";
  expect_one_line(glrefcheck("run --resume '" + d.string() + "'"),
                  (d / "journal.jsonl").string() +
                      ":1: expected a journal line of glrefcheck's, got invalid JSON at byte 2");
}

// The sixth hostile campaign (issue 45): a results.json with a verdict flipped or a case
// renamed by hand was merged and compared as a run's; a journal with a line edited (the
// tolerance of the options, a verdict, a model) resumed into results no run gives. Each is
// stamped now: an edit under the stamp is one line; a results.json without one (an older
// glrefcheck's) reads as it stands, with a note saying so.
TEST_F(Forged, EditsUnderAStampAreRefused) {
  const std::string run = "'" + (dir_ / "run").string() + "'";
  const fs::path edited = copied_run("edited");
  std::string text = read(edited / "results.json");
  const size_t at = text.find("\"status\": \"Pass\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 16, "\"status\": \"Fail\"");
  std::ofstream(edited / "results.json", std::ios::binary) << text;
  const std::string says = "results.json: written_by: expected the stamp glrefcheck wrote";
  expect_one_line(glrefcheck("compare " + run + " '" + edited.string() + "'"), says);
  expect_one_line(glrefcheck("report '" + edited.string() + "'"), says);
  expect_one_line(glrefcheck("merge '" + edited.string() + "' --out '" +
                             (dir_ / "merged_edited").string() + "'"),
                  says);
  EXPECT_FALSE(fs::exists(dir_ / "merged_edited/results.json"));
  // Without its stamp: read as it stands, and said so.
  json j = json::parse(text);
  j.erase("written_by");
  std::ofstream(edited / "results.json", std::ios::binary) << j.dump(2);
  const Outcome o = glrefcheck("compare " + run + " '" + edited.string() + "'");
  EXPECT_NE(o.exit_code, 2) << o.out << o.err;
  EXPECT_NE(o.err.find("holds no written_by stamp (an older glrefcheck's, or made by hand): read "
                       "as it stands"),
            std::string::npos)
      << o.err;

  // The journal: each line's digest.
  const auto resumed_journal = [&](const std::string& name,
                                   const std::function<void(std::string&)>& edit) {
    const fs::path d = copied_run(name);
    std::string journal = read(d / "journal.jsonl");
    edit(journal);
    std::ofstream(d / "journal.jsonl", std::ios::binary) << journal;
    fs::remove(d / "results.json");
    return d;
  };
  const auto replaced = [](std::string& s, const std::string& from, const std::string& to) {
    const size_t k = s.find(from);
    ASSERT_NE(k, std::string::npos) << from;
    s.replace(k, from.size(), to);
  };
  for (const auto& [name, from, to] :
       {std::tuple{"verdict", "\"status\":\"Pass\"", "\"status\":\"Fail\""},
        {"tolerance", "\"tolerance\":\"spec\"", "\"tolerance\":\"exact\""},
        {"model", "\"planes\":\"unsnapped\"", "\"planes\":\"snapped\""}}) {
    SCOPED_TRACE(name);
    // Copies: Clang 14 captures no structured binding in a lambda.
    const std::string old_text = from, new_text = to;
    const fs::path d =
        resumed_journal(name, [&](std::string& s) { replaced(s, old_text, new_text); });
    const Outcome resumed = glrefcheck("run --resume '" + d.string() + "'");
    expect_one_line(resumed,
                    "expected the line as glrefcheck wrote it after the line before, got one its "
                    "digest no longer matches (edited since, or another run's): start a new run");
    EXPECT_FALSE(fs::exists(d / "results.json"));
  }
  // A line of another run's journal, its own digest intact (the eighth hostile campaign: a
  // result of a spec run went into an exact one's resume).
  ASSERT_LE(glrefcheck("run cases/face_on.json --jobs 1 --tolerance exact --out '" +
                       (dir_ / "exact_run").string() + "'")
                .exit_code,
            1);
  const std::string other = read(dir_ / "exact_run/journal.jsonl");
  const fs::path mixed = resumed_journal("mixed", [&](std::string& s) {
    s = s.substr(0, s.find('\n') + 1) + other.substr(other.find('\n') + 1);
  });
  expect_one_line(glrefcheck("run --resume '" + mixed.string() + "'"),
                  "digest no longer matches (edited since, or another run's)");
  const fs::path bogus = resumed_journal("heatmaps", [&](std::string& s) {
    replaced(s, "\"result\":", "\"heatmaps\":\"bogus\",\"result\":");
  });
  expect_one_line(
      glrefcheck("run --resume '" + bogus.string() + "'"),
      "expected \"heatmaps\": \"follow\", or no \"heatmaps\" field, in a line with a result, got "
      "\"bogus\"");
  const fs::path undigested = resumed_journal("undigested", [&](std::string& s) {
    const size_t cut = s.find(",\"digest\":\"sha256:");
    ASSERT_NE(cut, std::string::npos);
    s.erase(cut, s.find('}', cut) - cut);
  });
  expect_one_line(glrefcheck("run --resume '" + undigested.string() + "'"),
                  "got one without its digest (edited since)");
  const fs::path older = resumed_journal("version1", [&](std::string& s) {
    replaced(s, "\"glrefcheck_journal\":3", "\"glrefcheck_journal\":2");
  });
  expect_one_line(glrefcheck("run --resume '" + older.string() + "'"),
                  ":1: expected a run journal of this glrefcheck (version 3), got version 2");
}

// The sixth hostile campaign: merge compared neither the driver asked for, nor the Mesa tree,
// nor GL_SUBPIXEL_BITS (from which the spec tolerance derives), nor --timeout.
TEST_F(Forged, MergeRefusesShardsOfAnotherDriverPrefixSubpixelBitsOrTimeout) {
  const auto shard = [&](const std::string& name, const std::function<void(json&)>& edit) {
    return forged_results(name, [&](json& j) {
      j["run"]["fraction"] = 2;
      j["run"]["fraction_start"] = name == "first" ? 1 : 2;
      j["run"]["total_cases"] = 2;
      if (name == "second") j["cases"][0]["name"] = "face_on_2";
      edit(j);
    });
  };
  const fs::path first = shard("first", [](json&) {});
  for (const auto& [field, edit, says] :
       {std::tuple<std::string, std::function<void(json&)>, std::string>{
            "driver", [](json& j) { j["run"]["driver"] = "softpipe"; },
            "got run.driver \"softpipe\" where"},
        {"mesa_prefix", [](json& j) { j["run"]["mesa_prefix"] = "/opt/mesa"; },
         "got run.mesa_prefix \"/opt/mesa\" where"},
        {"subpixel_bits", [](json& j) { j["run"]["gl_subpixel_bits"] = 4; },
         "got run.subpixel_bits 4 where"},
        {"timeout", [](json& j) { j["run"]["verdict_inputs"]["timeout"] = "5"; },
         "got timeout 5 where"},
        // The backend named, not the GL library that follows from it.
        {"backend",
         [](json& j) {
           j["run"]["backend"] = "egl";
           j["run"]["gl_library"] = "libEGL_mesa.so.0";
         },
         "got run.backend \"egl\" where"}}) {
    SCOPED_TRACE(field);
    const fs::path second = shard("second", edit);
    expect_one_line(glrefcheck("merge '" + first.string() + "' '" + second.string() + "' --out '" +
                               (dir_ / ("merged_" + field)).string() + "'"),
                    says);
  }
}

// The sixth hostile campaign's unclear messages: a marker a person garbled was called no marker;
// compare on a folder whose results a stopped glrefcheck set aside said "no such file".
TEST_F(Forged, AGarbledMarkerAndResultsSetAsideAreNamed) {
  const fs::path garbled = copied_run("garbled");
  std::ofstream(garbled / ".glrefcheck") << "my notes\n";
  expect_one_line(glrefcheck("run cases/face_on.json --out '" + garbled.string() + "'"),
                  "whose .glrefcheck is not glrefcheck's marker (its first line edited, or made by "
                  "hand)");
  const fs::path aside = copied_run("aside");
  fs::create_directories(aside / ".glrefcheck-earlier");
  fs::rename(aside / "results.json", aside / ".glrefcheck-earlier/results.json");
  expect_one_line(glrefcheck("compare '" + (dir_ / "run").string() + "' '" + aside.string() + "'"),
                  "holds no results.json: a glrefcheck stopped before it finished (a run or "
                  "campaign before GL started, or a merge) set them aside (.glrefcheck-earlier/); "
                  "`glrefcheck report ");
  // As it says: report puts them back, and says so.
  const Outcome report = glrefcheck("report '" + aside.string() + "'");
  EXPECT_EQ(report.exit_code, 0) << report.out << report.err;
  EXPECT_NE(report.out.find("earlier results, which a glrefcheck stopped before it finished had "
                            "set aside"),
            std::string::npos)
      << report.out;
  // Beside the results a stopped glrefcheck set aside, what it wrote of its own (a merge killed
  // halfway) was compared as the folder's results; and report on a killed run's folder named its
  // own lock as the other glrefcheck writing there.
  const fs::path halfway = copied_run("halfway");
  fs::create_directories(halfway / ".glrefcheck-earlier");
  fs::copy_file(halfway / "results.json", halfway / ".glrefcheck-earlier/results.json");
  expect_one_line(
      glrefcheck("compare '" + (dir_ / "run").string() + "' '" + halfway.string() + "'"),
      "holds what a glrefcheck stopped before it finished wrote, beside the earlier "
      "results it set aside");
  const fs::path killed = copied_run("killed");
  fs::remove(killed / "results.json");
  expect_one_line(glrefcheck("report '" + killed.string() + "'"),
                  "holds no results.json but a journal.jsonl: the run was killed");
  // A FIFO for a --baseline is named as one.
  const fs::path fifo = dir_ / "baseline.fifo";
  fs::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  expect_one_line(glrefcheck("run cases/face_on.json --baseline '" + fifo.string() + "' --out '" +
                             (dir_ / "fifo_run").string() + "'"),
                  "expected a baseline file of `case,Status` lines, got a FIFO (not read)");
  // A shard compared with the whole suite: every case outside it "removed", exit 0.
  const fs::path shard = forged_results("shard", [](json& j) {
    j["run"]["fraction"] = 2;
    j["run"]["total_cases"] = 2;
  });
  const Outcome against =
      glrefcheck("compare '" + (dir_ / "run").string() + "' '" + shard.string() + "'");
  EXPECT_EQ(against.exit_code, 1) << against.out << against.err;
  EXPECT_NE(against.out.find("current: shard 1 of 2, base: the whole suite (merge the shards "
                             "first"),
            std::string::npos)
      << against.out;
  // --emit writes one file: an --out beside it was ignored.
  expect_one_line(
      glrefcheck("fuzz --generator clip --replay 1:7 --emit '" + (dir_ / "x.json").string() +
                 "' --out '" + (dir_ / "d").string() + "'"),
      "--out: expected no --out with --emit");
  EXPECT_TRUE(fs::exists(aside / "results.json"));
}

// The ninth hostile campaign (issue 45): more shards than cases (the suite's 6 in GitLab's
// `parallel: 8`) left a shard of no case, which never started GL, and merge refused it as a
// shard of another GL. Its empty GL fields say nothing now.
TEST_F(Forged, AShardOfNoCaseMergesWithTheOthers) {
  for (const int start : {1, 2})
    ASSERT_EQ(glrefcheck("run cases/face_on.json --jobs 1 --fraction 2 --fraction-start " +
                         std::to_string(start) + " --out '" +
                         (dir_ / ("empty_shard" + std::to_string(start))).string() + "'")
                  .exit_code,
              0);
  const fs::path merged = dir_ / "empty_merged";
  const Outcome o =
      glrefcheck("merge '" + (dir_ / "empty_shard2").string() + "' '" +
                 (dir_ / "empty_shard1").string() + "' --out '" + merged.string() + "'");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  const json j = json::parse(read(merged / "results.json"));
  EXPECT_EQ(j["cases"].size(), 1u);
  EXPECT_EQ(j["run"]["gl_renderer"],
            json::parse(read(dir_ / "empty_shard1/results.json"))["run"]["gl_renderer"]);
}

// `compare --json FILE` and `report --out FILE` replaced whatever FILE held. A file glrefcheck
// wrote is still replaced, so the same command can run again.
TEST_F(Forged, OutputFilesReplaceOnlyWhatGlrefcheckWrote) {
  const fs::path mine = dir_ / "mine.txt";
  const std::string run = "'" + (dir_ / "run").string() + "'";
  for (const std::string option : {"--json", "--markdown", "--html"}) {
    SCOPED_TRACE(option);
    std::ofstream(mine) << "notes of mine\n";
    const Outcome o =
        glrefcheck("compare " + run + " " + run + " " + option + " '" + mine.string() + "'");
    expect_one_line(o, option + ": expected a new file or one glrefcheck wrote, got \"" +
                           mine.string() +
                           "\", which glrefcheck did not write (it holds no stamp)");
    EXPECT_EQ(read(mine), "notes of mine\n");
    const fs::path ours = dir_ / ("compare" + option.substr(1));
    for (int k = 0; k < 2; ++k)
      EXPECT_EQ(glrefcheck("compare " + run + " " + run + " " + option + " '" + ours.string() + "'")
                    .exit_code,
                0);
    // Once a person edits it, it is theirs: refused, and left as they made it.
    std::ofstream(ours, std::ios::app) << "my note\n";
    const std::string edited = read(ours);
    expect_one_line(
        glrefcheck("compare " + run + " " + run + " " + option + " '" + ours.string() + "'"),
        "which was changed since glrefcheck wrote it (its stamp no longer matches)");
    EXPECT_EQ(read(ours), edited);
  }
  // One file for two outputs would keep only the last, however it is spelt.
  expect_one_line(glrefcheck("compare " + run + " " + run + " --json '" + (dir_ / "x").string() +
                             "' --markdown '" + (dir_ / "x").string() + "'"),
                  "--json and --markdown: expected two different files");
  // (In the test folder: the second argument goes before the binary on the shell's line.)
  expect_one_line(glrefcheck("compare " + run + " " + run + " --json c5.json --markdown ./c5.json",
                             "cd '" + dir_.string() + "' &&"),
                  "--json and --markdown: expected two different files");
  // Another command's file is not compare's to replace (a case fuzz emitted).
  const fs::path emitted = dir_ / "emitted.json";
  ASSERT_EQ(
      glrefcheck("fuzz --replay 1:0 --generator sizes --emit '" + emitted.string() + "'").exit_code,
      0);
  const std::string before = read(emitted);
  expect_one_line(glrefcheck("compare " + run + " " + run + " --json '" + emitted.string() + "'"),
                  "which glrefcheck fuzz wrote, not glrefcheck compare");
  EXPECT_EQ(read(emitted), before);
  std::ofstream(mine) << "notes of mine\n";
  expect_one_line(glrefcheck("report " + run + " --out '" + mine.string() + "'"),
                  "--out: expected a new file or one glrefcheck wrote");
  EXPECT_EQ(read(mine), "notes of mine\n");
  const fs::path page = dir_ / "page.html";
  for (int k = 0; k < 2; ++k)
    EXPECT_EQ(glrefcheck("report " + run + " --out '" + page.string() + "'").exit_code, 0);
}

// Issue 45: compare took a run stopped after a quarter of its cases for a run with cases
// removed ("0 regressions", exit 0), and counted a case named twice; it read a campaign's
// results.json as a run missing "cases".
TEST_F(Forged, CompareRefusesOrFlagsWhatDoesNotBelongTogether) {
  const std::string run = "'" + (dir_ / "run").string() + "'";
  const fs::path stopped = forged_results("stopped", [](json& j) {
    j["run"]["interrupted"] = true;
    j["run"]["total_cases"] = 4;
  });
  Outcome o = glrefcheck("compare " + run + " '" + stopped.string() + "' --json '" +
                         (dir_ / "stopped.json").string() + "'");
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;
  EXPECT_NE(o.out.find("incomplete current: interrupted after 1 of 4 cases"), std::string::npos)
      << o.out;
  EXPECT_NE(o.out.find("--allow-incomplete"), std::string::npos) << o.out;
  EXPECT_EQ(json::parse(read(dir_ / "stopped.json"))["incomplete"],
            json::array({"current: interrupted after 1 of 4 cases"}));
  o = glrefcheck("compare " + run + " '" + stopped.string() + "' --allow-incomplete");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  // Not interrupted, but fewer cases than its suite: a partial results.json.
  const fs::path partial = forged_results("partial", [](json& j) { j["run"]["total_cases"] = 3; });
  o = glrefcheck("compare '" + partial.string() + "' " + run);
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;
  EXPECT_NE(o.out.find("incomplete base: 1 of 3 cases"), std::string::npos) << o.out;
  // A case named twice is bad input, in compare, merge and report alike.
  const fs::path twice = forged_results("twice", [](json& j) {
    j["cases"].push_back(j["cases"][0]);
    j["run"]["total_cases"] = 2;
  });
  expect_one_line(glrefcheck("compare " + run + " '" + twice.string() + "'"),
                  "cases[1].name: expected a name no other case has (cases[0] has it too)");
  expect_one_line(glrefcheck("report '" + twice.string() + "'"),
                  "cases[1].name: expected a name no other case has");
  // A campaign's results are not a run's.
  const fs::path campaign = dir_ / "campaign";
  fs::create_directories(campaign);
  std::ofstream(campaign / "results.json")
      << R"({"campaign": {"seed": 1}, "run": {}, "stats": {}, "failures": []})";
  expect_one_line(glrefcheck("compare " + run + " '" + campaign.string() + "'"),
                  "expected a run's results.json, got a fuzz campaign's");
}

// Issue 45: shards run with --strict-coverage and without merged into results no run gives.
TEST_F(Forged, MergeRefusesShardsJudgedOtherwise) {
  const std::string shard =
      "run cases/face_on.json cases/viewport_tiny.json --jobs 1 --fraction 2 ";
  const fs::path a = dir_ / "shard_a", b = dir_ / "shard_b";
  ASSERT_EQ(glrefcheck(shard + "--fraction-start 1 --out '" + a.string() + "'").exit_code, 0);
  ASSERT_LE(glrefcheck(shard + "--fraction-start 2 --strict-coverage --out '" + b.string() + "'")
                .exit_code,
            1);
  expect_one_line(glrefcheck("merge '" + a.string() + "' '" + b.string() + "' --out '" +
                             (dir_ / "merged").string() + "'"),
                  "expected shards judged alike, got strict_coverage true where");
  EXPECT_EQ(json::parse(read(a / "results.json"))["run"]["verdict_inputs"]["strict_coverage"],
            "false");
  // Shards of two suites (a case renamed between two checkouts): face_on twice.
  const fs::path c = dir_ / "shard_c";
  ASSERT_EQ(glrefcheck("run cases/attr_tiny.json cases/face_on.json --jobs 1 --fraction 2 "
                       "--fraction-start 2 --out '" +
                       c.string() + "'")
                .exit_code,
            0);
  expect_one_line(glrefcheck("merge '" + a.string() + "' '" + c.string() + "' --out '" +
                             (dir_ / "merged2").string() + "'"),
                  "expected shards judged alike, got case_files sha256:");
  // Without the suite's digest (results before it was recorded), by the name met twice.
  for (const fs::path& folder : {a, c}) {
    json j = json::parse(read(folder / "results.json"));
    j["run"]["verdict_inputs"].erase("case_files");
    write_restamped(folder / "results.json", j);
  }
  expect_one_line(glrefcheck("merge '" + a.string() + "' '" + c.string() + "' --out '" +
                             (dir_ / "merged3").string() + "'"),
                  "expected shards of one suite, got case \"face_on\" as case 1 and case 2");
}

// Issue 45's second hostile campaign: compare took case names that run refuses (W6), and merge
// said "expected the same GL and options" for shards of another --tolerance, naming neither
// the field nor the option (U1).
TEST_F(Forged, CaseNamesRunRefusesAndShardsJudgedByAnotherToleranceAreNamed) {
  const std::string run = "'" + (dir_ / "run").string() + "'";
  for (const auto& [name, bad, holds] : {std::tuple{"empty", "", "no character at all"},
                                         {"comma", "face,on", "a comma"},
                                         {"line_break", "face\non", "a line break"}}) {
    SCOPED_TRACE(name);
    const std::string bad_name = bad;  // a copy: Clang 14 captures no structured binding
    const fs::path forged =
        forged_results(name, [&](json& j) { j["cases"][0]["name"] = bad_name; });
    expect_one_line(glrefcheck("compare " + run + " '" + forged.string() + "'"),
                    std::string("cases[0].name: expected a case name fit for results.csv (it "
                                "holds ") +
                        holds + ")");
  }
  const auto shard = [&](const std::string& name, int start, const std::string& tolerance) {
    return forged_results(name, [&](json& j) {
      j["run"]["fraction"] = 2, j["run"]["fraction_start"] = start, j["run"]["total_cases"] = 2;
      j["cases"][0]["name"] = "case_" + std::to_string(start);
      if (!tolerance.empty()) j["run"]["tolerance"] = tolerance;
    });
  };
  const fs::path first = shard("shard_1", 1, ""), second = shard("shard_2", 2, "ulps");
  // Another GL library (another --mesa) under the same renderer and version: named too.
  const fs::path other_library = forged_results("shard_2_library", [&](json& j) {
    j = json::parse(read(shard("shard_2b", 2, "") / "results.json"));
    j["run"]["gl_library"] = "/elsewhere/libOSMesa.so.8";
  });
  expect_one_line(glrefcheck("merge '" + first.string() + "' '" + other_library.string() +
                             "' --out '" + (dir_ / "merged_library").string() + "'"),
                  "got run.gl_library \"/elsewhere/libOSMesa.so.8\"");
  const std::string spec = json::parse(read(first / "results.json"))["run"]["tolerance"];
  expect_one_line(glrefcheck("merge '" + first.string() + "' '" + second.string() + "' --out '" +
                             (dir_ / "merged_tolerance").string() + "'"),
                  "expected shards judged alike, got run.tolerance \"ulps\" where " +
                      first.string() + " has \"" + spec +
                      "\" (set by --tolerance, --spec-subpixel-bits)");
}

// Issue 45's third hostile campaign: merge waited for good on a shard whose results.json was a
// FIFO; merged shards of two checkouts whose case files differ under the same names; compare
// took a results.json with fewer cases in its suite than it holds, a negative maximum and a
// digest that is none; --emit replaced a symbolic link with a file; a merge into a shard's
// folder was accepted; a journal that is a FIFO was "none"; export took --driver "" for none.
TEST_F(Forged, WhatDoesNotBelongIsOneLineAndNothingWaits) {
  const std::string run = "'" + (dir_ / "run").string() + "'";
  const fs::path fifo = dir_ / "fifo_shard";
  fs::create_directories(fifo);
  ASSERT_EQ(mkfifo((fifo / "results.json").c_str(), 0600), 0);
  Outcome o = glrefcheck("merge '" + fifo.string() + "' --out '" + (dir_ / "m_fifo").string() + "'",
                         "timeout 30");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;  // 124: timeout's, a hang
  EXPECT_NE(o.err.find("other than a regular file"), std::string::npos) << o.err;
  o = glrefcheck(
      "merge " + run + " '" + fifo.string() + "' --out '" + (dir_ / "m_fifo2").string() + "'",
      "timeout 30");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;

  // Two checkouts: the same names, one case's content edited between them.
  const fs::path one = dir_ / "suite_one", two = dir_ / "suite_two";
  for (const fs::path& s : {one, two}) {
    fs::create_directories(s);
    for (const char* name : {"face_on", "viewport_tiny"})
      fs::copy_file(fs::path(GLRC_SOURCE_DIR) / "cases" / (std::string(name) + ".json"),
                    s / (std::string(name) + ".json"));
  }
  std::string text = read(two / "viewport_tiny.json");
  text.insert(text.find("\"description\": \"") + 16, "Edited: ");
  std::ofstream(two / "viewport_tiny.json") << text;
  const fs::path s1 = dir_ / "checkout_1", s2 = dir_ / "checkout_2";
  ASSERT_EQ(glrefcheck("run '" + one.string() +
                       "' --jobs 1 --fraction 2 --fraction-start 1 --out '" + s1.string() + "'")
                .exit_code,
            0);
  ASSERT_EQ(glrefcheck("run '" + two.string() +
                       "' --jobs 1 --fraction 2 --fraction-start 2 --out '" + s2.string() + "'")
                .exit_code,
            0);
  expect_one_line(glrefcheck("merge '" + s1.string() + "' '" + s2.string() + "' --out '" +
                             (dir_ / "m_checkouts").string() + "'"),
                  "expected shards judged alike, got case_files sha256:");
  // Into a shard's own folder: refused before anything is written there.
  const fs::path s1b = dir_ / "checkout_1b";
  ASSERT_EQ(glrefcheck("run '" + one.string() +
                       "' --jobs 1 --fraction 2 --fraction-start 2 --out '" + s1b.string() + "'")
                .exit_code,
            0);
  expect_one_line(glrefcheck("merge '" + s1.string() + "' '" + s1b.string() + "' --out '" +
                             (s1 / "failures").string() + "'"),
                  "expected a folder apart from the shards");
  EXPECT_FALSE(fs::exists(s1 / "failures"));

  for (const auto& [name, edit, says] :
       std::vector<std::tuple<std::string, std::function<void(json&)>, std::string>>{
           {"negative_ulps", [](json& j) { j["cases"][0]["channels"][0]["max_ulps"] = -100; },
            "cases[0].channels[0].max_ulps: expected a number >= 0, got -100"},
           {"bad_digest", [](json& j) { j["cases"][0]["gl_digest"] = "zz"; },
            "cases[0].gl_digest: expected a SHA-256 in 64 lowercase hex digits"},
           {"over_compared",
            [](json& j) {
              auto& ch = j["cases"][0]["channels"][0];
              ch["over_tolerance"] = ch["compared"].get<uint64_t>() + 1;
            },
            "cases[0].channels[0].over_tolerance: expected at most the pixels compared"}}) {
    SCOPED_TRACE(name);
    expect_one_line(glrefcheck("compare " + run + " '" + forged_results(name, edit).string() + "'"),
                    says);
  }
  const fs::path more = forged_results("more_than_total", [](json& j) {
    j["cases"].push_back(j["cases"][0]);
    j["cases"][1]["name"] = "face_on_again";
    j["run"]["total_cases"] = 1;
  });
  expect_one_line(glrefcheck("compare " + run + " '" + more.string() + "'"),
                  "run.total_cases: expected at least the cases results.json holds (2), got 1");

  // --emit through a symbolic link: the link is named, nothing written.
  const fs::path target = dir_ / "emitted.json", link = dir_ / "link.json";
  ASSERT_EQ(
      glrefcheck("fuzz --generator clip --replay 1:9 --emit '" + target.string() + "'").exit_code,
      0);
  fs::create_symlink(target, link);
  const std::string emitted = read(target);
  expect_one_line(glrefcheck("fuzz --generator clip --replay 1:10 --emit '" + link.string() + "'"),
                  "which is a symbolic link (name the file it points to)");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read(target), emitted);

  const fs::path piped = dir_ / "piped_journal";
  fs::copy(dir_ / "run", piped, fs::copy_options::recursive);
  fs::remove(piped / "journal.jsonl");
  ASSERT_EQ(mkfifo((piped / "journal.jsonl").c_str(), 0600), 0);
  expect_one_line(glrefcheck("run --resume '" + piped.string() + "'", "timeout 30"),
                  "expected a run folder with a journal.jsonl, got one that is not a regular file");
  expect_one_line(glrefcheck("export cases/face_on.json --driver ''"),
                  "--driver: expected llvmpipe, softpipe or zink, got "
                  "");
}

// Issue 45's hostile campaign: an option naming a path given as "" (an unset variable) was
// taken for the option not given: `run --resume ''` ran a fresh run over the folder's journal,
// `fuzz --emit ''` ran a campaign over fuzz-out/.
TEST(CommandLine, EmptyPathsAreRefused) {
  for (const std::string args :
       {"run --resume ''", "fuzz --replay 1:0 --emit ''", "run cases/face_on.json --out ''",
        "compare a b --json ''", "run cases/face_on.json --baseline ''"}) {
    SCOPED_TRACE(args);
    const Outcome o = glrefcheck(args);
    EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
    EXPECT_NE(o.err.find(": expected a path, got \"\" (an empty or unset variable?)"),
              std::string::npos)
        << o.err;
  }
}

// A misspelt command was "A subcommand is required", naming nothing.
TEST(CommandLine, AnUnknownCommandIsNamed) {
  const Outcome o = glrefcheck("bogus");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(
      o.err,
      "glrefcheck: expected a command (run, fuzz, compare, export, merge, report, diff, digest, "
      "list, identify, selftest), got \"bogus\" (see --help)\n");
  const Outcome bytes = glrefcheck("\"$(printf 'r\\377n')\"");
  EXPECT_EQ(bytes.exit_code, 2);
  EXPECT_NE(bytes.err.find("got \"r\\xffn\""), std::string::npos) << bytes.err;
}

// A folder with no case, or named case paths that are none, said "no case matches: nothing to
// run" without a path; a FIFO named outright was a note and then that line.
TEST(CommandLine, NoCaseFoundSaysWhereAndWhy) {
  const fs::path d = fs::temp_directory_path() / ("glrc_nocase_" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d / "empty");
  fs::create_directories(d / "x.json");
  fs::create_directories(d / "loop");
  fs::create_directory_symlink(".", d / "loop/self");
  ASSERT_EQ(mkfifo((d / "loop/pipe.json").c_str(), 0600), 0);
  for (const std::string cmd : {"list", "digest"}) {
    const Outcome empty = glrefcheck(cmd + " '" + (d / "empty").string() + "'");
    EXPECT_EQ(empty.exit_code, 2);
    EXPECT_EQ(empty.err, "glrefcheck: no case matches in " + (d / "empty").string() +
                             ": no *.json case file found\n");
    const Outcome dir = glrefcheck(cmd + " '" + (d / "x.json").string() + "'");
    EXPECT_EQ(dir.err, "glrefcheck: no case matches in " + (d / "x.json").string() +
                           ": no *.json case file found\n");
    const Outcome loop = glrefcheck(cmd + " '" + (d / "loop").string() + "'", "timeout 30");
    EXPECT_EQ(loop.exit_code, 2);
    EXPECT_EQ(lines(loop.err), 1u) << loop.err;
    EXPECT_EQ(loop.err.rfind("glrefcheck: no case matches in " + (d / "loop").string() +
                                 ": no *.json case file found; 2 passed over, the first ",
                             0),
              0u)
        << loop.err;
    const Outcome fifo =
        glrefcheck(cmd + " '" + (d / "loop/pipe.json").string() + "'", "timeout 30");
    EXPECT_EQ(fifo.exit_code, 2);
    EXPECT_EQ(fifo.err, "glrefcheck: " + (d / "loop/pipe.json").string() +
                            ": expected a case file or a directory of them, got a FIFO (not "
                            "read)\n");
  }
  fs::remove_all(d);
}

}  // namespace
}  // namespace glrc::cli
