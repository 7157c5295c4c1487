// The loaded case as `run` hands it to a worker (casefile/wire.hpp): the worker's case must be
// the runner's, every field and every float bit, so that a case file is parsed once per run.
#include <bit>
#include <cmath>
#include <cstdint>

#include "casefile/wire.hpp"
#include "tests/casefile/test_helpers.hpp"

namespace glrc::casefile::test {
namespace {

namespace fs = std::filesystem;

void expect_same(const Case& a, const Case& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.source_path, b.source_path);
  EXPECT_EQ(a.fb_width, b.fb_width);
  EXPECT_EQ(a.fb_height, b.fb_height);
  EXPECT_EQ(a.viewport.x, b.viewport.x);
  EXPECT_EQ(a.viewport.y, b.viewport.y);
  EXPECT_EQ(a.viewport.width, b.viewport.width);
  EXPECT_EQ(a.viewport.height, b.viewport.height);
  EXPECT_EQ(bits(a.depth_near), bits(b.depth_near));
  EXPECT_EQ(bits(a.depth_far), bits(b.depth_far));
  EXPECT_EQ(a.cull, b.cull);
  EXPECT_EQ(a.front_face, b.front_face);
  EXPECT_EQ(a.clip_origin, b.clip_origin);
  EXPECT_EQ(a.clip_depth, b.clip_depth);
  EXPECT_EQ(a.depth_clamp, b.depth_clamp);
  EXPECT_EQ(offset_bits(a.polygon_offset), offset_bits(b.polygon_offset));
  EXPECT_EQ(a.provoking, b.provoking);
  EXPECT_EQ(a.depth_func, b.depth_func);
  EXPECT_EQ(bits(a.depth_clear), bits(b.depth_clear));
  EXPECT_EQ(a.work_arounds, b.work_arounds);
  ASSERT_EQ(a.varyings.size(), b.varyings.size());
  for (size_t i = 0; i < a.varyings.size(); ++i) {
    EXPECT_EQ(a.varyings[i].name, b.varyings[i].name);
    EXPECT_EQ(a.varyings[i].size, b.varyings[i].size);
    EXPECT_EQ(a.varyings[i].interpolation, b.varyings[i].interpolation);
  }
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (size_t i = 0; i < a.vertices.size(); ++i) {
    for (size_t k = 0; k < 4; ++k)
      ASSERT_EQ(bits(a.vertices[i].clip[k]), bits(b.vertices[i].clip[k])) << i;
    ASSERT_EQ(a.vertices[i].values.size(), b.vertices[i].values.size());
    for (size_t k = 0; k < a.vertices[i].values.size(); ++k)
      ASSERT_EQ(bits(a.vertices[i].values[k]), bits(b.vertices[i].values[k])) << i;
  }
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.draws, b.draws);
  EXPECT_EQ(a.scissor, b.scissor);
  EXPECT_EQ(a.tolerance.varying_ulps, b.tolerance.varying_ulps);
  EXPECT_EQ(a.tolerance.depth_ulps, b.tolerance.depth_ulps);
  EXPECT_EQ(a.tolerance.allow_boundary, b.tolerance.allow_boundary);
}

TEST_F(CaseFileTest, EverySuiteCaseCrossesTheWireUnchanged) {
  size_t n = 0;
  for (const fs::path& file : collect({GLRC_SOURCE_DIR "/cases"})) {
    const Case c = load(file);
    // Through text, as the job line goes to the worker.
    expect_same(from_wire(nlohmann::json::parse(to_wire(c).dump())), c);
    ++n;
  }
  EXPECT_GT(n, 50u);
}

TEST_F(CaseFileTest, WireKeepsNegativeZeroSubnormalsAndOverrides) {
  Case c = load_text(R"({"description": "d", "depth_range": {"near": 1, "far": 0.25},
    "state": {"cull": "back", "front_face": "cw", "provoking_vertex": "first", "depth_func": "notequal",
              "depth_clear": "0x1p-149"}, "work_arounds": false,
    "varyings": [{"name": "a", "size": 1, "interpolation": "flat"},
                 {"name": "b", "size": 3, "interpolation": "noperspective"}],
    "vertices": [{"clip": [-0.0, "0x1p-149", 0, 1], "a": -0.0, "b": [1, 2, 3]},
                 {"clip": [1, -1, 0, 1], "a": 1, "b": ["0x1.fffffep127", 0, 0]},
                 {"clip": [0, 1, 0, 1], "a": 2, "b": [0, 0, 0]}],
    "triangles": [[2, 1, 0], [0, 1, 2]],
    "tolerance": {"varying_ulps": 3.5, "allow_boundary": false}})");
  const Case back = from_wire(nlohmann::json::parse(to_wire(c).dump()));
  expect_same(back, c);
  EXPECT_TRUE(std::signbit(back.vertices[0].clip[0]));
  EXPECT_EQ(bits(back.vertices[0].clip[1]), 1u);
  EXPECT_FALSE(back.tolerance.depth_ulps);
  EXPECT_THROW(from_wire(nlohmann::json::object()), std::runtime_error);
}

}  // namespace
}  // namespace glrc::casefile::test
