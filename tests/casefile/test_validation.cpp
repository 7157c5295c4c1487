// Every validation rule: the error is one line naming the file, the field path and what was
// expected, and what was found.
#include "tests/casefile/test_helpers.hpp"

namespace glrc::casefile::test {
namespace {

// A valid case with `fields` added at the top level.
std::string with(const std::string& fields) {
  return R"({"description": "d", )" + fields + "}";
}
// Three plain vertices, for cases whose error is elsewhere.
const std::string kTri =
    R"("vertices": [{"clip": [-1, -1, 0, 1]}, {"clip": [1, -1, 0, 1]}, {"clip": [0, 1, 0, 1]}])";
// Three vertices with one vec4 varying "color" of the given interpolation.
std::string color_case(const std::string& interpolation, const std::string& v1_clip,
                       const std::string& extra = "") {
  return with(R"("varyings": [{"name": "color", "size": 4, "interpolation": ")" + interpolation +
              R"("}],
    "vertices": [{"clip": [-1, -1, 0, 1], "color": [1, 2, 3, 4]},
                 {"clip": )" +
              v1_clip + R"(, "color": [5, 6, 7, 8]},
                 {"clip": [0, 1, 0, 1], "color": [9, 10, 11, 12]}])" +
              extra);
}

TEST_F(CaseFileTest, ExactMessagesForTheDocumentedExamples) {
  const std::string file = (dir_ / "case.json").string();
  EXPECT_EQ(
      error_of(with(R"("state": {"cull": "frnt"}, )" + kTri)),
      file + R"(: state.cull: expected one of none, front, back, front_and_back, got "frnt")");
  EXPECT_EQ(error_of(color_case("smooth", "[1, -1, 0]")),
            file + ": vertices[1].clip: expected 4 numbers, got 3");
}

TEST_F(CaseFileTest, InvalidJsonNamesLineAndColumn) {
  const std::string msg = error_of("{\"description\": \"d\",\n  \"vertices\": [\n}\n");
  const std::string file = (dir_ / "case.json").string();
  EXPECT_EQ(msg.rfind(file + ": line 3, column 1: expected valid JSON, got ", 0), 0u) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_NE(error_of("").find("expected valid JSON"), std::string::npos);
  // Comments are not JSON.
  EXPECT_NE(error_of(with("// c\n" + kTri)).find("expected valid JSON"), std::string::npos);
}

TEST_F(CaseFileTest, TopLevelShapeAndRequiredFields) {
  EXPECT_CASE_ERROR(R"({"vertices": []})", "description");
  EXPECT_CASE_ERROR(R"({"description": "d"})", "vertices");
  EXPECT_CASE_ERROR(R"({"description": "two\nlines", )" + kTri + "}", "description");
  EXPECT_CASE_ERROR(R"({"description": 5, )" + kTri + "}", "description");
  EXPECT_CASE_ERROR(with(R"("vertices": [])"), "vertices");
}

// With no field to name, the message is "<file>: expected ..., got ...".
TEST_F(CaseFileTest, NonObjectTopLevel) {
  const std::string msg = error_of("[1, 2]");
  EXPECT_EQ(msg, (dir_ / "case.json").string() +
                     ": expected a JSON object at the top level, got an array of 2");
}

