// Which model judges a run: the command line's, the fixed default, or the identified one, and
// the cache that keeps identified models between runs.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/session.hpp"
#include "identify/model_cache.hpp"
#include "tests/support/glrefcheck_process.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using glrc::Model;
using glrc::Planes;
using glrc::TieBreak;
using glrc::cli::Options;
using glrc::identify::ModelCacheSlot;
using glrc::test::glrefcheck;
using glrc::test::Outcome;
using glrc::test::proxied_workers;

// softpipe on Mesa 22.3.6, as `identify` finds it.
Model softpipe_model() {
  Model m;
  m.subpixel_bits = 0;
  m.planes = Planes::unsnapped;
  m.tie_break = TieBreak::bottom_right;
  return m;
}

class ModelCache : public glrc::test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    file_ = dir_ / "glrefcheck" / "models.json";
    lib_ = dir_ / "libOSMesa.so.8";
    std::ofstream(lib_) << "driver code, version 1";
  }
  ModelCacheSlot slot(const std::string& renderer = "softpipe",
                      const std::string& version = "3.3 (Core Profile) Mesa 22.3.6") const {
    return glrc::identify::model_cache_slot(renderer, version, {lib_.string()}, file_);
  }
  fs::path file_, lib_;
};

TEST_F(ModelCache, HitReturnsTheStoredModel) {
  EXPECT_FALSE(slot().load());  // no file yet: a miss
  slot().save(softpipe_model());
  ASSERT_TRUE(fs::exists(file_));
  const auto m = slot().load();
  ASSERT_TRUE(m);
  EXPECT_EQ(m->describe(), "subpixel_bits=0 planes=unsnapped tie=bottom-right");
  // Saving again replaces the entry, it does not add one.
  Model other = softpipe_model();
  other.tie_break = TieBreak::top_left;
  slot().save(other);
  EXPECT_EQ(slot().load()->tie_break, TieBreak::top_left);
  const auto j = nlohmann::json::parse(std::ifstream(file_));
  EXPECT_EQ(j["models"].size(), 1u);
}

TEST_F(ModelCache, MissesOnAnotherRendererVersionOrLibrary) {
  slot().save(softpipe_model());
  EXPECT_FALSE(slot("llvmpipe (LLVM 15.0.6, 256 bits)").load());
  EXPECT_FALSE(slot("softpipe", "3.3 (Core Profile) Mesa 25.0.7-2~bpo12+1").load());
  // The same strings from a rebuilt library: identified again.
  std::ofstream(lib_) << "driver code, version 2";
  EXPECT_FALSE(slot().load());
  std::ofstream(lib_) << "driver code, version 1";
  EXPECT_TRUE(slot().load());
  // Both entries live side by side.
  Model llvmpipe;
  slot("llvmpipe (LLVM 15.0.6, 256 bits)", "4.5 (Core Profile) Mesa 22.3.6").save(llvmpipe);
  EXPECT_EQ(slot().load()->subpixel_bits, 0);
  EXPECT_EQ(slot("llvmpipe (LLVM 15.0.6, 256 bits)", "4.5 (Core Profile) Mesa 22.3.6")
                .load()
                ->subpixel_bits,
            8);
}

TEST_F(ModelCache, CorruptFileIsIgnoredAndRewritten) {
  fs::create_directories(file_.parent_path());
  for (
      const char* text :
      {"{ not json", "[]", R"({"format": 1, "models": 7})", "\x01\x02garbage",
       R"({"format": 1, "models": [{"gl_renderer": "softpipe", "gl_version": "3.3 (Core Profile) Mesa 22.3.6", "driver_sha256": "x", "model": {"subpixel_bits": 99}}]})"}) {
    std::ofstream(file_) << text;
    EXPECT_FALSE(slot().load()) << text;
    slot().save(softpipe_model());
    ASSERT_TRUE(slot().load()) << text;
    EXPECT_EQ(slot().load()->tie_break, TieBreak::bottom_right);
  }
  // An entry for this key whose model is not one: a miss, then replaced.
  const std::string digest = slot().driver_digest;
  std::ofstream(file_) << nlohmann::json{
      {"format", 1},
      {"models",
       {{{"gl_renderer", "softpipe"},
         {"gl_version", "3.3 (Core Profile) Mesa 22.3.6"},
         {"driver_sha256", digest},
         {"model", {{"subpixel_bits", 0}, {"planes", "sideways"}, {"tie_break", "top-left"}}}}}}};
  EXPECT_FALSE(slot().load());
  slot().save(softpipe_model());
  EXPECT_TRUE(slot().load());
}

