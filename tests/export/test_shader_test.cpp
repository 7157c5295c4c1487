// export/shader_test's text without GL: what shader_runner cannot express is refused with one
// line, every float reads back as the same float32 (vertex data through strtod and a cast, as
// shader_runner reads it; GLSL ranges through strtof, as Mesa's GLSL lexer does) and the ranges
// are exactly the values `run` accepts, and the probes reach the pixels where Mesa 22.3.6 fails
// (tests/cli/export_shader_test.sh runs the files with shader_runner).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "campaign/random.hpp"
#include "casefile/casefile.hpp"
#include "check/check.hpp"
#include "compare/compare.hpp"
#include "export/shader_test.hpp"

namespace {

using namespace glrc;

std::string source(const std::string& relative) {
  return std::string(GLRC_SOURCE_DIR) + "/" + relative;
}

struct Exported {
  Case c;
  Expectation expected;
  Tolerance tolerance;
  reproducer::ShaderTest test;
};

// As `export --driver llvmpipe` (or softpipe) judges: that driver's model and reported bits.
check::CheckOptions options_for(bool softpipe, int* reported_bits) {
  check::CheckOptions o;
  *reported_bits = 8;
  if (softpipe) {
    o.model = Model{0, Planes::unsnapped, TieBreak::bottom_right};
    *reported_bits = 4;
  }
  return o;
}

Exported export_case(Case c, bool softpipe = false) {
  int bits = 0;
  const check::CheckOptions o = options_for(softpipe, &bits);
  Exported x{std::move(c), {}, {}, {}};
  x.expected = check::expectation_for(x.c, o, bits);
  x.tolerance = check::tolerance_for(x.c, o, bits);
  reproducer::ShaderTestSetup setup;
  setup.exported_by = "test";
  setup.model = o.model.describe();
  x.test = reproducer::shader_test(x.c, x.expected, x.tolerance, setup);
  return x;
}

Exported export_file(const std::string& relative, bool softpipe = false) {
  return export_case(casefile::load(source(relative)), softpipe);
}

// The lines of section [name], up to the next section.
std::vector<std::string> section(const std::string& text, const std::string& name) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '[') {
      inside = line == "[" + name + "]";
      continue;
    }
    if (inside) lines.push_back(line);
  }
  return lines;
}

struct Probe {
  std::array<float, 4> tolerance{};
  int x = 0, y = 0, w = 0, h = 0;
  std::array<float, 4> expected{};
};
std::vector<Probe> rect_probes(const std::string& text) {
  std::vector<Probe> probes;
  std::array<float, 4> tolerance{};
  for (const std::string& line : section(text, "test")) {
    if (std::sscanf(line.c_str(), "tolerance %f %f %f %f", &tolerance[0], &tolerance[1],
                    &tolerance[2], &tolerance[3]) == 4)
      continue;
    Probe p;
    p.tolerance = tolerance;
    if (std::sscanf(line.c_str(), "probe rect rgba (%d, %d, %d, %d) (%f, %f, %f, %f)", &p.x, &p.y,
                    &p.w, &p.h, &p.expected[0], &p.expected[1], &p.expected[2],
                    &p.expected[3]) == 8)
      probes.push_back(p);
  }
  return probes;
}

// Whether a probe requires `fragments` fragments at (x, y).
bool fragments_probed(const std::vector<Probe>& probes, int x, int y, int fragments) {
  for (const Probe& p : probes)
    if (x >= p.x && x < p.x + p.w && y >= p.y && y < p.y + p.h && p.tolerance[0] < 0.5f &&
        p.expected[0] == float(fragments))
      return true;
  return false;
}

// The integers of a GLSL constant array `const int NAME[...] = int[](...);`.
std::vector<long> int_array(const std::string& text, const std::string& name) {
  std::vector<long> values;
  const size_t at = text.find("const int " + name + "[");
  if (at == std::string::npos) return values;
  const size_t open = text.find("int[](", at) + 6, close = text.find(')', open);
  std::istringstream in(text.substr(open, close - open));
  std::string item;
  while (std::getline(in, item, ','))
    values.push_back(std::strtol(item.c_str(), nullptr, 10));
  return values;
}

bool accepted(float g, float e, double a) {
  return std::isfinite(g) && std::fabs(double(g) - double(e)) <= a;
}