TEST_F(CaseFileTest, UnknownKeysAnywhereAreErrors) {
  EXPECT_CASE_ERROR(with(R"("descripton": "x", )" + kTri), "descripton");
  EXPECT_CASE_ERROR(with(R"("state": {"culll": "none"}, )" + kTri), "state.culll");
  EXPECT_CASE_ERROR(with(R"("framebuffer": {"width": 8, "height": 8, "depth": 1}, )" + kTri),
                    "framebuffer.depth");
  EXPECT_CASE_ERROR(with(R"("tolerance": {"varying_ulp": 1}, )" + kTri), "tolerance.varying_ulp");
  EXPECT_CASE_ERROR(with(R"("varyings": [{"name": "a", "sise": 2}], )" + kTri), "varyings[0].sise");
  EXPECT_CASE_ERROR(with(R"("transform": {"modle": []}, )" + kTri), "transform.modle");
  EXPECT_CASE_ERROR(
      with(R"("transform": {"model": [{"rotate": {"degrees": 5, "axis": [0,0,1], "x": 1}}]}, )" +
           kTri),
      "transform.model[0].rotate.x");
  // A vertex key that is no declared varying.
  EXPECT_CASE_ERROR(with(R"("varyings": [{"name": "color", "size": 1}],
    "vertices": [{"clip": [-1, -1, 0, 1], "color": 1}, {"clip": [1, -1, 0, 1], "color": 2},
                 {"clip": [0, 1, 0, 1], "color": 3, "colr": 3}])"),
                    "vertices[2].colr");
  // The same key twice in one object.
  EXPECT_CASE_ERROR(with(R"("state": {"cull": "back", "cull": "none"}, )" + kTri), "state.cull");
  EXPECT_CASE_ERROR(
      with(R"("vertices": [{"clip": [-1, -1, 0, 1]}, {"clip": [1, -1, 0, 1], "clip": [1, -1, 0, 1]},
                          {"clip": [0, 1, 0, 1]}])"),
      "vertices[1].clip");
}

TEST_F(CaseFileTest, FramebufferAndViewport) {
  EXPECT_CASE_ERROR(with(R"("framebuffer": {"width": 0, "height": 8}, )" + kTri),
                    "framebuffer.width");
  EXPECT_CASE_ERROR(with(R"("framebuffer": {"width": 8, "height": 4097}, )" + kTri),
                    "framebuffer.height");
  EXPECT_CASE_ERROR(with(R"("framebuffer": {"width": "64", "height": 8}, )" + kTri),
                    "framebuffer.width");
  EXPECT_CASE_ERROR(with(R"("framebuffer": {"width": 64.5, "height": 8}, )" + kTri),
                    "framebuffer.width");
  EXPECT_CASE_ERROR(with(R"("framebuffer": {"width": 64}, )" + kTri), "framebuffer.height");
  EXPECT_CASE_ERROR(with(R"("viewport": {"x": 0, "y": 0, "width": 0, "height": 8}, )" + kTri),
                    "viewport.width");
  EXPECT_CASE_ERROR(with(R"("viewport": {"x": -16385, "y": 0, "width": 8, "height": 8}, )" + kTri),
                    "viewport.x");
  EXPECT_CASE_ERROR(with(R"("viewport": {"x": 0, "y": 0, "width": 16385, "height": 8}, )" + kTri),
                    "viewport.width");
  // Without a framebuffer, the viewport's extent is the framebuffer and must be a legal size.
  EXPECT_CASE_ERROR(with(R"("viewport": {"x": 100, "y": 0, "width": 4000, "height": 8}, )" + kTri),
                    "framebuffer");
  EXPECT_CASE_ERROR(with(R"("viewport": {"x": -1, "y": 0, "width": 8, "height": 8}, )" + kTri),
                    "framebuffer");
  // With one, the viewport may lie partly or wholly beyond it.
  const Case beyond = load_text(with(R"("framebuffer": {"width": 96, "height": 64},
                            "viewport": {"x": -50, "y": 30, "width": 480, "height": 40}, )" +
                                     kTri));
  EXPECT_EQ(beyond.viewport.x, -50);
  EXPECT_EQ(beyond.viewport.width, 480);
  EXPECT_TRUE(beyond.viewport.integral());
  // Fractional bounds (glViewportIndexedf), numbers or decimal strings, each a float32.
  const Case fractional = load_text(with(R"("framebuffer": {"width": 64, "height": 64},
                            "viewport": {"x": -2.25, "y": "0.1", "width": 40.5, "height": 3}, )" +
                                         kTri));
  EXPECT_EQ(fractional.viewport.x, -2.25f);
  EXPECT_EQ(fractional.viewport.y, 0.1f);
  EXPECT_EQ(fractional.viewport.width, 40.5f);
  EXPECT_FALSE(fractional.viewport.integral());
  // Without a framebuffer, a fractional extent rounds up to whole pixels.
  const Case sized =
      load_text(with(R"("viewport": {"x": 1.5, "y": 0, "width": 8.25, "height": 8}, )" + kTri));
  EXPECT_EQ(sized.fb_width, 10);
  EXPECT_CASE_ERROR(with(R"("viewport": {"x": 0, "y": 0, "width": 0.5, "height": 8}, )" + kTri),
                    "viewport.width");
  EXPECT_CASE_ERROR(with(R"("viewport": {"x": "nan", "y": 0, "width": 8, "height": 8}, )" + kTri),
                    "viewport.x");
  EXPECT_CASE_ERROR(with(R"("viewport": {"x": 0, "y": 0, "width": 8, "height": 8},
                            "scissor": {"x": 0.5, "y": 0, "width": 8, "height": 8}, )" +
                         kTri),
                    "scissor.x");
  // The scissor box: origins as the viewport's, sizes from 0.
  EXPECT_CASE_ERROR(with(R"("scissor": {"x": 0, "y": 0, "width": -1, "height": 8}, )" + kTri),
                    "scissor.width");
  EXPECT_CASE_ERROR(with(R"("scissor": {"x": 0, "y": 0, "width": 8}, )" + kTri), "scissor.height");
  EXPECT_CASE_ERROR(with(R"("scissor": {"x": 0, "y": -16385, "width": 8, "height": 8}, )" + kTri),
                    "scissor.y");
  EXPECT_CASE_ERROR(with(R"("scissor": [0, 0, 8, 8], )" + kTri), "scissor");
  const Case boxed =
      load_text(with(R"("scissor": {"x": -3, "y": 5, "width": 0, "height": 8}, )" + kTri));
  ASSERT_TRUE(boxed.scissor.has_value());
  EXPECT_EQ(boxed.scissor->x, -3);
  EXPECT_EQ(boxed.scissor->width, 0);
  EXPECT_TRUE(scissor_region(boxed).empty());
}

