// The C reproducer's GL_DEPTH_CLAMP and glPolygonOffset / glPolygonOffsetClamp, as text and
// without GL: the scene's fields (the floats as hexadecimal literals that read back exactly, with
// their decimals), the runtime's calls (enabled after the capabilities it turns off, the clamp
// looked up only for a scene that needs it, one line when it is missing), and the file compiling
// with cc -std=c99 -Wall -Wextra -pedantic -Werror. tests/cli/test_export.cpp builds reproducers
// with the harness's shaders and runs them on Mesa.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "casefile/casefile.hpp"
#include "check/check.hpp"
#include "export/reproducer.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

using namespace glrc;

std::string source(const std::string& relative) {
  return std::string(GLRC_SOURCE_DIR) + "/" + relative;
}

// The harness's first draw as gl_harness/first_draw.hpp describes it: one triangle over a 4x4
// framebuffer, one flat float of 1.
Case first_draw() {
  Case c;
  c.name = "first draw";
  c.fb_width = c.fb_height = 4;
  c.viewport = {0, 0, 4, 4};
  c.varyings = {{"v", 1, Interpolation::flat}};
  for (const auto& clip : {std::array<float, 4>{-1, -1, 0, 1}, std::array<float, 4>{3, -1, 0, 1},
                           std::array<float, 4>{-1, 3, 0, 1}}) {
    Vertex v;
    v.clip = clip;
    v.values = {1.0f};
    c.vertices.push_back(v);
  }
  c.triangles = {{0, 1, 2}};
  return c;
}

