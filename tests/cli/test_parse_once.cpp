// `run` parses each case file once: the runner loads and validates it, and the worker process
// takes the loaded case from its job (casefile/wire.hpp) instead of reading the file again
// (issue 11: a 50 MB case was parsed twice per run). Here a worker gets a job whose file does
// not exist: it must check the case it was handed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "casefile/casefile.hpp"
#include "casefile/wire.hpp"
#include "cli/session.hpp"
#include "identify/model_cache.hpp"

namespace glrc::cli {
namespace {

namespace fs = std::filesystem;

// Runs `glrefcheck worker` with `input` on its stdin; its result lines.
std::string run_worker(const std::string& input) {
  const fs::path in = fs::temp_directory_path() / ("glrc_parse_once_" + std::to_string(getpid()));
  std::ofstream(in) << input;
  const std::string cmd =
      "'" GLRC_BINARY_DIR "/glrefcheck' worker < '" + in.string() + "' 2>/dev/null";
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;)
    out.append(buf, n);
  pclose(p);
  fs::remove(in);
  return out;
}

TEST(ParseOnce, TheWorkerChecksTheCaseItIsHandedNotTheFile) {
  Case c = casefile::load(GLRC_SOURCE_DIR "/cases/face_on.json");
  Options o;
  o.model.name = "ideal";
  o.out =
      (fs::temp_directory_path() / ("glrc_parse_once_out_" + std::to_string(getpid()))).string();
  const nlohmann::json job = {{"index", 0},
                              {"file", "/nonexistent/face_on.json"},
                              {"case", casefile::to_wire(c)},
                              {"name", c.name},
                              {"images", false},
                              {"model", identify::model_json(o.model.reference_model())}};
  const std::string out = run_worker(options_json(o) + "\n" + job.dump() + "\n");
  const size_t at = out.find("{\"index\":0,\"result\":");
  ASSERT_NE(at, std::string::npos) << out;
  const auto result = nlohmann::json::parse(out.substr(at, out.find('\n', at) - at));
  EXPECT_EQ(result["result"]["name"], "face_on");
  EXPECT_EQ(result["result"]["status"], "Pass") << result.dump();

  // Without "case" the worker reads the file, as before: here it does not exist.
  nlohmann::json file_only = job;
  file_only.erase("case");
  const std::string out2 = run_worker(options_json(o) + "\n" + file_only.dump() + "\n");
  EXPECT_NE(out2.find("\"status\":\"Error\""), std::string::npos) << out2;
  fs::remove_all(o.out);
}

}  // namespace
}  // namespace glrc::cli