TEST_F(CaseFileTest, DepthRangeAndState) {
  EXPECT_CASE_ERROR(with(R"("depth_range": {"near": 1.5}, )" + kTri), "depth_range.near");
  EXPECT_CASE_ERROR(with(R"("depth_range": {"far": -0.25}, )" + kTri), "depth_range.far");
  EXPECT_CASE_ERROR(with(R"("state": {"front_face": "CCW"}, )" + kTri), "state.front_face");
  EXPECT_CASE_ERROR(with(R"("state": {"provoking_vertex": 1}, )" + kTri), "state.provoking_vertex");
  EXPECT_CASE_ERROR(with(R"("state": {"depth_func": "LEQUAL"}, )" + kTri), "state.depth_func");
  EXPECT_CASE_ERROR(with(R"("state": {"depth_func": "le"}, )" + kTri), "state.depth_func");
  EXPECT_CASE_ERROR(with(R"("state": {"depth_clear": 1.5}, )" + kTri), "state.depth_clear");
  EXPECT_CASE_ERROR(with(R"("state": {"clip_origin": "GL_UPPER_LEFT"}, )" + kTri),
                    "state.clip_origin");
  EXPECT_CASE_ERROR(with(R"("state": {"clip_depth": "zero_to_1"}, )" + kTri), "state.clip_depth");
  EXPECT_CASE_ERROR(with(R"("state": {"clip_depth": 0}, )" + kTri), "state.clip_depth");
  const Case controlled = load_text(
      with(R"("state": {"clip_origin": "upper_left", "clip_depth": "zero_to_one"}, )" + kTri));
  EXPECT_EQ(controlled.clip_origin, ClipOrigin::upper_left);
  EXPECT_EQ(controlled.clip_depth, ClipDepth::zero_to_one);
  EXPECT_EQ(load_text(with(kTri)).clip_origin, ClipOrigin::lower_left);
  EXPECT_CASE_ERROR(with(R"("state": {"depth_clear": -0.25}, )" + kTri), "state.depth_clear");
  EXPECT_CASE_ERROR(with(R"("state": {"depth_clear": "nan"}, )" + kTri), "state.depth_clear");
  EXPECT_CASE_ERROR(with(R"("work_arounds": 0, )" + kTri), "work_arounds");
  EXPECT_CASE_ERROR(with(R"("work_arounds": "no", )" + kTri), "work_arounds");
  EXPECT_CASE_ERROR(with(R"("state": [], )" + kTri), "state");
}