// The C text of case `c` as `export --driver llvmpipe` judges it; placeholder GLSL (the text is
// not drawn here).
std::string c_text(const Case& c) {
  check::CheckOptions o;
  const Expectation expected = check::expectation_for(c, o, 8);
  const Tolerance tolerance = check::tolerance_for(c, o, 8);
  reproducer::CReproducerSetup setup;
  const reproducer::ReproducerShaders glsl{"/* vertex */",       "/* geometry */",
                                           "/* fragment */",     "/* fragment after geometry */",
                                           "/* count vertex */", "/* count geometry */"};
  setup.shaders = setup.first_draw_shaders = glsl;
  setup.first_draw = first_draw();
  setup.count_fragment = "/* count */";
  setup.trace_fragment = "/* trace */";
  setup.exported_by = "test";
  setup.model = o.model.describe();
  return reproducer::c_reproducer(c, expected, tolerance, setup);
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

// Whether the C99 hexadecimal literal `literal` is the float `want`, bit for bit.
bool reads_back(const std::string& literal, float want) {
  char* end = nullptr;
  const float read = float(std::strtod(literal.c_str(), &end));
  return *end == '\0' && std::bit_cast<uint32_t>(read) == std::bit_cast<uint32_t>(want);
}

class ReproducerStates : public glrc::test::TempDirTest {
 protected:
  // Compiles `text` (no linking: GL is opened at run time) with the flags tests/cli uses.
  void expect_compiles(const std::string& text, const std::string& name) {
    if (std::system("command -v cc >/dev/null 2>&1") != 0) GTEST_SKIP() << "no C compiler (cc)";
    const std::string file = (dir_ / (name + ".c")).string();
    std::ofstream(file) << text;
    const std::string compile = "cc -std=c99 -Wall -Wextra -pedantic -Werror -c -o '" +
                                (dir_ / (name + ".o")).string() + "' '" + file + "'";
    EXPECT_EQ(std::system(compile.c_str()), 0) << compile;
  }
};

TEST_F(ReproducerStates, DepthClampIsTheScenesField) {
  Case c = casefile::load(source("cases/face_on.json"));
  c.vertices[2].clip[2] = 1.6f;  // beyond the far plane: drawn only under GL_DEPTH_CLAMP
  c.depth_clamp = true;
  const std::string text = c_text(c);
  // The case's scene enables it, the first draw's does not; neither has a polygon offset.
  EXPECT_EQ(occurrences(text, "\n    .depth_clamp = 1,\n"), 1u);
  EXPECT_EQ(occurrences(text, "\n    .depth_clamp = 0,\n"), 1u);
  EXPECT_EQ(text.find("    .polygon_offset = "), std::string::npos);
  EXPECT_LT(text.find("static const struct scene THE_CASE"), text.find(".depth_clamp = 1,"));
  EXPECT_LT(text.find(".depth_clamp = 1,"), text.find("static const struct scene FIRST_DRAW"));
  expect_compiles(text, "depth_clamp");

  c.depth_clamp = false;
  EXPECT_EQ(occurrences(c_text(c), "\n    .depth_clamp = 0,\n"), 2u);
}

TEST_F(ReproducerStates, PolygonOffsetIsTheScenesFieldInHexadecimal) {
  Case c = casefile::load(source("cases/face_on.json"));
  c.polygon_offset = PolygonOffset{2.0f, 4.0f, std::nullopt};
  std::string text = c_text(c);
  EXPECT_NE(
      text.find("\n    .polygon_offset = {1, 0x1p+1, 0x1p+2, 0, 0}, /* factor 2, units 4 */\n"),
      std::string::npos)
      << text.substr(text.find("static const struct scene THE_CASE"), 1200);
  EXPECT_EQ(occurrences(text, "    .polygon_offset = "), 1u);  // not the first draw's
  EXPECT_EQ(occurrences(text, "\n    .depth_clamp = 0,\n"), 2u);
  expect_compiles(text, "polygon_offset");

  // glPolygonOffsetClamp: the clamp and its flag; numbers that are no short decimals exactly.
  c.polygon_offset = PolygonOffset{-0.1f, 1.0f, 0.0005f};
  text = c_text(c);
  const std::string field = "\n    .polygon_offset = {1, ";
  const size_t at = text.find(field);
  ASSERT_NE(at, std::string::npos);
  const std::string line = text.substr(at + 1, text.find('\n', at + 1) - at - 1);
  EXPECT_EQ(line,
            "    .polygon_offset = {1, -0x1.99999ap-4, 0x1p+0, 1, 0x1.0624dep-11}, /* factor "
            "-0.100000001, units 1, clamp 0.000500000024 */");
  EXPECT_TRUE(reads_back("-0x1.99999ap-4", -0.1f));
  EXPECT_TRUE(reads_back("0x1.0624dep-11", 0.0005f));
  expect_compiles(text, "polygon_offset_clamp");
}

// The runtime every reproducer holds: both states set with the others the case controls, after
// the capabilities it turns off (which must not name them), glPolygonOffsetClamp looked up only
// for a scene whose offset is clamped, by the name GL 4.6 or an extension gives (Mesa answers a
// name it lacks with a stub that fails with GL_INVALID_OPERATION: softpipe, GL 3.3, has
// neither), with one line where GL has none.
TEST_F(ReproducerStates, RuntimeSetsBothStates) {
  const std::string text = c_text(casefile::load(source("cases/face_on.json")));
  const size_t caps = text.find("static const GLenum caps_off[] = {");
  ASSERT_NE(caps, std::string::npos);
  const std::string caps_off = text.substr(caps, text.find("};", caps) - caps);
  EXPECT_EQ(caps_off.find("GL_DEPTH_CLAMP"), std::string::npos) << caps_off;
  EXPECT_EQ(caps_off.find("GL_POLYGON_OFFSET_FILL"), std::string::npos) << caps_off;
  const size_t turned_off = text.find("glDisable(caps_off[k]);");
  for (const char* call :
       {"  if (s->depth_clamp)\n    glEnable(GL_DEPTH_CLAMP);\n  else\n    "
        "glDisable(GL_DEPTH_CLAMP);\n",
        "  if (s->polygon_offset.enabled) {\n    glEnable(GL_POLYGON_OFFSET_FILL);\n",
        "      glPolygonOffsetClamp(s->polygon_offset.factor, s->polygon_offset.units,\n"
        "                           s->polygon_offset.clamp);\n",
        "      glPolygonOffset(s->polygon_offset.factor, s->polygon_offset.units);\n",
        "    glDisable(GL_POLYGON_OFFSET_FILL);\n"}) {
    const size_t where = text.find(call);
    EXPECT_NE(where, std::string::npos) << call;
    EXPECT_LT(where, turned_off) << call;
  }
  for (const char* lookup :
       {"  if (s->polygon_offset.clamped && !glPolygonOffsetClamp) {\n",
        "    if (gl_integer(GL_MAJOR_VERSION) * 10 + gl_integer(GL_MINOR_VERSION) >= 46 ||\n"
        "        gl_extension(\"GL_ARB_polygon_offset_clamp\"))\n"
        "      name = \"glPolygonOffsetClamp\";\n"
        "    else if (gl_extension(\"GL_EXT_polygon_offset_clamp\"))\n"
        "      name = \"glPolygonOffsetClampEXT\";\n",
        "    if (name) glPolygonOffsetClamp = (pfn_glPolygonOffsetClamp)get_proc_address(name);\n",
        "      set_error(\"the GL context has no glPolygonOffsetClamp (GL 4.6, "
        "GL_ARB_polygon_offset_clamp \"\n                \"or GL_EXT_polygon_offset_clamp)\");\n",
        "glGetStringi(GL_EXTENSIONS, (GLuint)k)"})
    EXPECT_NE(text.find(lookup), std::string::npos) << lookup;
  // glPolygonOffset is GL 1.1's, loaded with every other function.
  EXPECT_NE(text.find("  X(void, PolygonOffset, (GLfloat factor, GLfloat units))"),
            std::string::npos);
}

}  // namespace