TEST_F(ModelCache, UnwritableOrUnknownMeansNoCache) {
  // A cache folder that cannot be made (its parent is a file): save does nothing, no throw.
  std::ofstream(dir_ / "a_file") << "x";
  const auto blocked = glrc::identify::model_cache_slot("softpipe", "3.3", {lib_.string()},
                                                        dir_ / "a_file" / "m.json");
  EXPECT_TRUE(blocked.usable());
  blocked.save(softpipe_model());
  EXPECT_FALSE(blocked.load());
  // A library that cannot be read, or none known: no key, no cache.
  EXPECT_FALSE(
      glrc::identify::model_cache_slot("softpipe", "3.3", {(dir_ / "missing.so").string()}, file_)
          .usable());
  EXPECT_FALSE(glrc::identify::model_cache_slot("softpipe", "3.3", {}, file_).usable());
  EXPECT_TRUE(glrc::identify::driver_files(glrc::gl::GlInfo{}).empty());
}

// The driver's digest is remembered with its files' identities, and used only while they hold.
TEST_F(ModelCache, RemembersTheDriverDigestWhileTheFilesAreTheSame) {
  const fs::path store = dir_ / "glrefcheck" / "driver_digests.json";
  const std::vector<std::string> files = {lib_.string()};
  const std::string real = glrc::identify::files_digest(files);
  ASSERT_EQ(real.size(), 64u);
  // Changed within the last second: hashed, not remembered.
  EXPECT_EQ(glrc::identify::remembered_files_digest(files, store), real);
  EXPECT_FALSE(fs::exists(store));
  // As seen a minute later: remembered. Then the store's digest is what comes back, proven by
  // planting another one there.
  const auto later = fs::file_time_type::clock::now() + std::chrono::minutes(1);
  EXPECT_EQ(glrc::identify::remembered_files_digest(files, store, later), real);
  ASSERT_TRUE(fs::exists(store));
  auto j = nlohmann::json::parse(std::ifstream(store));
  ASSERT_EQ(j["digests"].size(), 1u);
  j["digests"][0]["sha256"] = "planted";
  std::ofstream(store) << j.dump();
  EXPECT_EQ(glrc::identify::remembered_files_digest(files, store, later), "planted");
  // The library rewritten (same size, same inode): its change time moves, it is hashed again.
  std::ofstream(lib_) << "driver code, version 2";
  const std::string rebuilt = glrc::identify::files_digest(files);
  EXPECT_NE(rebuilt, real);
  EXPECT_EQ(glrc::identify::remembered_files_digest(files, store, later + std::chrono::minutes(1)),
            rebuilt);
  // A store that is not ours, or a file that is gone: hashed as before, never an error.
  std::ofstream(store) << "{ not json";
  EXPECT_EQ(glrc::identify::remembered_files_digest(files, store, later), rebuilt);
  EXPECT_EQ(glrc::identify::remembered_files_digest({(dir_ / "missing.so").string()}, store), "");
}

TEST_F(ModelCache, FileFollowsXdgCacheHome) {
  const char* old_xdg = std::getenv("XDG_CACHE_HOME");
  const std::string saved = old_xdg ? old_xdg : "";
  setenv("XDG_CACHE_HOME", dir_.c_str(), 1);
  EXPECT_EQ(glrc::identify::model_cache_file(), dir_ / "glrefcheck" / "models.json");
  setenv("XDG_CACHE_HOME", "relative/path", 1);  // invalid by the specification: ignored
  if (const char* home = std::getenv("HOME")) {
    EXPECT_EQ(glrc::identify::model_cache_file(), fs::path(home) / ".cache/glrefcheck/models.json");
  }
  if (old_xdg)
    setenv("XDG_CACHE_HOME", saved.c_str(), 1);
  else
    unsetenv("XDG_CACHE_HOME");
}