TEST_F(CaseFileTest, DepthClampAndPolygonOffset) {
  EXPECT_CASE_ERROR(with(R"("state": {"depth_clamp": 1}, )" + kTri), "state.depth_clamp");
  EXPECT_CASE_ERROR(with(R"("state": {"depth_clamp": "on"}, )" + kTri), "state.depth_clamp");
  EXPECT_TRUE(load_text(with(R"("state": {"depth_clamp": true}, )" + kTri)).depth_clamp);
  EXPECT_FALSE(load_text(with(kTri)).depth_clamp);
  EXPECT_CASE_ERROR(with(R"("polygon_offset": [1, 2], )" + kTri), "polygon_offset");
  EXPECT_CASE_ERROR(with(R"("polygon_offset": {"slope": 1}, )" + kTri), "polygon_offset.slope");
  EXPECT_CASE_ERROR(with(R"("polygon_offset": {"factor": "x"}, )" + kTri), "polygon_offset.factor");
  EXPECT_CASE_ERROR(with(R"("polygon_offset": {"units": 1e39}, )" + kTri), "polygon_offset.units");
  EXPECT_CASE_ERROR(with(R"("polygon_offset": {"clamp": "inf"}, )" + kTri), "polygon_offset.clamp");
  const Case offset =
      load_text(with(R"("polygon_offset": {"factor": -1.5, "units": "0.1"}, )" + kTri));
  ASSERT_TRUE(offset.polygon_offset.has_value());
  EXPECT_EQ(offset.polygon_offset->factor, -1.5f);
  EXPECT_EQ(offset.polygon_offset->units, 0.1f);  // rounded to float32 once
  EXPECT_FALSE(offset.polygon_offset->clamp.has_value());
  const Case clamped = load_text(with(R"("polygon_offset": {"clamp": 0.25}, )" + kTri));
  EXPECT_EQ(clamped.polygon_offset->factor, 0.0f);
  EXPECT_EQ(clamped.polygon_offset->clamp, 0.25f);
  EXPECT_FALSE(load_text(with(kTri)).polygon_offset.has_value());
}

TEST_F(CaseFileTest, Varyings) {
  auto one = [](const std::string& varying) {
    return with(R"("varyings": [)" + varying + "], " + kTri);
  };
  EXPECT_CASE_ERROR(one(R"({"name": "gl_Color"})"), "varyings[0].name");
  EXPECT_CASE_ERROR(one(R"({"name": "2uv"})"), "varyings[0].name");
  EXPECT_CASE_ERROR(one(R"({"name": "u-v"})"), "varyings[0].name");
  EXPECT_CASE_ERROR(one(R"({"name": ""})"), "varyings[0].name");
  EXPECT_CASE_ERROR(one(R"({"name": "a__b"})"), "varyings[0].name");
  EXPECT_CASE_ERROR(one(R"({"name": "flat"})"), "varyings[0].name");
  EXPECT_CASE_ERROR(one(R"({"name": "clip"})"), "varyings[0].name");
  EXPECT_CASE_ERROR(one(R"({"size": 2})"), "varyings[0].name");
  EXPECT_CASE_ERROR(one(R"({"name": "a", "size": 5})"), "varyings[0].size");
  EXPECT_CASE_ERROR(one(R"({"name": "a", "size": 0})"), "varyings[0].size");
  EXPECT_CASE_ERROR(one(R"({"name": "a", "interpolation": "linear"})"),
                    "varyings[0].interpolation");
  EXPECT_CASE_ERROR(with(R"("varyings": [{"name": "a"}, {"name": "a"}], )" + kTri),
                    "varyings[1].name");
  EXPECT_CASE_ERROR(with(R"("varyings": [{"name": "a"}, {"name": "b"}, {"name": "c"},
    {"name": "d"}, {"name": "e"}, {"name": "f"}, {"name": "g"}, {"name": "h"}], )" +
                         kTri),
                    "varyings");
  EXPECT_CASE_ERROR(with(R"("varyings": {"name": "a"}, )" + kTri), "varyings");
  // Built-ins: known names, once each, their own keys only; no "gl_" varying in their place.
  EXPECT_CASE_ERROR(one(R"({"builtin": "gl_PointCoord"})"), "varyings[0].builtin");
  EXPECT_CASE_ERROR(one(R"({"builtin": "gl_FragCoord", "size": 4})"), "varyings[0].size");
  EXPECT_CASE_ERROR(one(R"({"builtin": "gl_FrontFacing", "origin_upper_left": true})"),
                    "varyings[0].origin_upper_left");
  EXPECT_CASE_ERROR(one(R"({"builtin": "gl_FragCoord", "origin_upper_left": "yes"})"),
                    "varyings[0].origin_upper_left");
  EXPECT_CASE_ERROR(one(R"({"name": "gl_FragCoord", "size": 4})"), "varyings[0].name");
  EXPECT_NE(error_of(one(R"({"origin_upper_left": true})"))
                .find("varyings[0].origin_upper_left: expected a \"builtin\" beside it"),
            std::string::npos);
  EXPECT_CASE_ERROR(with(R"("varyings": [{"builtin": "gl_FrontFacing"},
    {"builtin": "gl_FrontFacing"}], )" +
                         kTri),
                    "varyings[1].builtin");
  const Case c = load_text(one(R"({"builtin": "gl_FragCoord", "pixel_center_integer": true})"));
  ASSERT_EQ(c.varyings.size(), 1u);
  EXPECT_EQ(c.varyings[0].name, "gl_FragCoord");
  EXPECT_EQ(c.varyings[0].size, 4);
  EXPECT_TRUE(c.varyings[0].layout.pixel_center_integer);
  EXPECT_FALSE(c.varyings[0].layout.origin_upper_left);
  EXPECT_EQ(c.vertices[0].values, std::vector<float>(4, 0.0f));
}

