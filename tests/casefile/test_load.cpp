// Loading valid case files: fields, defaults, and the float32 rounding rule for numbers.
#include <cfloat>
#include <cmath>

#include "tests/casefile/test_helpers.hpp"

namespace glrc::casefile::test {
namespace {

constexpr const char* kMinimal = R"({
  "description": "minimal",
  "vertices": [{"clip": [-1, -1, 0, 1]}, {"clip": [1, -1, 0.5, 1]}, {"clip": [0, 1, -0.5, 2]}]
})";

TEST_F(CaseFileTest, MinimalCaseTakesDefaults) {
  const auto path = write("tri_min.json", kMinimal);
  const Case c = load(path);
  EXPECT_EQ(c.name, "tri_min");
  EXPECT_EQ(c.source_path, path.string());
  EXPECT_EQ(c.description, "minimal");
  EXPECT_EQ(c.fb_width, 64);
  EXPECT_EQ(c.fb_height, 64);
  EXPECT_EQ(c.viewport.x, 0);
  EXPECT_EQ(c.viewport.y, 0);
  EXPECT_EQ(c.viewport.width, 64);
  EXPECT_EQ(c.viewport.height, 64);
  EXPECT_EQ(c.depth_near, 0.0f);
  EXPECT_EQ(c.depth_far, 1.0f);
  EXPECT_EQ(c.cull, CullFace::none);
  EXPECT_EQ(c.front_face, FrontFace::ccw);
  EXPECT_EQ(c.provoking, ProvokingVertex::last);
  EXPECT_EQ(c.depth_func, DepthFunc::always);
  EXPECT_TRUE(c.varyings.empty());
  ASSERT_EQ(c.vertices.size(), 3u);
  EXPECT_EQ(c.vertices[1].clip, (std::array<float, 4>{1, -1, 0.5f, 1}));
  EXPECT_EQ(c.vertices[2].clip, (std::array<float, 4>{0, 1, -0.5f, 2}));
  EXPECT_TRUE(c.vertices[0].values.empty());
  ASSERT_EQ(c.triangles.size(), 1u);
  EXPECT_EQ(c.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_FALSE(c.tolerance.varying_ulps);
  EXPECT_FALSE(c.tolerance.depth_ulps);
  EXPECT_FALSE(c.tolerance.allow_boundary);
}

TEST_F(CaseFileTest, EveryFieldIsRead) {
  const Case c = load_text(R"({
    "description": "all fields",
    "framebuffer": {"width": 96, "height": 64},
    "viewport": {"x": 13, "y": 7, "width": 48, "height": 40},
    "depth_range": {"near": 1, "far": 0.25},
    "state": {"cull": "front_and_back", "front_face": "cw", "provoking_vertex": "first",
              "depth_func": "less"},
    "varyings": [{"name": "color", "size": 3, "interpolation": "noperspective"},
                 {"name": "id", "size": 1, "interpolation": "flat"},
                 {"name": "uv", "size": 2},
                 {"name": "_q4", "interpolation": "smooth"}],
    "vertices": [
      {"clip": [-1, -1, 0, 1], "color": [1, 2, 3], "id": 7, "uv": [0.5, 0.25], "_q4": [1, 2, 3, 4]},
      {"clip": [1, -1, 0, 1], "color": [4, 5, 6], "id": [8], "uv": [1, 0], "_q4": [5, 6, 7, 8]},
      {"clip": [0, 1, 0, 1], "color": [7, 8, 9], "id": 9, "uv": [0, 1], "_q4": [9, 10, 11, 12]},
      {"clip": [1, 1, 0, 1], "color": [0, 0, 0], "id": 10, "uv": [1, 1], "_q4": [0, 0, 0, 0]}
    ],
    "triangles": [[0, 1, 2], [2, 1, 3]],
    "tolerance": {"varying_ulps": 512, "depth_ulps": 4.5, "allow_boundary": false}
  })");
  EXPECT_EQ(c.fb_width, 96);
  EXPECT_EQ(c.fb_height, 64);
  EXPECT_EQ(c.viewport.x, 13);
  EXPECT_EQ(c.viewport.y, 7);
  EXPECT_EQ(c.viewport.width, 48);
  EXPECT_EQ(c.viewport.height, 40);
  EXPECT_EQ(c.depth_near, 1.0f);
  EXPECT_EQ(c.depth_far, 0.25f);
  EXPECT_EQ(c.cull, CullFace::front_and_back);
  EXPECT_EQ(c.front_face, FrontFace::cw);
  EXPECT_EQ(c.provoking, ProvokingVertex::first);
  EXPECT_EQ(c.depth_func, DepthFunc::less);
  ASSERT_EQ(c.varyings.size(), 4u);
  EXPECT_EQ(c.varyings[0].name, "color");
  EXPECT_EQ(c.varyings[0].size, 3);
  EXPECT_EQ(c.varyings[0].interpolation, Interpolation::noperspective);
  EXPECT_EQ(c.varyings[1].size, 1);
  EXPECT_EQ(c.varyings[1].interpolation, Interpolation::flat);
  EXPECT_EQ(c.varyings[2].interpolation, Interpolation::smooth);  // the default
  EXPECT_EQ(c.varyings[3].size, 4);                               // the default
  EXPECT_EQ(c.component_count(), 10);
  ASSERT_EQ(c.vertices.size(), 4u);
  // Values are concatenated in the order of the varyings' declaration.
  EXPECT_EQ(c.vertices[1].values,
            (std::vector<float>{4, 5, 6, 8, 1, 0, 5, 6, 7, 8}));  // "id": [8] is a size-1 array
  EXPECT_EQ(c.vertices[0].values[3], 7.0f);                       // "id": 7, a bare number
  ASSERT_EQ(c.triangles.size(), 2u);
  EXPECT_EQ(c.triangles[1], (std::array<uint32_t, 3>{2, 1, 3}));
  EXPECT_EQ(c.tolerance.varying_ulps, 512.0);
  EXPECT_EQ(c.tolerance.depth_ulps, 4.5);
  EXPECT_EQ(c.tolerance.allow_boundary, false);
  const Tolerance t = c.tolerance.applied_to(Tolerance{});
  EXPECT_EQ(t.varying_ulps, 512.0);
}