TEST(ModelJson, RoundTripsAndRejectsNonsense) {
  const auto j = glrc::identify::model_json(softpipe_model());
  EXPECT_EQ(j.dump(), R"({"planes":"unsnapped","subpixel_bits":0,"tie_break":"bottom-right"})");
  EXPECT_EQ(glrc::identify::model_from_json(j)->describe(), softpipe_model().describe());
  EXPECT_FALSE(glrc::identify::model_from_json(nlohmann::json::parse(
      R"({"planes":"unsnapped","subpixel_bits":17,"tie_break":"bottom-right"})")));
  EXPECT_FALSE(glrc::identify::model_from_json(
      nlohmann::json::parse(R"({"planes":"unsnapped","subpixel_bits":4,"tie_break":"left"})")));
  EXPECT_FALSE(glrc::identify::model_from_json(nlohmann::json::parse(R"({"subpixel_bits":4})")));
}

// --- which model: the precedence ---------------------------------------------------------

TEST(ModelChoice, IdentifiedUnlessTheCommandLineSaysOtherwise) {
  Options o;  // the defaults: --model identified
  EXPECT_FALSE(glrc::cli::model_from_command_line(o)) << "the default is to identify";

  Options ideal;
  ideal.model.name = "ideal";
  const auto fixed = glrc::cli::model_from_command_line(ideal);
  ASSERT_TRUE(fixed);
  EXPECT_EQ(fixed->source, "default");
  EXPECT_EQ(fixed->model.describe(), "subpixel_bits=8 planes=unsnapped tie=bottom-left");

  // Any of --subpixel-bits, --planes, --tie-break: the command line's model, with either
  // --model identified or ideal, the options not given at their fixed defaults.
  for (const char* model : {"identified", "ideal"}) {
    Options typed;
    typed.model.name = model;
    typed.model.tie_break = TieBreak::top_left;
    typed.model.given = true;
    const auto chosen = glrc::cli::model_from_command_line(typed);
    ASSERT_TRUE(chosen) << model;
    EXPECT_EQ(chosen->source, "command line");
    EXPECT_EQ(chosen->model.describe(), "subpixel_bits=8 planes=unsnapped tie=top-left");
  }

  // A driver model is the command line's too.
  Options driver;
  driver.model.name = "softpipe";
  ASSERT_TRUE(glrc::cli::model_from_command_line(driver));
  EXPECT_EQ(glrc::cli::model_from_command_line(driver)->source, "command line");

  // A failed identification: the fixed default model, saying why on one line.
  const auto fallback = glrc::cli::fallback_model(o, "worker killed\nby signal 9");
  EXPECT_EQ(fallback.source, "default (identify failed: worker killed by signal 9)");
  EXPECT_EQ(fallback.model.describe(), "subpixel_bits=8 planes=unsnapped tie=bottom-left");
}

TEST(ModelChoice, SetModelIsWhatModelOfReads) {
  Options o;
  o.model.set_reference_model(softpipe_model());
  EXPECT_EQ(o.model.reference_model().describe(), softpipe_model().describe());
  // The workers get the options as JSON: whether the model was typed travels with them.
  o.model.given = true;
  EXPECT_TRUE(glrc::cli::options_from_json(glrc::cli::options_json(o)).model.given);
}

// --- end to end --------------------------------------------------------------------------