TEST_F(CaseFileTest, VertexValues) {
  // Every vertex has every varying, with the right count.
  EXPECT_CASE_ERROR(with(R"("varyings": [{"name": "c", "size": 2}],
    "vertices": [{"clip": [-1, -1, 0, 1], "c": [1, 2]}, {"clip": [1, -1, 0, 1]},
                 {"clip": [0, 1, 0, 1], "c": [1, 2]}])"),
                    "vertices[1].c");
  EXPECT_CASE_ERROR(with(R"("varyings": [{"name": "c", "size": 2}],
    "vertices": [{"clip": [-1, -1, 0, 1], "c": [1, 2]}, {"clip": [1, -1, 0, 1], "c": [1, 2, 3]},
                 {"clip": [0, 1, 0, 1], "c": [1, 2]}])"),
                    "vertices[1].c");
  EXPECT_CASE_ERROR(with(R"("varyings": [{"name": "c", "size": 2}],
    "vertices": [{"clip": [-1, -1, 0, 1], "c": [1, 2]}, {"clip": [1, -1, 0, 1], "c": 1},
                 {"clip": [0, 1, 0, 1], "c": [1, 2]}])"),
                    "vertices[1].c");
  EXPECT_CASE_ERROR(color_case("smooth", R"([1, -1, 0, true])"), "vertices[1].clip[3]");
  EXPECT_CASE_ERROR(color_case("smooth", R"([1, -1, 0, "1.5x"])"), "vertices[1].clip[3]");
  EXPECT_CASE_ERROR(color_case("smooth", R"([1, -1, 0, " 1"])"), "vertices[1].clip[3]");
  EXPECT_CASE_ERROR(color_case("smooth", R"({"x": 1})"), "vertices[1].clip");
  EXPECT_CASE_ERROR(with(R"("vertices": [1, 2, 3])"), "vertices[0]");
}

