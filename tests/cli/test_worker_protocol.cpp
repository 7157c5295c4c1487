// The worker protocol's messages (cli/workers/protocol.hpp): GL's description crosses from the
// worker to the runner whole, and a job carries its case and model.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "casefile/casefile.hpp"
#include "casefile/wire.hpp"
#include "cli/workers/protocol.hpp"
#include "identify/model_cache.hpp"

namespace glrc::cli {
namespace {

TEST(WorkerProtocol, GlInfoRoundTripsWithEveryField) {
  gl::GlInfo info;
  info.vendor = "Mesa", info.renderer = "softpipe", info.version = "4.5 (Core Profile)";
  info.platform = "EGL surfaceless platform", info.library = "libEGL_mesa.so.0";
  info.subpixel_bits = 4;
  info.initial_provoking_vertex = ProvokingVertex::first;
  info.primitive_id_from_geometry_shader = true;  // the field the hello used to drop on the way
  info.warnings = {"first draw: pixel (0, 0) expected 0, got 1"};
  const nlohmann::json hello = hello_message(info, {"/x/swrast_dri.so"});
  const auto back = hello.at("hello").get<gl::GlInfo>();
  EXPECT_EQ(nlohmann::json(back), nlohmann::json(info));
  EXPECT_EQ(back.initial_provoking_vertex, ProvokingVertex::first);
  EXPECT_TRUE(back.primitive_id_from_geometry_shader);
  EXPECT_EQ(hello["hello"]["driver_files"], nlohmann::json::array({"/x/swrast_dri.so"}));

  nlohmann::json broken = hello["hello"];
  broken.erase("subpixel_bits");
  EXPECT_THROW(broken.get<gl::GlInfo>(), nlohmann::json::exception);
}

TEST(WorkerProtocol, AJobCarriesItsCaseAndModel) {
  const Case c = casefile::load(std::string(GLRC_SOURCE_DIR) + "/cases/flat_provoking_first.json");
  Model m;
  m.tie_break = TieBreak::top_right;
  const std::string line = job_line(7, c, true, m);
  ASSERT_EQ(line.back(), '\n');
  const auto job = nlohmann::json::parse(line);
  EXPECT_EQ(job.at("index"), 7);
  EXPECT_EQ(job.at("name"), "flat_provoking_first");
  EXPECT_TRUE(job.at("images").get<bool>());
  EXPECT_EQ(identify::model_from_json(job.at("model"))->describe(), m.describe());
  const Case back = casefile::from_wire(job.at("case"));
  EXPECT_EQ(back.triangles.size(), c.triangles.size());
  EXPECT_EQ(back.provoking, ProvokingVertex::first);

  const CaseResult r = unfinished_result(c, Status::timeout, "no result after 2 s", 2.5);
  EXPECT_EQ(r.name, c.name);
  EXPECT_EQ(r.status, Status::timeout);
  EXPECT_EQ(r.outcome, Status::timeout);
  EXPECT_EQ(r.seconds, 2.5);
}

// A result line is JSON of the protocol's fields, and read_result_line takes back what
// result_line put in; any other line is not a result line.
TEST(WorkerProtocol, ResultLinesRoundTrip) {
  const std::string result = R"({"name":"a","channels":[{"x":1}]})";
  for (const bool images : {false, true}) {
    const std::string line = result_line(40213, result, images);
    const auto j = nlohmann::json::parse(line);
    EXPECT_EQ(j.at("index").get<size_t>(), 40213u);
    EXPECT_EQ(j.value("images", false), images);
    EXPECT_EQ(j.at("result"), nlohmann::json::parse(result));
    const auto back = read_result_line(line);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->index, 40213u);
    EXPECT_EQ(back->images, images);
    EXPECT_EQ(back->result, result);
  }
  for (const char* other : {R"({"hello":{}})", R"({"images_done":3})", R"({"index":,"result":{}})",
                            R"({"index":3,"images":false,"result":{}})", R"({"index":3})",
                            R"({"index": 3, "result": {}})", "not JSON"})
    EXPECT_FALSE(read_result_line(other)) << other;
}

}  // namespace
}  // namespace glrc::cli