// pixel_centre_edges and shared_diagonal_centres put pixel centres exactly on edges: softpipe
// takes right edges, so under the fixed default model (bottom-left) they show 126 + 247
// coverage mismatches at edges, none under its own. Two cases and two workers: the second
// worker waits for the model the first one identifies.
class ModelCli : public glrc::test::TempDirTest {
 protected:
  nlohmann::json run(const std::string& args, std::string* out = nullptr) {
    const Outcome o = glrefcheck(
        "run --filter '^(pixel_centre_edges|shared_diagonal_centres)$' --jobs 2 --out '" +
            (dir_ / "out").string() + "' " + args,
        "XDG_CACHE_HOME='" + (dir_ / "cache").string() + "'");
    EXPECT_EQ(o.exit_code, 0) << args << "\n" << o.out << o.err;
    if (out) *out = o.out;
    const auto j = nlohmann::json::parse(std::ifstream(dir_ / "out" / "results.json"));
    at_edges_ = 0;
    for (const auto& c : j["cases"])
      at_edges_ += c["coverage"]["boundary"].get<int>();
    return j["run"];
  }
  int at_edges_ = -1;
};

TEST_F(ModelCli, SoftpipeRunIsJudgedByItsIdentifiedModel) {
  std::string out;
  nlohmann::json info = run("--driver softpipe", &out);
  EXPECT_EQ(info["model"], "subpixel_bits=0 planes=unsnapped tie=bottom-right");
  EXPECT_EQ(info["model_source"], "identify");
  EXPECT_NE(out.find("model subpixel_bits=0 planes=unsnapped tie=bottom-right from identify |"),
            std::string::npos)
      << out;
  EXPECT_EQ(at_edges_, 0);
  const fs::path cache = dir_ / "cache" / "glrefcheck" / "models.json";
  ASSERT_TRUE(fs::exists(cache));

  info = run("--driver softpipe");
  EXPECT_EQ(info["model"], "subpixel_bits=0 planes=unsnapped tie=bottom-right");
  EXPECT_EQ(info["model_source"], "identify (cached)");

  // A corrupt cache: identified again, and the file rewritten.
  std::ofstream(cache) << "{\"format\": 1, \"models\": [";
  info = run("--driver softpipe");
  EXPECT_EQ(info["model_source"], "identify");
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(cache))["models"].size(), 1u);

  // The command line overrides.
  info = run("--driver softpipe --tie-break top-left", &out);
  EXPECT_EQ(info["model"], "subpixel_bits=8 planes=unsnapped tie=top-left");
  EXPECT_EQ(info["model_source"], "command line");
  EXPECT_NE(out.find("from command line"), std::string::npos) << out;
  info = run("--driver softpipe --model ideal");
  EXPECT_EQ(info["model"], "subpixel_bits=8 planes=unsnapped tie=bottom-left");
  EXPECT_EQ(info["model_source"], "default");
  EXPECT_EQ(at_edges_, 126 + 247);
}

// A driver that dies identifying itself does not lose the run: the fixed default model judges
// it, and says why.
TEST_F(ModelCli, FailedIdentificationFallsBackToTheDefaultModel) {
  const Outcome o =
      glrefcheck("run --filter '^face_on' --jobs 2 --out '" + (dir_ / "out").string() + "'" +
                     proxied_workers("--crash-on-identify"),
                 "XDG_CACHE_HOME='" + (dir_ / "cache").string() + "'");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  const auto j = nlohmann::json::parse(std::ifstream(dir_ / "out" / "results.json"));
  EXPECT_EQ(j["run"]["model"], "subpixel_bits=8 planes=unsnapped tie=bottom-left");
  EXPECT_EQ(j["run"]["model_source"].get<std::string>().rfind(
                "default (identify failed: its worker killed by signal 6", 0),
            0u)
      << j["run"]["model_source"];
  EXPECT_EQ(j["summary"]["pass"], j["summary"]["total"]);
  EXPECT_FALSE(fs::exists(dir_ / "cache" / "glrefcheck" / "models.json"));
}

TEST_F(ModelCli, DiffSaysWhichModelJudgedIt) {
  const Outcome o = glrefcheck("diff cases/pixel_centre_edges.json --driver softpipe --out '" +
                                   (dir_ / "diff").string() + "'",
                               "XDG_CACHE_HOME='" + (dir_ / "cache").string() + "'");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  EXPECT_NE(o.out.find("model subpixel_bits=0 planes=unsnapped tie=bottom-right from identify |"),
            std::string::npos)
      << o.out;
}

}  // namespace
