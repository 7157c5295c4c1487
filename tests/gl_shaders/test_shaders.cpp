// The GLSL text gl_harness draws with (gl_harness/shaders.hpp) and how its outputs meet the
// framebuffer's attachments (gl_harness/framebuffer.hpp), checked as text: no GL context, so
// these run on every machine, whatever GL it has. What the text does on a driver is
// tests/gl's part.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "gl_harness/framebuffer.hpp"
#include "gl_harness/shaders.hpp"

namespace glrc::gl {
namespace {

// Three varyings, one of each qualifier and of three sizes, named what GLSL would reject.
Case three_varyings() {
  Case c;
  c.name = "three";
  c.varyings = {{"color", 4, Interpolation::smooth},
                {"flat", 1, Interpolation::flat},
                {"in", 2, Interpolation::noperspective}};
  c.vertices = {{{-1, -1, 0, 1}, {0, 0, 0, 1, 7, 0, 0}},
                {{1, -1, 0, 1}, {1, 0, 0, 1, 7, 1, 0}},
                {{-1, 1, 0, 1}, {0, 1, 0, 1, 7, 0, 1}}};
  c.triangles = {{0, 1, 2}};
  return c;
}

bool has(const std::string& text, const std::string& line) {
  return text.find(line) != std::string::npos;
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

TEST(Shaders, EveryShaderIsGlsl330Core) {
  const Case c = three_varyings();
  for (const std::string& s : {vertex_shader_source(c), geometry_shader_source(c),
                               fragment_shader_source(c, false), fragment_shader_source(c, true),
                               count_vertex_shader_source({}), count_geometry_shader_source({}),
                               count_fragment_shader_source(), trace_fragment_shader_source()})
    EXPECT_EQ(s.rfind("#version 330 core\n", 0), 0u) << s;
}

TEST(Shaders, VertexShaderPassesClipAndEachVaryingWithItsQualifierSizeAndLocation) {
  const std::string vs = vertex_shader_source(three_varyings());
  EXPECT_TRUE(has(vs, "layout(location = 0) in vec4 a_clip;\n")) << vs;
  EXPECT_TRUE(has(vs, "  gl_Position = a_clip;\n")) << vs;
  EXPECT_TRUE(has(vs, "layout(location = 1) in vec4 a0;\nsmooth out vec4 v0;\n")) << vs;
  EXPECT_TRUE(has(vs, "layout(location = 2) in float a1;\nflat out float v1;\n")) << vs;
  EXPECT_TRUE(has(vs, "layout(location = 3) in vec2 a2;\nnoperspective out vec2 v2;\n")) << vs;
  for (const char* copy : {"  v0 = a0;\n", "  v1 = a1;\n", "  v2 = a2;\n"})
    EXPECT_TRUE(has(vs, copy)) << copy << " in\n" << vs;
  // One qualifier each, and no fourth varying.
  EXPECT_EQ(occurrences(vs, "smooth "), 1u) << vs;
  EXPECT_EQ(occurrences(vs, "flat "), 1u) << vs;
  EXPECT_EQ(occurrences(vs, "noperspective "), 1u) << vs;
  EXPECT_FALSE(has(vs, "location = 4")) << vs;
}

TEST(Shaders, CaseNamesNeverReachTheText) {
  // "flat" and "in" are GLSL keywords: the generated names stand in for every case name.
  const Case c = three_varyings();
  for (const std::string& s :
       {vertex_shader_source(c), geometry_shader_source(c), fragment_shader_source(c, false)}) {
    EXPECT_FALSE(has(s, "color")) << s;
    EXPECT_FALSE(has(s, "vec2 in")) << s;
    EXPECT_FALSE(has(s, "float flat")) << s;
  }
}

TEST(Shaders, FragmentShaderWritesVaryingKToOutputKPaddedAndThePrimitiveIdAfterThem) {
  const std::string fs = fragment_shader_source(three_varyings(), false);
  EXPECT_TRUE(has(fs, "smooth in vec4 v0;\nlayout(location = 0) out vec4 o0;\n")) << fs;
  EXPECT_TRUE(has(fs, "flat in float v1;\nlayout(location = 1) out vec4 o1;\n")) << fs;
  EXPECT_TRUE(has(fs, "noperspective in vec2 v2;\nlayout(location = 2) out vec4 o2;\n")) << fs;
  EXPECT_TRUE(has(fs, "  o0 = vec4(v0);\n")) << fs;
  EXPECT_TRUE(has(fs, "  o1 = vec4(v1, 0.0, 0.0, 0.0);\n")) << fs;
  EXPECT_TRUE(has(fs, "  o2 = vec4(v2, 0.0, 0.0);\n")) << fs;
  EXPECT_TRUE(has(fs, "layout(location = 3) out int o_primitive;\n")) << fs;
  EXPECT_TRUE(has(fs, "  o_primitive = gl_PrimitiveID;\n")) << fs;
  EXPECT_FALSE(has(fs, "g0")) << fs;
}

TEST(Shaders, FragmentShaderAfterAGeometryShaderReadsItsOutputs) {
  const std::string fs = fragment_shader_source(three_varyings(), true);
  EXPECT_TRUE(has(fs, "smooth in vec4 g0;\n")) << fs;
  EXPECT_TRUE(has(fs, "flat in float g1;\n")) << fs;
  EXPECT_TRUE(has(fs, "noperspective in vec2 g2;\n")) << fs;
  EXPECT_TRUE(has(fs, "  o1 = vec4(g1, 0.0, 0.0, 0.0);\n")) << fs;
  EXPECT_TRUE(has(fs, "  o_primitive = gl_PrimitiveID;\n")) << fs;
  EXPECT_FALSE(has(fs, "v0")) << fs;
}

TEST(Shaders, GeometryShaderPassesOneTriangleThroughInOrderWithTheQualifiersAndPrimitiveId) {
  const std::string gs = geometry_shader_source(three_varyings());
  EXPECT_TRUE(has(gs, "layout(triangles) in;\n")) << gs;
  EXPECT_TRUE(has(gs, "layout(triangle_strip, max_vertices = 3) out;\n")) << gs;
  // The qualifier on both sides: interpolation happens after the geometry shader.
  EXPECT_TRUE(has(gs, "smooth in vec4 v0[];\nsmooth out vec4 g0;\n")) << gs;
  EXPECT_TRUE(has(gs, "flat in float v1[];\nflat out float g1;\n")) << gs;
  EXPECT_TRUE(has(gs, "noperspective in vec2 v2[];\nnoperspective out vec2 g2;\n")) << gs;
  EXPECT_TRUE(has(gs, "  for (int i = 0; i < 3; ++i) {\n")) << gs;
  EXPECT_TRUE(has(gs, "    gl_Position = gl_in[i].gl_Position;\n")) << gs;
  EXPECT_TRUE(has(gs, "    gl_PrimitiveID = gl_PrimitiveIDIn;\n")) << gs;
  for (const char* copy : {"    g0 = v0[i];\n", "    g1 = v1[i];\n", "    g2 = v2[i];\n"})
    EXPECT_TRUE(has(gs, copy)) << copy << " in\n" << gs;
  EXPECT_EQ(occurrences(gs, "EmitVertex();"), 1u) << gs;
  EXPECT_EQ(occurrences(gs, "EndPrimitive();"), 1u) << gs;
}

TEST(Shaders, CaseWithoutVaryingsWritesOnlyThePrimitiveIdAtLocationZero) {
  Case c = three_varyings();
  c.varyings.clear();
  const std::string vs = vertex_shader_source(c), fs = fragment_shader_source(c, false);
  EXPECT_EQ(vs,
            "#version 330 core\nlayout(location = 0) in vec4 a_clip;\n"
            "void main() {\n  gl_Position = a_clip;\n}\n");
  EXPECT_TRUE(has(fs, "layout(location = 0) out int o_primitive;\n")) << fs;
  EXPECT_FALSE(has(fs, "vec4")) << fs;
}

TEST(Shaders, CountPassTakesPositionsAndWritesOnePerFragment) {
  const std::string vs = count_vertex_shader_source({}), fs = count_fragment_shader_source();
  EXPECT_TRUE(has(vs, "layout(location = 0) in vec4 a_clip;\n")) << vs;
  EXPECT_TRUE(has(vs, "gl_Position = a_clip;")) << vs;
  EXPECT_TRUE(has(fs, "layout(location = 0) out float o_count;\n")) << fs;
  EXPECT_TRUE(has(fs, "o_count = 1.0;")) << fs;
  // The trace's terms: p + 1, and the hash of p (fragment_hash, in uint arithmetic).
  const std::string trace = trace_fragment_shader_source();
  EXPECT_TRUE(has(trace, "layout(location = 0) out vec2 o_trace;\n")) << trace;
  EXPECT_TRUE(has(trace, "float(gl_PrimitiveID + 1)")) << trace;
  const std::string gs = count_geometry_shader_source({});
  EXPECT_TRUE(has(gs, "gl_PrimitiveID = gl_PrimitiveIDIn;")) << gs;
}

// The distances: inputs after the varyings', the redeclared built-ins, each copied; in the
// case's program, the count pass's and both pass-through geometry shaders; the cull distance
// extension only where the case has cull distances.
TEST(Shaders, DistancesAreWrittenByEveryVertexStage) {
  Case c = three_varyings();
  c.distances = {2, 1, 1u};
  const std::string vs = vertex_shader_source(c), count = count_vertex_shader_source(c.distances);
  for (const std::string& s : {vs, count}) {
    EXPECT_EQ(s.rfind("#version 330 core\n#extension GL_ARB_cull_distance : require\n", 0), 0u)
        << s;
    EXPECT_TRUE(has(s, "layout(location = 8) in float a_distance0;\n")) << s;
    EXPECT_TRUE(has(s, "layout(location = 10) in float a_distance2;\n")) << s;
    EXPECT_TRUE(has(s, "out float gl_ClipDistance[2];\n")) << s;
    EXPECT_TRUE(has(s, "out float gl_CullDistance[1];\n")) << s;
    EXPECT_TRUE(has(s, "  gl_ClipDistance[1] = a_distance1;\n")) << s;
    EXPECT_TRUE(has(s, "  gl_CullDistance[0] = a_distance2;\n")) << s;
  }
  for (const std::string& gs :
       {geometry_shader_source(c), count_geometry_shader_source(c.distances)}) {
    EXPECT_TRUE(has(gs, "gl_ClipDistance[1] = gl_in[i].gl_ClipDistance[1];")) << gs;
    EXPECT_TRUE(has(gs, "gl_CullDistance[0] = gl_in[i].gl_CullDistance[0];")) << gs;
  }
  EXPECT_NE(program_key(c), program_key(three_varyings()));
  c.distances.cull = 0;
  EXPECT_EQ(vertex_shader_source(c).find("#extension"), std::string::npos);
}

TEST(Shaders, GlslTypesAndQualifiers) {
  EXPECT_STREQ(glsl_type(1), "float");
  EXPECT_STREQ(glsl_type(2), "vec2");
  EXPECT_STREQ(glsl_type(3), "vec3");
  EXPECT_STREQ(glsl_type(4), "vec4");
  EXPECT_STREQ(glsl_qualifier(Interpolation::smooth), "smooth");
  EXPECT_STREQ(glsl_qualifier(Interpolation::flat), "flat");
  EXPECT_STREQ(glsl_qualifier(Interpolation::noperspective), "noperspective");
}

TEST(Shaders, SizeOutsideOneToFourIsRefusedNotReadPastTheTable) {
  EXPECT_THROW(glsl_type(0), std::invalid_argument);
  EXPECT_THROW(glsl_type(5), std::invalid_argument);
  Case c = three_varyings();
  c.varyings[1].size = 5;
  EXPECT_THROW(vertex_shader_source(c), std::invalid_argument);
  EXPECT_THROW(geometry_shader_source(c), std::invalid_argument);
  EXPECT_THROW(fragment_shader_source(c, false), std::invalid_argument);
}

TEST(ProgramKey, NamesEverySizeAndQualifierInOrder) {
  EXPECT_EQ(program_key(three_varyings()), "4smooth,1flat,2noperspective,");
  Case none = three_varyings();
  none.varyings.clear();
  EXPECT_EQ(program_key(none), "");
}

TEST(ProgramKey, CasesThatDifferOnlyInValuesShareAProgram) {
  const Case a = three_varyings();
  Case b = a;
  b.name = "other";
  b.varyings[0].name = "colour";
  for (auto& v : b.vertices) {
    v.clip[0] *= 0.5f;
    for (float& x : v.values)
      x = -2 * x + 3;
  }
  b.vertices.push_back(b.vertices[0]);
  b.triangles.push_back({1, 2, 3});
  b.fb_width = b.fb_height = 7;
  b.provoking = ProvokingVertex::first;
  b.cull = CullFace::back;
  EXPECT_EQ(program_key(a), program_key(b));
  // The same program text, too: the cache hands b the program compiled for a.
  EXPECT_EQ(vertex_shader_source(a), vertex_shader_source(b));
  EXPECT_EQ(fragment_shader_source(a, false), fragment_shader_source(b, false));
  EXPECT_EQ(geometry_shader_source(a), geometry_shader_source(b));
}

TEST(ProgramKey, SizeOrQualifierOrOrderMakesAnotherProgram) {
  const Case a = three_varyings();
  Case size = a, qualifier = a, order = a;
  size.varyings[2].size = 3;
  qualifier.varyings[0].interpolation = Interpolation::noperspective;
  std::swap(order.varyings[0], order.varyings[1]);
  for (const Case* other : {&size, &qualifier, &order}) {
    EXPECT_NE(program_key(a), program_key(*other));
    EXPECT_NE(vertex_shader_source(a), vertex_shader_source(*other));
  }
}

// Fragment output k must land in colour attachment k of case_colour_formats: RGBA32F for each
// varying (any size, padded to vec4), R32I for gl_PrimitiveID after them, up to the most
// varyings the harness takes.
TEST(ShadersAndFramebuffer, OutputLocationsMatchTheAttachmentFormats) {
  for (int n = 0; n <= kMaxVaryings; ++n) {
    Case c;
    for (int k = 0; k < n; ++k)
      c.varyings.push_back({"v", 1 + k % 4, Interpolation::smooth});
    const std::vector<GLenum> formats = case_colour_formats(n);
    ASSERT_EQ(formats.size(), size_t(n) + 1);
    const std::string fs = fragment_shader_source(c, false);
    for (int k = 0; k < n; ++k) {
      EXPECT_EQ(formats[size_t(k)], GLenum(GL_RGBA32F));
      EXPECT_TRUE(has(fs, "layout(location = " + std::to_string(k) + ") out vec4 o" +
                              std::to_string(k) + ";\n"))
          << fs;
    }
    EXPECT_EQ(formats.back(), GLenum(GL_R32I));
    EXPECT_TRUE(has(fs, "layout(location = " + std::to_string(n) + ") out int o_primitive;\n"))
        << fs;
  }
  // Every attachment within GL 3.3's guaranteed 8 draw buffers.
  EXPECT_LE(case_colour_formats(kMaxVaryings).size(), 8u);
}

TEST(FramebufferStatus, NamesAreTheSpecsEnumNames) {
  EXPECT_STREQ(framebuffer_status_name(GL_FRAMEBUFFER_COMPLETE), "GL_FRAMEBUFFER_COMPLETE");
  EXPECT_STREQ(framebuffer_status_name(GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT),
               "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT");
  EXPECT_STREQ(framebuffer_status_name(GL_FRAMEBUFFER_UNSUPPORTED), "GL_FRAMEBUFFER_UNSUPPORTED");
  EXPECT_STREQ(framebuffer_status_name(0), "unknown framebuffer status");
}

// A built-in in place of a varying: the fragment shader writes gl_FragCoord (redeclared with its
// layout qualifiers where it has any) or gl_FrontFacing to the varying's output; the vertex and
// geometry shaders pass nothing for it. Cases that differ only in which built-in, or in its
// layout, must not share a program (two front-facing cases once drew with gl_FragCoord's).
TEST(Shaders, BuiltinsAreWrittenByTheFragmentShaderAndKeyTheirProgram) {
  Case c = three_varyings();
  c.varyings[2] = builtin_varying(Builtin::frag_coord, {true, false});
  const std::string fs = fragment_shader_source(c, false);
  EXPECT_NE(fs.find("layout(origin_upper_left) in vec4 gl_FragCoord;"), std::string::npos) << fs;
  EXPECT_NE(fs.find("o2 = gl_FragCoord;"), std::string::npos) << fs;
  EXPECT_EQ(vertex_shader_source(c).find("v2"), std::string::npos);
  EXPECT_EQ(geometry_shader_source(c).find("g2"), std::string::npos);
  Case facing = c;
  facing.varyings[2] = builtin_varying(Builtin::front_facing);
  EXPECT_NE(fragment_shader_source(facing, false).find("o2 = vec4(gl_FrontFacing ? 1.0 : 0.0"),
            std::string::npos);
  Case plain = c;
  plain.varyings[2] = builtin_varying(Builtin::frag_coord);
  EXPECT_EQ(fragment_shader_source(plain, false).find("layout(origin"), std::string::npos);
  EXPECT_NE(program_key(c), program_key(facing));
  EXPECT_NE(program_key(c), program_key(plain));
  EXPECT_NE(program_key(plain), program_key(facing));
}

}  // namespace
}  // namespace glrc::gl