TEST_F(CaseFileTest, FramebufferDefaultsToViewportExtent) {
  const Case c = load_text(R"({"description": "d",
    "viewport": {"x": 13, "y": 7, "width": 48, "height": 40},
    "vertices": [{"clip": [-1, -1, 0, 1]}, {"clip": [1, -1, 0, 1]}, {"clip": [0, 1, 0, 1]}]})");
  EXPECT_EQ(c.fb_width, 61);
  EXPECT_EQ(c.fb_height, 47);
  EXPECT_EQ(c.viewport.x, 13);
}

TEST_F(CaseFileTest, ViewportDefaultsToFramebuffer) {
  const Case c = load_text(R"({"description": "d", "framebuffer": {"width": 4096, "height": 1},
    "vertices": [{"clip": [-1, -1, 0, 1]}, {"clip": [1, -1, 0, 1]}, {"clip": [0, 1, 0, 1]}]})");
  EXPECT_EQ(c.viewport.x, 0);
  EXPECT_EQ(c.viewport.width, 4096);
  EXPECT_EQ(c.viewport.height, 1);
}

TEST_F(CaseFileTest, DefaultTrianglesAreConsecutiveTriples) {
  const Case c = load_text(R"({"description": "d", "vertices": [
    {"clip": [-1, -1, 0, 1]}, {"clip": [1, -1, 0, 1]}, {"clip": [0, 1, 0, 1]},
    {"clip": [-1, 1, 0, 1]}, {"clip": [1, 1, 0, 1]}, {"clip": [0, -1, 0, 1]}]})");
  ASSERT_EQ(c.triangles.size(), 2u);
  EXPECT_EQ(c.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(c.triangles[1], (std::array<uint32_t, 3>{3, 4, 5}));
}