TEST_F(CaseFileTest, NonFiniteValues) {
  // A value that overflows float32 is an error, whether JSON number or string.
  EXPECT_CASE_ERROR(color_case("smooth", "[1e39, -1, 0, 1]"), "vertices[1].clip[0]");
  EXPECT_CASE_ERROR(color_case("smooth", "[-3.4028235677973366e38, -1, 0, 1]"),
                    "vertices[1].clip[0]");  // exactly half-way to 2^128: rounds to infinity
  EXPECT_CASE_ERROR(color_case("smooth", R"(["0x1p128", -1, 0, 1])"), "vertices[1].clip[0]");
  EXPECT_CASE_ERROR(color_case("smooth", R"(["inf", -1, 0, 1])"), "vertices[1].clip[0]");
  EXPECT_CASE_ERROR(color_case("smooth", R"(["nan", -1, 0, 1])"), "vertices[1].clip[0]");
  EXPECT_CASE_ERROR(color_case("smooth", "[1e400, -1, 0, 1]"), "vertices[1].clip[0]");
  EXPECT_CASE_ERROR(with(R"("varyings": [{"name": "s", "size": 1}],
    "vertices": [{"clip": [-1, -1, 0, 1], "s": 1}, {"clip": [1, -1, 0, 1], "s": "-1e39"},
                 {"clip": [0, 1, 0, 1], "s": 1}])"),
                    "vertices[1].s");
}

TEST_F(CaseFileTest, ClipOrPosition) {
  EXPECT_CASE_ERROR(with(R"("vertices": [{"clip": [-1, -1, 0, 1], "position": [0, 0, 0]},
                          {"clip": [1, -1, 0, 1]}, {"clip": [0, 1, 0, 1]}])"),
                    "vertices[0]");
  EXPECT_CASE_ERROR(with(R"("vertices": [{"clip": [-1, -1, 0, 1]}, {},
                          {"clip": [0, 1, 0, 1]}])"),
                    "vertices[1]");
  // position only with a transform.
  EXPECT_CASE_ERROR(with(R"("vertices": [{"clip": [-1, -1, 0, 1]}, {"position": [1, -1, 0]},
                          {"clip": [0, 1, 0, 1]}])"),
                    "vertices[1].position");
  EXPECT_CASE_ERROR(with(R"("transform": {}, "vertices": [{"position": [-1, -1]},
                          {"position": [1, -1, 0]}, {"position": [0, 1, 0]}])"),
                    "vertices[0].position");
  // The transform's result must fit float32 too.
  EXPECT_CASE_ERROR(with(R"("transform": {"model": [{"scale": [1e30, 1e30, 1e30]}]},
               "vertices": [{"position": [-1, -1, 0]}, {"position": [1e30, -1, 0]},
                            {"position": [0, 1, 0]}])"),
                    "vertices[1].position");
}

TEST_F(CaseFileTest, Triangles) {
  EXPECT_CASE_ERROR(with(kTri + R"(, "triangles": [[0, 1, 3]])"), "triangles[0][2]");
  EXPECT_CASE_ERROR(with(kTri + R"(, "triangles": [[0, 1, 2], [0, -1, 2]])"), "triangles[1][1]");
  EXPECT_CASE_ERROR(with(kTri + R"(, "triangles": [[0, 1, 2], [0, 1]])"), "triangles[1]");
  EXPECT_CASE_ERROR(with(kTri + R"(, "triangles": [[0, 1, 1.5]])"), "triangles[0][2]");
  EXPECT_CASE_ERROR(with(kTri + R"(, "triangles": [])"), "triangles");  // at least one
  EXPECT_CASE_ERROR(
      with(
          R"("vertices": [{"clip": [-1, -1, 0, 1]}, {"clip": [1, -1, 0, 1]}, {"clip": [0, 1, 0, 1]},
                          {"clip": [0, 0, 0, 1]}])"),
      "vertices");  // no "triangles": the count must be a multiple of 3
}

TEST_F(CaseFileTest, NoperspectiveBehindTheEyeIsRejected) {
  for (const char* w : {"-0.5", "0", "-0.0"}) {
    const std::string text = color_case("noperspective", std::string("[1, -1, 0, ") + w + "]");
    EXPECT_CASE_ERROR(text, "triangles[0]");
    const std::string msg = error_of(text);
    EXPECT_NE(msg.find("noperspective"), std::string::npos) << msg;
    EXPECT_NE(msg.find("behind the eye"), std::string::npos) << msg;
    EXPECT_NE(msg.find("undefined"), std::string::npos) << msg;
    EXPECT_NE(msg.find("vertex 1"), std::string::npos) << msg;
  }
  // The same triangle with smooth or flat varyings is fine.
  EXPECT_EQ(error_of(color_case("smooth", "[1, -1, 0, -0.5]")), "");
  EXPECT_EQ(error_of(color_case("flat", "[1, -1, 0, -0.5]")), "");
  // The triangle is named by its index in "triangles".
  EXPECT_CASE_ERROR(
      color_case("noperspective", "[1, -1, 0, -2]", R"(, "triangles": [[0, 2, 0], [2, 0, 1]])"),
      "triangles[1]");
}