TEST(ShaderTest, RefusesWhatShaderRunnerCannotExpressInOneLine) {
  const Case face_on = casefile::load(source("cases/face_on.json"));
  auto refusal = [](const Case& c) {
    const std::optional<std::string> why = reproducer::shader_test_state_refusal(c);
    EXPECT_TRUE(why.has_value()) << c.name;
    if (why) {
      EXPECT_EQ(why->find('\n'), std::string::npos) << *why;
    }
    return why.value_or("");
  };
  Case c = face_on;
  c.depth_near = 0.25f, c.depth_far = 0.75f;
  EXPECT_EQ(refusal(c),
            "depth_range (near 0.25, far 0.75) cannot be expressed in a shader_test: shader_runner "
            "has no glDepthRange command (only [0, 1])");
  c = face_on;
  c.cull = CullFace::front_and_back;
  EXPECT_EQ(refusal(c).rfind("cull front_and_back cannot be expressed in a shader_test: "
                             "shader_runner has no glCullFace command",
                             0),
            0u);
  c = face_on;
  c.cull = CullFace::back;
  c.depth_func = DepthFunc::less;
  EXPECT_EQ(refusal(c).rfind("cull back with depth_func less cannot be expressed in a "
                             "shader_test: shader_runner has no glCullFace command",
                             0),
            0u);
  c = face_on;
  c.clip_depth = ClipDepth::zero_to_one;
  EXPECT_EQ(refusal(c),
            "glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) cannot be expressed in a shader_test: "
            "shader_runner has no glClipControl command");
  c = face_on;
  c.front_face = FrontFace::cw;
  c.varyings.push_back(builtin_varying(Builtin::front_facing));
  EXPECT_EQ(refusal(c).rfind("gl_FrontFacing under glFrontFace(GL_CW) cannot be expressed", 0), 0u);
  c = face_on;
  c.clip_origin = ClipOrigin::upper_left;
  EXPECT_EQ(refusal(c).rfind("glClipControl(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE)", 0), 0u);
  c = face_on;
  c.triangles.assign(reproducer::kMaxShaderTestTriangles + 1, c.triangles.front());
  EXPECT_EQ(refusal(c),
            "4,097 triangles; a shader_test takes at most 4,096: shrink the case first (glrefcheck "
            "fuzz --replay ...)");
  c = face_on;
  c.fb_width = c.fb_height = 1024;
  EXPECT_EQ(refusal(c),
            "a 1024x1024 framebuffer; a shader_test takes at most 262,144 pixels: shrink the case "
            "first (glrefcheck fuzz --replay ...)");

  // Culling alone is drawn (by discard), with either front face.
  for (FrontFace f : {FrontFace::ccw, FrontFace::cw})
    for (CullFace cull : {CullFace::front, CullFace::back}) {
      c = face_on;
      c.cull = cull, c.front_face = f;
      EXPECT_FALSE(reproducer::shader_test_state_refusal(c).has_value());
    }

  // A driver model's bits are no range; shader_test() throws the refusal.
  Exported x = export_case(face_on);
  Tolerance exact = x.tolerance;
  exact.mode = ToleranceMode::exact;
  const auto why = reproducer::shader_test_refusal(x.c, x.expected, exact);
  ASSERT_TRUE(why.has_value());
  EXPECT_EQ(why->rfind("exact tolerance (a driver model's bits) cannot be expressed", 0), 0u);
  EXPECT_THROW(reproducer::shader_test(x.c, x.expected, exact, {}), std::invalid_argument);
  c = face_on;
  c.depth_near = 1, c.depth_far = 0;
  EXPECT_THROW(reproducer::shader_test(c, x.expected, x.tolerance, {}), std::invalid_argument);
}