TEST_F(CaseFileTest, NumberStringsGiveExactBits) {
  const Case c = load_text(R"({"description": "d", "varyings": [{"name": "v", "size": 4}],
    "vertices": [
      {"clip": ["0x1.8p-3", "-0x1.fffffep127", "0x1p-149", "1"], "v": ["0.1", 0.1, "-0X1P+0", "1e-3"]},
      {"clip": [16777217, "1.00000005960464477539062500001", 1.00000005960464477539062500001, 1],
       "v": ["0x1.000002p0", "-0.0", 1e-46, "3.4028235e38"]},
      {"clip": [0, 1, 0, 1], "v": [0, 0, 0, 0]}]})");
  const auto& v0 = c.vertices[0];
  EXPECT_EQ(bits(v0.clip[0]), 0x3e400000u);  // 0x1.8p-3 = 0.1875
  EXPECT_EQ(v0.clip[1], -FLT_MAX);
  EXPECT_EQ(bits(v0.clip[2]), 0x00000001u);    // the smallest subnormal
  EXPECT_EQ(bits(v0.values[0]), 0x3dcccccdu);  // 0.1f
  EXPECT_EQ(bits(v0.values[1]), 0x3dcccccdu);  // the JSON number 0.1 rounds to the same float
  EXPECT_EQ(v0.values[2], -1.0f);
  EXPECT_EQ(v0.values[3], 1e-3f);
  const auto& v1 = c.vertices[1];
  EXPECT_EQ(v1.clip[0], 16777216.0f);  // 2^24 + 1 rounds to even
  // Just above the midpoint between 1 and its float successor: strtof rounds up, whereas a JSON
  // number is first read as a double, which lands exactly on the midpoint, and then rounds to
  // even, down to 1. This is why the format offers strings for exact bits.
  EXPECT_EQ(bits(v1.clip[1]), 0x3f800001u);
  EXPECT_EQ(bits(v1.clip[2]), 0x3f800000u);
  EXPECT_EQ(bits(v1.values[0]), 0x3f800001u);
  EXPECT_EQ(bits(v1.values[1]), 0x80000000u);  // negative zero kept
  EXPECT_EQ(bits(v1.values[2]), 0x00000000u);  // underflows to zero
  EXPECT_EQ(v1.values[3], FLT_MAX);
}

TEST_F(CaseFileTest, JsonNumbersJustBelowFloatOverflowClampToFloatMax) {
  // 2^128 - 3*2^102 lies between FLT_MAX (2^128 - 2^104) and the midpoint to 2^128 (2^128 - 2^103),
  // so it rounds to FLT_MAX.
  const Case c = load_text(R"({"description": "d", "vertices": [
    {"clip": [3.4028235170913126e38, -1, 0, 1]}, {"clip": [1, -1, 0, 1]}, {"clip": [0, 1, 0, 1]}]})");
  EXPECT_EQ(c.vertices[0].clip[0], FLT_MAX);
}

TEST_F(CaseFileTest, NoperspectiveIsFineWhenOnlyUnusedVerticesHaveNegativeW) {
  const Case c = load_text(R"({"description": "d",
    "varyings": [{"name": "s", "size": 1, "interpolation": "noperspective"}],
    "vertices": [{"clip": [-1, -1, 0, 1], "s": 1}, {"clip": [1, -1, 0, 1], "s": 2},
                 {"clip": [0, 1, 0, 1], "s": 3}, {"clip": [0, 0, 0, -1], "s": 4}],
    "triangles": [[0, 1, 2]]})");
  EXPECT_EQ(c.vertices[3].clip[3], -1.0f);
}

TEST_F(CaseFileTest, SmoothAndFlatAllowVerticesBehindTheEye) {
  const Case c = load_text(R"({"description": "d",
    "varyings": [{"name": "s", "size": 1}, {"name": "f", "size": 2, "interpolation": "flat"}],
    "vertices": [{"clip": [-1, -1, 0, 1], "s": 1, "f": [1, 2]},
                 {"clip": [1, -1, 0, -1], "s": 2, "f": [3, 4]},
                 {"clip": [0, 1, 0, 0], "s": 3, "f": [5, 6]}]})");
  EXPECT_EQ(c.vertices[1].clip[3], -1.0f);
}

TEST_F(CaseFileTest, ClipVerticesMayMixWithPositionsWhenATransformIsGiven) {
  const Case c = load_text(R"({"description": "d", "transform": {},
    "vertices": [{"position": [0.5, 0.25, 0.125]}, {"clip": [1, -1, 0, 2]},
                 {"position": [0, 1, 0, 0.5]}]})");
  // An empty transform is the identity; a 3-component position gets w = 1.
  EXPECT_EQ(c.vertices[0].clip, (std::array<float, 4>{0.5f, 0.25f, 0.125f, 1}));
  EXPECT_EQ(c.vertices[1].clip, (std::array<float, 4>{1, -1, 0, 2}));
  EXPECT_EQ(c.vertices[2].clip, (std::array<float, 4>{0, 1, 0, 0.5f}));
}

}  // namespace
}  // namespace glrc::casefile::test