TEST_F(CaseFileTest, TransformOperations) {
  auto tf = [](const std::string& transform) {
    return with(R"("transform": )" + transform +
                R"(, "vertices": [{"position": [-1, -1, -2]}, {"position": [1, -1, -2]},
                                  {"position": [0, 1, -2]}])");
  };
  EXPECT_CASE_ERROR(tf(R"({"model": [{"rotat": {"degrees": 5, "axis": [0, 0, 1]}}]})"),
                    "transform.model[0].rotat");
  EXPECT_CASE_ERROR(tf(R"({"model": [{"translate": [1, 2, 3], "scale": [1, 1, 1]}]})"),
                    "transform.model[0]");
  EXPECT_CASE_ERROR(tf(R"({"model": [{"translate": [1, 2]}]})"), "transform.model[0].translate");
  EXPECT_CASE_ERROR(tf(R"({"model": {"translate": [1, 2, 3]}})"), "transform.model");
  EXPECT_CASE_ERROR(tf(R"({"view": [{"rotate": {"degrees": 5, "axis": [0, 0, 0]}}]})"),
                    "transform.view[0].rotate.axis");
  EXPECT_CASE_ERROR(tf(R"({"view": [{"rotate": {"axis": [0, 0, 1]}}]})"),
                    "transform.view[0].rotate.degrees");
  EXPECT_CASE_ERROR(
      tf(R"({"view": [{"look_at": {"eye": [0, 0, 1], "center": [0, 0, 1], "up": [0, 1, 0]}}]})"),
      "transform.view[0].look_at.center");
  EXPECT_CASE_ERROR(
      tf(R"({"view": [{"look_at": {"eye": [0, 0, 1], "center": [0, 0, 0], "up": [0, 0, 2]}}]})"),
      "transform.view[0].look_at.up");
  EXPECT_CASE_ERROR(
      tf(R"({"projection": {"perspective": {"fovy_degrees": 60, "aspect": 1, "near": 0, "far": 10}}})"),
      "transform.projection.perspective.near");
  EXPECT_CASE_ERROR(
      tf(R"({"projection": {"perspective": {"fovy_degrees": 180, "aspect": 1, "near": 1, "far": 10}}})"),
      "transform.projection.perspective.fovy_degrees");
  EXPECT_CASE_ERROR(
      tf(R"({"projection": {"perspective": {"fovy_degrees": 60, "aspect": 1, "near": 1}}})"),
      "transform.projection.perspective.far");
  EXPECT_CASE_ERROR(
      tf(R"({"projection": {"frustum": {"left": 1, "right": 1, "bottom": -1, "top": 1, "near": 1, "far": 2}}})"),
      "transform.projection.frustum.right");
  EXPECT_CASE_ERROR(
      tf(R"({"projection": {"ortho": {"left": -1, "right": 1, "bottom": -1, "top": 1, "near": 2, "far": 2}}})"),
      "transform.projection.ortho.far");
  EXPECT_CASE_ERROR(tf(R"({"projection": {"orthographic": {}}})"),
                    "transform.projection.orthographic");
  EXPECT_CASE_ERROR(tf(R"({"projection": []})"), "transform.projection");
}

TEST_F(CaseFileTest, Tolerance) {
  EXPECT_CASE_ERROR(with(R"("tolerance": {"varying_ulps": -1}, )" + kTri),
                    "tolerance.varying_ulps");
  EXPECT_CASE_ERROR(with(R"("tolerance": {"depth_ulps": "16"}, )" + kTri), "tolerance.depth_ulps");
  EXPECT_CASE_ERROR(with(R"("tolerance": {"allow_boundary": 1}, )" + kTri),
                    "tolerance.allow_boundary");
}

TEST_F(CaseFileTest, MissingFile) {
  const auto path = dir_ / "nope.json";
  try {
    load(path);
    FAIL() << "loaded a missing file";
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": expected ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace glrc::casefile::test
