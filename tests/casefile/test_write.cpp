// Writing a Case as a case file (casefile/write.hpp): load(to_case_file(c)) is c, every field and
// every float bit, for the whole suite and for floats that a decimal JSON number cannot carry.
#include <bit>
#include <cfloat>
#include <cmath>
#include <vector>

#include "casefile/write.hpp"
#include "tests/casefile/test_helpers.hpp"

namespace glrc::casefile::test {
namespace {

namespace fs = std::filesystem;

uint64_t dbits(double d) {
  return std::bit_cast<uint64_t>(d);
}

void expect_same_double(const std::optional<double>& a, const std::optional<double>& b,
                        const char* what) {
  ASSERT_EQ(a.has_value(), b.has_value()) << what;
  if (a) {
    EXPECT_EQ(dbits(*a), dbits(*b)) << what;
  }
}

// Every field the case-file format has (all but source_path), floats by their bits.
void expect_same(const Case& a, const Case& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
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
  EXPECT_EQ(std::bit_cast<uint32_t>(a.depth_clear), std::bit_cast<uint32_t>(b.depth_clear));
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
      ASSERT_EQ(bits(a.vertices[i].clip[k]), bits(b.vertices[i].clip[k]))
          << "vertex " << i << " clip " << k;
    ASSERT_EQ(a.vertices[i].values.size(), b.vertices[i].values.size()) << "vertex " << i;
    for (size_t k = 0; k < a.vertices[i].values.size(); ++k)
      ASSERT_EQ(bits(a.vertices[i].values[k]), bits(b.vertices[i].values[k]))
          << "vertex " << i << " value " << k;
  }
  EXPECT_EQ(a.triangles, b.triangles);
  expect_same_double(a.tolerance.varying_ulps, b.tolerance.varying_ulps, "varying_ulps");
  expect_same_double(a.tolerance.depth_ulps, b.tolerance.depth_ulps, "depth_ulps");
  EXPECT_EQ(a.tolerance.allow_boundary, b.tolerance.allow_boundary);
}

class WriteTest : public CaseFileTest {
 protected:
  // `c` written to <tmp>/out/<name>.json (its stem is the case's name) and loaded back.
  Case round_trip(const Case& c) {
    const std::string text = to_case_file(c);
    EXPECT_FALSE(text.empty());
    if (!text.empty()) {
      EXPECT_EQ(text.back(), '\n');
    }
    EXPECT_EQ(to_case_file(c), text);  // deterministic
    return load(write("out/" + c.name + ".json", text));
  }
};

TEST_F(WriteTest, EverySuiteCaseWritesAndLoadsBackUnchanged) {
  size_t n = 0;
  for (const fs::path& file : collect({GLRC_SOURCE_DIR "/cases"})) {
    SCOPED_TRACE(file.string());
    const Case c = load(file);
    const Case back = round_trip(c);
    expect_same(back, c);
    // Writing the loaded-back case gives the same text.
    EXPECT_EQ(to_case_file(back), to_case_file(c));
    ++n;
  }
  EXPECT_GT(n, 50u);
}

// Floats that a decimal JSON number read through a double cannot carry, or only by luck.
const std::vector<float> kHostile = {
    -0.0f,
    0x1p-149f,  // the smallest subnormal
    FLT_MAX,
    -FLT_MAX,
    0.1f,
    1e-30f,
    1e30f,
    16777215.0f,
    0x1.fffffep-1f,  // the float below 1
    std::nextafter(1.0f, 2.0f),
    -0x1.fffffcp-127f,  // the largest subnormal, negative
    0x1p-126f,          // the smallest normal
    std::nextafter(FLT_MAX, 0.0f),
    -0.1f,
    0x1.8p-3f,
    -0.734375f,
    1024.0f,
    0.0f,
    3.0f,
    1e-6f,
    -16777216.0f,
    0.3f,
    2.5e-38f,
};

Case hostile_case() {
  Case c;
  c.name = "hostile";
  c.description = "hostile floats: \"quoted\", back\\slash and unicode \xc3\xbc";
  c.fb_width = 96;
  c.fb_height = 80;
  // Fractional bounds (glViewportIndexedf), one of them no short decimal.
  c.viewport = {13.25f, 0.1f, 48.5f, 40.0f};
  c.depth_near = 0x1.fffffep-1f;
  c.depth_far = 0x1p-149f;
  c.cull = CullFace::front_and_back;
  c.front_face = FrontFace::cw;
  c.provoking = ProvokingVertex::first;
  c.depth_func = DepthFunc::gequal;
  c.depth_clear = 0.25f;
  c.work_arounds = false;
  c.varyings = {{"a", 1, Interpolation::flat},
                {"bb", 2, Interpolation::noperspective},
                {"c3", 3, Interpolation::smooth},
                {"_d", 4, Interpolation::smooth}};
  const size_t n = kHostile.size();
  for (size_t i = 0; i < 2 * n; ++i) {
    Vertex v;
    v.clip = {kHostile[i % n], kHostile[(i + 1) % n], kHostile[(i + 2) % n], kHostile[(i + 3) % n]};
    for (size_t k = 0; k < 10; ++k)
      v.values.push_back(kHostile[(3 * i + k + 5) % n]);
    c.vertices.push_back(v);
  }
  // noperspective needs w_c > 0 at every vertex a triangle uses.
  std::vector<uint32_t> positive_w;
  for (uint32_t i = 0; i < c.vertices.size(); ++i)
    if (c.vertices[i].clip[3] > 0) positive_w.push_back(i);
  for (size_t k = 0; k + 2 < positive_w.size(); ++k)
    c.triangles.push_back({positive_w[k + 2], positive_w[k], positive_w[k + 1]});
  c.triangles.push_back({positive_w[0], positive_w[0], positive_w[0]});
  c.tolerance.varying_ulps = 0.1;
  c.tolerance.depth_ulps = 0x1p-1074;  // the smallest subnormal double
  c.tolerance.allow_boundary = false;
  return c;
}

TEST_F(WriteTest, HostileFloatsComeBackBitForBit) {
  const Case c = hostile_case();
  const Case back = round_trip(c);
  expect_same(back, c);
  EXPECT_TRUE(std::signbit(back.vertices[0].clip[0]));
  EXPECT_EQ(bits(back.vertices[0].clip[1]), 1u);

  // Each float once as a clip coordinate and as a value of a varying of each size.
  const size_t n = kHostile.size();
  std::vector<bool> in_clip(n), in_value(n);
  for (size_t i = 0; i < c.vertices.size(); ++i)
    for (size_t k = 0; k < n; ++k) {
      for (float f : c.vertices[i].clip)
        if (bits(f) == bits(kHostile[k])) in_clip[k] = true;
      for (float f : c.vertices[i].values)
        if (bits(f) == bits(kHostile[k])) in_value[k] = true;
    }
  for (size_t k = 0; k < n; ++k) {
    EXPECT_TRUE(in_clip[k]) << k;
    EXPECT_TRUE(in_value[k]) << k;
  }
}

TEST_F(WriteTest, ExactFloatsArePlainNumbersOthersStrings) {
  Case c;
  c.name = "numbers";
  c.description = "d";
  c.varyings = {{"v", 1, Interpolation::smooth}};
  const std::vector<std::array<float, 4>> clips = {
      {0.5f, 3.0f, -0.734375f, 1024.0f}, {0.1f, 1e-30f, -0.0f, 1.0f}, {FLT_MAX, 0x1p-149f, 0, 1}};
  for (size_t i = 0; i < clips.size(); ++i)
    c.vertices.push_back({clips[i], {float(i)}});
  c.triangles = {{0, 1, 2}};
  const std::string text = to_case_file(c);
  EXPECT_NE(text.find("{\"clip\": [0.5, 3, -0.734375, 1024], \"v\": 0}"), std::string::npos)
      << text;
  EXPECT_NE(text.find("{\"clip\": [\"0.1\", \"1e-30\", \"-0.0\", 1], \"v\": 1}"), std::string::npos)
      << text;
  EXPECT_NE(text.find("{\"clip\": [\"3.4028235e+38\", \"1e-45\", 0, 1], \"v\": 2}"),
            std::string::npos)
      << text;
  // Defaults left out; framebuffer, viewport and triangles always written.
  EXPECT_EQ(text.find("depth_range"), std::string::npos);
  EXPECT_EQ(text.find("state"), std::string::npos);
  EXPECT_EQ(text.find("tolerance"), std::string::npos);
  EXPECT_NE(text.find("\"framebuffer\": {\"width\": 64, \"height\": 64}"), std::string::npos);
  EXPECT_NE(text.find("\"viewport\": {\"x\": 0, \"y\": 0, \"width\": 64, \"height\": 64}"),
            std::string::npos);
  EXPECT_NE(text.find("\"triangles\": [\n    [0, 1, 2]\n  ]"), std::string::npos) << text;
  expect_same(round_trip(c), c);
}

TEST_F(WriteTest, ToleranceKeepsNegativeZeroAndEveryDoubleBit) {
  Case c;
  c.name = "tol";
  c.description = "d";
  c.vertices = {{{-1, -1, 0, 1}, {}}, {{1, -1, 0, 1}, {}}, {{0, 1, 0, 1}, {}}};
  c.triangles = {{0, 1, 2}};
  c.tolerance.varying_ulps = -0.0;
  c.tolerance.depth_ulps = DBL_MAX;
  Case back = round_trip(c);
  expect_same(back, c);
  EXPECT_TRUE(std::signbit(*back.tolerance.varying_ulps));
  EXPECT_FALSE(back.tolerance.allow_boundary);

  c.tolerance = {};
  c.tolerance.depth_ulps = 1.0 / 3.0;
  c.tolerance.allow_boundary = true;
  back = round_trip(c);
  expect_same(back, c);
  EXPECT_FALSE(back.tolerance.varying_ulps);
}

TEST_F(WriteTest, ACaseTheLoaderRefusesIsWrittenAsIsAndTheLoaderSaysWhy) {
  Case c = hostile_case();
  for (int k = 0; k < 4; ++k)
    c.varyings.push_back({"e" + std::to_string(k), 1, Interpolation::flat});
  const std::string text = to_case_file(c);
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find("varyings: expected at most 7 varyings, got 8"), std::string::npos) << msg;
}

}  // namespace
}  // namespace glrc::casefile::test