// Vertex data and stated ranges of a case whose numbers are hard to write: random bit patterns,
// subnormals, -0, the largest floats, and decimals one digit from a midpoint.
TEST(ShaderTest, FloatsRoundTripExactly) {
  Case c;
  c.name = "hostile";
  c.description = "hostile floats";
  c.fb_width = c.fb_height = 4;
  c.viewport = {0, 0, 4, 4};
  c.varyings = {{"s", 4, Interpolation::smooth}, {"f", 4, Interpolation::flat}};
  std::vector<float> hostile = {-0.0f,
                                0x1p-149f,
                                -0x1p-149f,
                                0x1.fffffcp-127f,
                                std::numeric_limits<float>::max(),
                                -std::numeric_limits<float>::max(),
                                0.1f,
                                16777216.0f,
                                0x1.000002p0f,
                                3.4e38f,
                                1e-30f,
                                7.038531e-26f};
  campaign::Random random(2024);
  while (hostile.size() < 3 * 8 * 12) {
    const float v = std::bit_cast<float>(uint32_t(random.next()));
    if (std::isfinite(v)) hostile.push_back(v);
  }
  // Twelve triangles over the framebuffer, each vertex with eight hostile values.
  const std::array<std::array<float, 4>, 3> corners = {
      {{-1, -1, 0.25f, 1}, {3, -1, -0.5f, 1}, {-1, 3, 0.125f, 1}}};
  size_t next = 0;
  for (uint32_t t = 0; t < 12; ++t) {
    for (const auto& clip : corners) {
      Vertex v;
      v.clip = clip;
      v.clip[3] = 1.0f + float(t) * 0.0625f;
      for (int k = 0; k < 8; ++k)
        v.values.push_back(hostile[next++]);
      c.vertices.push_back(v);
    }
    c.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  const Exported x = export_case(c);

  // [vertex data]: a header, then x y z w, the eight values and the triangle, per vertex.
  const std::vector<std::string> rows = section(x.test.text, "vertex data");
  ASSERT_GE(rows.size(), 1 + c.vertices.size());
  EXPECT_EQ(rows[0], "a_clip/float/vec4 a0/float/vec4 a1/float/vec4 a_triangle/int/int");
  for (size_t v = 0; v < c.vertices.size(); ++v) {
    std::istringstream in(rows[1 + v]);
    std::vector<std::string> tokens;
    for (std::string t; in >> t;)
      tokens.push_back(t);
    ASSERT_EQ(tokens.size(), 13u) << rows[1 + v];
    for (size_t k = 0; k < 12; ++k) {
      // As shader_runner's strtof_hex: "0x" would be a bit pattern, so there is none.
      EXPECT_NE(tokens[k].rfind("0x", 0), 0u) << tokens[k];
      const float read = float(std::strtod(tokens[k].c_str(), nullptr));
      const float want = k < 4 ? c.vertices[v].clip[k] : c.vertices[v].values[k - 4];
      EXPECT_EQ(std::bit_cast<uint32_t>(read), std::bit_cast<uint32_t>(want))
          << "vertex " << v << " value " << k << ": " << tokens[k];
    }
    EXPECT_EQ(tokens[12], std::to_string(v / 3));
  }

  // Every pair is listed (16 pixels, one kept triangle each: at most 512 / 9 = 56), and each
  // range [lo, hi] is exactly the floats `run` accepts: lo and hi are, the floats beyond not.
  ASSERT_EQ(x.test.value_checks, x.test.value_pairs);
  const std::string& text = x.test.text;
  size_t at = text.find("const vec2 RANGE[CHECKS * CHANNELS] = vec2[](");
  ASSERT_NE(at, std::string::npos);
  const size_t ids = text.find("const ivec3 CHECK_AT[CHECKS] = ivec3[](");
  ASSERT_NE(ids, std::string::npos);
  size_t id_at = ids, checked = 0;
  const compare::UlpTable ulps(c);
  for (size_t n = 0; n < x.test.value_checks; ++n) {
    id_at = text.find("ivec3(", id_at + 6);
    int px = 0, py = 0, t = 0;
    ASSERT_EQ(std::sscanf(text.c_str() + id_at, "ivec3(%d, %d, %d)", &px, &py, &t), 3);
    const size_t i = x.expected.frame.index(px, py);
    ASSERT_EQ(x.expected.frame.primitive[i], t);
    for (Channel ch : channels_of(c.component_count())) {
      at = text.find("vec2(", at + 5);
      const char* p = text.c_str() + at + 5;
      char* end = nullptr;
      const float lo = std::strtof(p, &end);
      const float hi = std::strtof(end + 1, nullptr);
      const float e = x.expected.frame.values(ch)[i];
      const double a =
          compare::ChannelAllowance(c, x.expected, x.tolerance, ch).at(i, ulps.ulp(t, ch));
      if (!std::isfinite(e)) {
        EXPECT_GT(lo, hi);  // not judged
        continue;
      }
      EXPECT_TRUE(accepted(lo, e, a) && accepted(hi, e, a)) << lo << " " << e << " " << hi;
      if (lo > -std::numeric_limits<float>::max()) {
        EXPECT_FALSE(accepted(std::nextafter(lo, -INFINITY), e, a)) << lo << " " << e;
      }
      if (hi < std::numeric_limits<float>::max()) {
        EXPECT_FALSE(accepted(std::nextafter(hi, INFINITY), e, a)) << hi << " " << e;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 100u);
}

TEST(ShaderTest, ProbesReachThePixelsWhereMesaFails) {
  // The finite clipper variant: its one covered pixel, (0, 1), has a stated range.
  const Exported finite = export_file("cases/clip_noperspective_finite_wrong.json");
  EXPECT_EQ(finite.test.value_checks, 1u);
  EXPECT_NE(finite.test.text.find("ivec3(0, 1, 0));"), std::string::npos);

  // The clipper NaN at (63, 17): its values are checked for NaN (no free span holds it).
  const Exported nan = export_file("cases/clip_noperspective_x_plane.json");
  const std::vector<long> spans = int_array(nan.test.text, "FREE");
  ASSERT_FALSE(spans.empty());
  for (size_t s = 0; s + 1 < spans.size(); s += 2)
    EXPECT_FALSE(spans[s] <= 17 * 64 + 63 && 17 * 64 + 63 < spans[s + 1]);
  EXPECT_NE(nan.test.text.find("if (non_finite(v[k])) verdict |= 1u;"), std::string::npos);

  // softpipe's gap and double hit on a shared edge and its holes inside a steep edge: one
  // fragment required there.
  const Exported gap = export_file("tests/cli/data/softpipe_gap.json", true);
  EXPECT_TRUE(fragments_probed(rect_probes(gap.test.text), 13, 11, 1));
  const Exported hit = export_file("tests/cli/data/softpipe_double_hit.json", true);
  EXPECT_TRUE(fragments_probed(rect_probes(hit.test.text), 14, 4, 1));
  const Exported steep = export_file("cases/steep_edge_interior.json", true);
  const std::vector<Probe> probes = rect_probes(steep.test.text);
  for (const auto& [hx, hy] : {std::pair{56, 27}, {55, 38}, {54, 49}, {53, 60}})
    EXPECT_TRUE(fragments_probed(probes, hx, hy, 1)) << hx << ", " << hy;
  // Coverage decided at every pixel but the snapping band's, and the verdict everywhere.
  EXPECT_GT(steep.test.pixels_decided, size_t(59 * 93 - 100));
  EXPECT_NE(steep.test.text.find("tolerance 1e9 1e9 0.25 1e9\nprobe all rgba 0 0 0 1\n"),
            std::string::npos);
}

TEST(ShaderTest, StatesAsShaderRunnerCommands) {
  const std::string viewport = export_file("cases/viewport_offset.json").test.text;
  EXPECT_NE(viewport.find("GL_ARB_viewport_array\n"), std::string::npos);
  EXPECT_NE(viewport.find("viewport indexed 0 13 7 48 40\n"), std::string::npos);
  EXPECT_NE(viewport.find("SIZE 96 80\n"), std::string::npos);
  EXPECT_NE(
      export_file("cases/flat_provoking_first.json").test.text.find("provoking vertex first\n"),
      std::string::npos);
  const std::string less = export_file("cases/depth_less_overlap.json").test.text;
  for (const char* line : {"depthbuffer\n", "layout(early_fragment_tests) in;\n",
                           "clear depth 1\nclear\nenable GL_DEPTH_TEST\ndepthfunc GL_LESS\n"})
    EXPECT_NE(less.find(line), std::string::npos) << line;
  EXPECT_NE(
      export_file("cases/cull_front_cw.json").test.text.find("  if (!gl_FrontFacing) discard;\n"),
      std::string::npos);
  const std::string plain = export_file("cases/face_on.json").test.text;
  EXPECT_EQ(plain.rfind(reproducer::kShaderTestSignature, 0), 0u);
  for (const char* absent : {"viewport indexed", "provoking vertex", "depthbuffer", "discard"})
    EXPECT_EQ(plain.find(absent), std::string::npos) << absent;
}

// GL_DEPTH_CLAMP is shader_runner's `enable GL_DEPTH_CLAMP` (its enable table has it), before
// every draw of the case, the count without the depth test too (the near and far planes clip
// nothing there either); the depth judged is gl_FragCoord.z clamped to [0, 1], as the depth
// buffer the harness reads takes it (llvmpipe's gl_FragCoord.z is not clamped).
TEST(ShaderTest, DepthClampIsEnabledAndTheJudgedDepthClamped) {
  Case c = casefile::load(source("cases/face_on.json"));
  c.vertices[2].clip[2] = 1.6f;  // beyond the far plane: drawn only under GL_DEPTH_CLAMP
  c.depth_clamp = true;
  const std::string clamped = export_case(c).test.text;
  const std::vector<std::string> test = section(clamped, "test");
  const auto enable = std::find(test.begin(), test.end(), "enable GL_DEPTH_CLAMP");
  ASSERT_NE(enable, test.end()) << clamped;
  const auto first_draw = std::find_if(test.begin(), test.end(), [](const std::string& line) {
    return line.rfind("draw arrays ", 0) == 0;
  });
  EXPECT_LT(enable, first_draw);
  EXPECT_EQ(std::count(test.begin(), test.end(), "enable GL_DEPTH_CLAMP"), 1);
  EXPECT_NE(clamped.find("  float depth = isnan(gl_FragCoord.z) ? gl_FragCoord.z : "
                         "clamp(gl_FragCoord.z, 0.0, 1.0);\n"
                         "  float v[CHANNELS] = float[](depth, v0.x, v0.y, v0.z, v0.w);\n"),
            std::string::npos)
      << clamped;
  EXPECT_NE(clamped.find("# GL_DEPTH_CLAMP is enabled (`enable GL_DEPTH_CLAMP`)"),
            std::string::npos);

  // With a depth test: enabled before the count that runs without it.
  c.depth_func = DepthFunc::less;
  const std::string less = export_case(c).test.text;
  const size_t at = less.find("enable GL_DEPTH_CLAMP\n");
  ASSERT_NE(at, std::string::npos);
  EXPECT_LT(at, less.find("uniform int resolve 2\n"));
  EXPECT_LT(at, less.find("enable GL_DEPTH_TEST\n"));

  // Without it: neither, and gl_FragCoord.z as it comes.
  const std::string plain = export_file("cases/face_on.json").test.text;
  EXPECT_EQ(plain.find("GL_DEPTH_CLAMP"), std::string::npos);
  EXPECT_NE(plain.find("  float depth = gl_FragCoord.z;\n"), std::string::npos);
}

// shader_runner has no glPolygonOffset or glPolygonOffsetClamp command, and its `enable` takes
// no GL_POLYGON_OFFSET_FILL: a polygon offset, even of 0, is refused with one line naming it,
// before the reference is drawn, and shader_test() throws it.
TEST(ShaderTest, PolygonOffsetIsRefusedInOneLine) {
  const Case face_on = casefile::load(source("cases/face_on.json"));
  Case c = face_on;
  c.polygon_offset = PolygonOffset{2.0f, 4.0f, std::nullopt};
  EXPECT_EQ(reproducer::shader_test_state_refusal(c).value_or(""),
            "polygon_offset (factor 2, units 4) cannot be expressed in a shader_test: "
            "shader_runner has no glPolygonOffset command (and its `enable` takes no "
            "GL_POLYGON_OFFSET_FILL)");
  c.polygon_offset = PolygonOffset{-0.5f, 1.0f, 0.25f};
  EXPECT_EQ(reproducer::shader_test_state_refusal(c).value_or(""),
            "polygon_offset (factor -0.5, units 1, clamp 0.25) cannot be expressed in a "
            "shader_test: shader_runner has no glPolygonOffsetClamp command (and its `enable` "
            "takes no GL_POLYGON_OFFSET_FILL)");
  c.polygon_offset = PolygonOffset{};
  EXPECT_EQ(reproducer::shader_test_state_refusal(c).value_or("").rfind(
                "polygon_offset (factor 0, units 0) cannot be expressed in a shader_test", 0),
            0u);
  const Exported x = export_case(face_on);
  const auto why = reproducer::shader_test_refusal(c, x.expected, x.tolerance);
  ASSERT_TRUE(why.has_value());
  EXPECT_EQ(why->find('\n'), std::string::npos);
  EXPECT_THROW(reproducer::shader_test(c, x.expected, x.tolerance, {}), std::invalid_argument);
  // GL_DEPTH_CLAMP alone is no refusal.
  c = face_on;
  c.depth_clamp = true;
  EXPECT_FALSE(reproducer::shader_test_state_refusal(c).has_value());
}

TEST(ShaderTest, ValueChecksAreBounded) {
  // 4,096 pixels with five channels: 64 pairs; many channels: 512 ranges in all.
  const Exported face_on = export_file("cases/face_on.json");
  EXPECT_EQ(face_on.test.value_checks, reproducer::kMaxShaderTestValueChecks);
  EXPECT_GT(face_on.test.value_pairs, 1000u);
  const Exported mixed = export_file("cases/varyings_mixed.json");
  const size_t channels = size_t(mixed.c.component_count()) + 1;
  EXPECT_EQ(mixed.test.value_checks,
            reproducer::shader_test_value_checks(mixed.c.component_count()));
  EXPECT_LE(mixed.test.value_checks * channels, reproducer::kMaxShaderTestRanges);
  EXPECT_EQ(reproducer::shader_test_value_checks(1000), 1u);
  EXPECT_EQ(reproducer::shader_test_value_checks(0), reproducer::kMaxShaderTestValueChecks);
}

}  // namespace
