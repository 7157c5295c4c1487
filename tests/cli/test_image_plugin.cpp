// The image plugin (image_io/) as a user meets it: a glrefcheck that cannot load it still checks
// and reports, and says in one line what it tried; a stale one is refused by its version.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "image_io/glrc_images.h"
#include "tests/support/glrefcheck_process.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;

using glrc::test::glrefcheck;
using glrc::test::Outcome;

size_t lines(const std::string& s) {
  return size_t(std::count(s.begin(), s.end(), '\n'));
}

class ImagePlugin : public glrc::test::TempDirTest {};

TEST_F(ImagePlugin, DiffWithoutThePluginIsOneLineAndNoCrash) {
  const fs::path missing = dir_ / "no-such-plugin.so";
  const Outcome o = glrefcheck("diff cases/face_on.json --out '" + (dir_ / "diff").string() + "'",
                               "GLRC_IMAGES_PLUGIN='" + missing.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;  // a signal would read -1
  EXPECT_EQ(lines(o.err), 1u) << o.err;
  EXPECT_EQ(o.err.rfind("glrefcheck: cannot write ", 0), 0u) << o.err;
  EXPECT_NE(
      o.err.find("GLRC_IMAGES_PLUGIN: " + missing.string() + ": cannot open shared object file"),
      std::string::npos)
      << o.err;
  // The check itself ran and was printed before the images were attempted.
  EXPECT_NE(o.out.find("face_on"), std::string::npos) << o.out;
}

TEST_F(ImagePlugin, RunWithoutThePluginStillWritesItsResults) {
  const fs::path out = dir_ / "out";
  const Outcome o = glrefcheck(
      "run --filter '^(face_on|clip_noperspective_x_plane)$' --jobs 1 --out '" + out.string() + "'",
      "GLRC_IMAGES_PLUGIN='" + (dir_ / "no-such-plugin.so").string() + "'");
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;  // the clipper's NaN fails, as with images
  const auto results = nlohmann::json::parse(std::ifstream(out / "results.json"));
  ASSERT_EQ(results["cases"].size(), 2u) << results;
  for (const auto& c : results["cases"]) {
    if (c["name"] != "clip_noperspective_x_plane") continue;
    EXPECT_EQ(c["status"], "Fail") << c;
    EXPECT_NE(c["message"].get<std::string>().find("heatmaps not written: cannot write"),
              std::string::npos)
        << c;
  }
  EXPECT_FALSE(fs::exists(out / "cases/clip_noperspective_x_plane/n.x_error.png"));
}

TEST_F(ImagePlugin, AStalePluginIsRefusedByItsVersion) {
  const Outcome o = glrefcheck("diff cases/face_on.json --out '" + (dir_ / "diff").string() + "'",
                               "GLRC_IMAGES_PLUGIN='" GLRC_STALE_IMAGES_PLUGIN "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_EQ(lines(o.err), 1u) << o.err;
  EXPECT_NE(o.err.find("has ABI version " + std::to_string(GLRC_IMAGES_ABI_VERSION - 1) +
                       ", this glrefcheck needs " + std::to_string(GLRC_IMAGES_ABI_VERSION)),
            std::string::npos)
      << o.err;
}

// The plugin found the ordinary way (next to the executable, in the build tree) writes them.
TEST_F(ImagePlugin, DiffFindsThePluginWithoutBeingTold) {
  const Outcome o = glrefcheck("diff cases/face_on.json --out '" + (dir_ / "diff").string() + "'",
                               "unset GLRC_IMAGES_PLUGIN;");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  EXPECT_TRUE(fs::exists(dir_ / "diff" / "coverage.png")) << o.out << o.err;
  EXPECT_TRUE(fs::exists(dir_ / "diff" / "depth_error.exr")) << o.out << o.err;
}

}  // namespace
