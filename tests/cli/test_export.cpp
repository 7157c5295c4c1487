// glrefcheck export --format c as a user runs it: the C reproducer is built with the system's
// C compiler alone and run on the system's Mesa through EGL and OSMesa. It finds Mesa 22.3.6's
// clipper NaN (cases/known-failures.txt) on llvmpipe, passes the cases llvmpipe passes, and finds
// softpipe's gap and double hit on a shared edge (tests/cli/data/, minimal cases from
// `glrefcheck fuzz --generator mesh --driver softpipe --seed 22`) on softpipe only. Bad input is
// one line and exit 2. The library's text (export/reproducer.hpp) is checked without GL too.
// --format shader_test's name and refusals are checked here; its text in
// tests/export/test_shader_test.cpp, its runs on shader_runner in export_shader_test.sh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "casefile/casefile.hpp"
#include "check/check.hpp"
#include "export/reproducer.hpp"
#include "export/shader_test.hpp"
#include "gl_harness/first_draw.hpp"
#include "gl_harness/shaders.hpp"
#include "tests/support/glrefcheck_process.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

using glrc::test::glrefcheck;
using glrc::test::Outcome;

// A shell command's exit status and its stdout and stderr together.
Outcome shell(const std::string& command) {
  Outcome o;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0)
    o.out.append(buf, n);
  const int status = pclose(p);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::string source(const std::string& relative) {
  return std::string(GLRC_SOURCE_DIR) + "/" + relative;
}

class Export : public glrc::test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    has_cc_ = shell("command -v cc").exit_code == 0;
  }

  // Exports `case_file` with `options` into the temporary folder as <name>.c and builds it;
  // the program's path, or "" after a failed expectation.
  std::string build(const std::string& case_file, const std::string& name,
                    const std::string& options = "") {
    const std::string c_file = (dir_ / (name + ".c")).string();
    const auto r =
        glrefcheck("export '" + case_file + "' --format c --out '" + c_file + "' " + options);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("wrote " + c_file + ": compile with cc -std=c99 -O2 -o"),
              std::string::npos)
        << r.out;
    const std::string program = (dir_ / name).string();
    const auto cc = shell("cc -std=c99 -O2 -Wall -Wextra -pedantic -Werror -o '" + program + "' '" +
                          c_file + "' -ldl -lm");
    EXPECT_EQ(cc.exit_code, 0) << cc.out;
    return cc.exit_code == 0 ? program : "";
  }

  // Runs a built reproducer under GALLIUM_DRIVER=driver on `backend`.
  static Outcome run(const std::string& program, const std::string& driver,
                     const std::string& backend) {
    return shell("GALLIUM_DRIVER=" + driver + " '" + program + "' " + backend);
  }

  bool has_cc_ = false;
};

TEST_F(Export, ClipperNaNFailsOnLlvmpipe) {
  if (!has_cc_) GTEST_SKIP() << "no C compiler (cc)";
  const std::string program = build(source("cases/clip_noperspective_x_plane.json"), "clipper");
  ASSERT_FALSE(program.empty());
  for (const char* backend : {"egl", "osmesa"}) {
    const auto r = run(program, "llvmpipe", backend);
    EXPECT_EQ(r.exit_code, 1) << backend << "\n" << r.out;
    // 392 pixels of n.x and n.y read NaN (cases/known-failures.txt): 30 lines, then the rest.
    EXPECT_NE(r.out.find("n.x at (63, 17): GL nan, reference 0.026041666, allowed +-"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("... and 754 more"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("clip_noperspective_x_plane: FAIL: 0 of 4096 pixels' coverage and 784 of"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("GL_RENDERER \"llvmpipe"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("GL_VERSION \""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(std::string("(") + backend + ": "), std::string::npos) << r.out;
  }
}

TEST_F(Export, PassingCasesPassOnLlvmpipe) {
  if (!has_cc_) GTEST_SKIP() << "no C compiler (cc)";
  // One triangle, a mesh with shared edges, and centres exactly on shared edges.
  for (const char* name : {"face_on", "grid_mesh", "shared_centres_grid"}) {
    const std::string program = build(source("cases/") + name + ".json", name);
    ASSERT_FALSE(program.empty()) << name;
    for (const char* backend : {"egl", "osmesa"}) {
      const auto r = run(program, "llvmpipe", backend);
      EXPECT_EQ(r.exit_code, 0) << name << " " << backend << "\n" << r.out;
      EXPECT_NE(r.out.find(std::string(name) + ": pass: 4096 pixels' coverage and "),
                std::string::npos)
          << r.out;
      EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    }
  }
}

// The reproducer calls glClipControl: without it the upper-left case would draw the triangles
// its culling keeps upside down and cull the others, the zero-to-one case draw in front of
// z_c = 0 with other depths.
TEST_F(Export, ClipControlCasesPassOnLlvmpipe) {
  if (!has_cc_) GTEST_SKIP() << "no C compiler (cc)";
  for (const char* name : {"clip_control_upper_left_cull_back", "clip_control_zero_to_one_near"}) {
    const std::string program = build(source("cases/") + name + ".json", name);
    ASSERT_FALSE(program.empty()) << name;
    const auto r = run(program, "llvmpipe", "egl");
    EXPECT_EQ(r.exit_code, 0) << name << "\n" << r.out;
    EXPECT_NE(r.out.find(std::string(name) + ": pass: "), std::string::npos) << r.out;
  }
}

// softpipe leaves a pixel of a shared edge undrawn in one case and draws one twice in the other;
// llvmpipe draws both right. glrefcheck itself says so first, so that the data stays evidence.
TEST_F(Export, SoftpipeSharedEdgeFailuresOnSoftpipeOnly) {
  if (!has_cc_) GTEST_SKIP() << "no C compiler (cc)";
  const std::pair<const char*, const char*> cases[] = {
      {"softpipe_gap", "gap at (13, 11): 0 fragments, reference 1\n"},
      {"softpipe_double_hit", "double hit at (14, 4): 2 fragments, reference 1\n"},
      // The same beside a third triangle's snapping band, where the count alone is free: the
      // fragment trace shows both triangles of the shared edge.
      {"softpipe_double_hit_beside_band", "double hit at (14, 4): 2 fragments, reference 1\n"},
  };
  for (const auto& [name, failure] : cases) {
    const std::string file = source("tests/cli/data/") + name + ".json";
    const std::string out = " --jobs 1 --out '" + (dir_ / "run").string() + "'";
    EXPECT_EQ(glrefcheck("run '" + file + "' --driver softpipe" + out).exit_code, 1) << name;
    EXPECT_EQ(glrefcheck("run '" + file + "'" + out).exit_code, 0) << name;

    // Judged as for each driver: its model and GL_SUBPIXEL_BITS.
    const std::string on_softpipe =
        build(file, std::string(name) + "_softpipe", "--driver softpipe");
    const std::string on_llvmpipe =
        build(file, std::string(name) + "_llvmpipe", "--driver llvmpipe");
    ASSERT_FALSE(on_softpipe.empty() || on_llvmpipe.empty());
    for (const char* backend : {"egl", "osmesa"}) {
      const auto soft = run(on_softpipe, "softpipe", backend);
      EXPECT_EQ(soft.exit_code, 1) << name << " " << backend << "\n" << soft.out;
      EXPECT_EQ(soft.out.rfind(failure, 0), 0u) << soft.out;
      EXPECT_NE(soft.out.find(std::string(name) + ": FAIL: 1 of "), std::string::npos) << soft.out;
      EXPECT_NE(soft.out.find("GL_RENDERER \"softpipe\""), std::string::npos) << soft.out;
      const auto llvm = run(on_llvmpipe, "llvmpipe", backend);
      EXPECT_EQ(llvm.exit_code, 0) << name << " " << backend << "\n" << llvm.out;
    }
    // --subpixel-bits as the drivers report them: the same verdicts.
    const std::string bits4 = build(file, std::string(name) + "_4", "--subpixel-bits 4");
    ASSERT_FALSE(bits4.empty());
    EXPECT_EQ(run(bits4, "softpipe", "egl").exit_code, 1) << name;
    const std::string bits8 = build(file, std::string(name) + "_8", "--subpixel-bits 8");
    ASSERT_FALSE(bits8.empty());
    EXPECT_EQ(run(bits8, "llvmpipe", "egl").exit_code, 0) << name;
  }
}

TEST_F(Export, NoGLIsExit2) {
  if (!has_cc_) GTEST_SKIP() << "no C compiler (cc)";
  const std::string program = build(source("cases/face_on.json"), "face_on");
  ASSERT_FALSE(program.empty());
  // OSMesa cannot run zink (Mesa crashes trying): refused, as glrefcheck refuses it.
  const auto zink = run(program, "zink", "osmesa");
  EXPECT_EQ(zink.exit_code, 2) << zink.out;
  EXPECT_NE(zink.out.find("face_on: no GL: OSMesa runs llvmpipe and softpipe only"),
            std::string::npos)
      << zink.out;
  const auto usage = run(program, "llvmpipe", "vulkan");
  EXPECT_EQ(usage.exit_code, 2) << usage.out;
  EXPECT_NE(usage.out.find("usage: "), std::string::npos) << usage.out;
}

TEST_F(Export, DefaultNameAndItsOwnFileReplaced) {
  // Into the working folder as <case name>.c; again over its own file.
  const std::string cd = "cd '" + dir_.string() + "' && '" + GLRC_BINARY_DIR + "/glrefcheck' ";
  const std::string args = "export '" + source("cases/face_on.json") + "' --format c";
  for (int k = 0; k < 2; ++k) {
    const auto r = shell(cd + args);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    EXPECT_EQ(r.out,
              "wrote face_on.c: compile with cc -std=c99 -O2 -o face_on face_on.c -ldl -lm, run "
              "with ./face_on [egl|osmesa]\n");
  }
  const std::string text = read(dir_ / "face_on.c");
  EXPECT_EQ(text.rfind(glrc::reproducer::kCReproducerSignature, 0), 0u);
  EXPECT_NE(text.find(" *   Build:  cc -std=c99 -O2 -o face_on face_on.c -ldl -lm\n"),
            std::string::npos);
  // Issue 45: a name starting with '-' was taken for cc's option, one with a space split.
  const auto dash = shell(cd + args + " --out='-my case.c'");
  EXPECT_EQ(dash.exit_code, 0) << dash.out;
  EXPECT_EQ(dash.out,
            "wrote -my case.c: compile with cc -std=c99 -O2 -o './-my case' './-my case.c' -ldl "
            "-lm, run with './-my case' [egl|osmesa]\n");
}

TEST_F(Export, BadInputIsOneLineAndExit2) {
  std::ofstream(dir_ / "mine.c") << "int main(void) { return 0; }\n";
  // More pixel values than a reproducer embeds: 200 x 300 pixels, 4 components, 7 values each.
  std::string big = read(source("cases/face_on.json"));
  big.insert(big.find('{') + 1, "\n  \"framebuffer\": {\"width\": 200, \"height\": 300},");
  std::ofstream(dir_ / "big.json") << big;
  const std::string face_on = " '" + source("cases/face_on.json") + "'";
  const std::pair<std::string, std::string> cases[] = {
      {"export '" + (dir_ / "missing.json").string() + "'",
       "missing.json: expected a readable case file"},
      {"export" + face_on + " --format xyz", "--format: expected c or shader_test, got \"xyz\""},
      {"export" + face_on + " --out '" + (dir_ / "mine.c").string() + "'",
       "--out: expected a new file or one glrefcheck wrote"},
      {"export" + face_on + " --out '" + (dir_ / "x.txt").string() + "'",
       "--out: expected a file name ending in .c"},
      {"export" + face_on + " --driver nvidia", "--driver: expected llvmpipe, softpipe or zink"},
      {"export" + face_on + " --threads 100000", "--threads"},  // it hung starting them
      {"export" + face_on + " --driver softpipe --tie-break top-left",
       "--tie-break: expected no model option with --driver softpipe"},
      {"export '" + (dir_ / "big.json").string() + "'",
       "big.json: 420,000 pixel values; a reproducer embeds at most 400,000: shrink the case "
       "first (glrefcheck fuzz --replay ...)"},
  };
  for (const auto& [args, message] : cases) {
    const auto e = glrefcheck(args);
    EXPECT_EQ(e.exit_code, 2) << args << "\n" << e.out << e.err;
    EXPECT_NE(e.err.find(message), std::string::npos) << args << "\n" << e.err;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << args << "\n" << e.err;
    EXPECT_TRUE(e.out.empty()) << args << "\n" << e.out;
  }
  EXPECT_EQ(read(dir_ / "mine.c"), "int main(void) { return 0; }\n");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.txt"));
}

// --format shader_test (export/shader_test.hpp; tests/cli/export_shader_test.sh runs the files
// with piglit's shader_runner): its name, its own file replaced, and what it refuses.
TEST_F(Export, ShaderTestDefaultNameAndItsOwnFileReplaced) {
  const std::string cd = "cd '" + dir_.string() + "' && '" + GLRC_BINARY_DIR + "/glrefcheck' ";
  const std::string args =
      "export '" + source("cases/face_on.json") + "' --format shader_test --driver llvmpipe";
  for (int k = 0; k < 2; ++k) {
    const auto r = shell(cd + args);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    EXPECT_EQ(r.out.rfind("wrote face_on.shader_test: run with PIGLIT_PLATFORM=surfaceless_egl "
                          "shader_runner face_on.shader_test -auto -fbo (values checked against "
                          "their ranges at 64 of ",
                          0),
              0u)
        << r.out;
  }
  const std::string text = read(dir_ / "face_on.shader_test");
  EXPECT_EQ(
      text.rfind(std::string(glrc::reproducer::kShaderTestSignature) + " of case face_on\n", 0),
      0u);
  EXPECT_NE(text.find("\n# Written by: glrefcheck export " + source("cases/face_on.json") +
                      " --format shader_test --driver llvmpipe\n"),
            std::string::npos);
  EXPECT_NE(text.find("#   Run: PIGLIT_PLATFORM=surfaceless_egl shader_runner face_on.shader_test "
                      "-auto -fbo\n"),
            std::string::npos);
  for (const char* section : {"\n[require]\n", "\n[vertex shader]\n", "\n[fragment shader]\n",
                              "\n[vertex data]\n", "\n[test]\n"})
    EXPECT_NE(text.find(section), std::string::npos) << section;
}

TEST_F(Export, ShaderTestBadInputIsOneLineAndExit2) {
  std::ofstream(dir_ / "mine.shader_test") << "[require]\n";
  const std::string st = " --format shader_test";
  const std::pair<std::string, std::string> cases[] = {
      {"export '" + source("cases/depth_range_partial.json") + "'" + st,
       "depth_range_partial.json: depth_range (near 0.25, far 0.75) cannot be expressed in a "
       "shader_test: shader_runner has no glDepthRange command (only [0, 1])"},
      {"export '" + source("cases/look_at_cube.json") + "'" + st,
       "look_at_cube.json: cull back with depth_func less cannot be expressed in a shader_test"},
      {"export '" + source("cases/cull_front_and_back.json") + "'" + st,
       "cull_front_and_back.json: cull front_and_back cannot be expressed in a shader_test"},
      {"export '" + source("cases/face_on.json") + "'" + st + " --out '" +
           (dir_ / "mine.shader_test").string() + "'",
       "--out: expected a new file or one glrefcheck wrote"},
      {"export '" + source("cases/face_on.json") + "'" + st + " --out '" + (dir_ / "x.c").string() +
           "'",
       "--out: expected a file name ending in .shader_test"},
      {"export '" + source("cases/face_on.json") + "'" + st + " --out '" +
           (dir_ / ".shader_test").string() + "'",
       "--out: expected a file name ending in .shader_test"},
  };
  for (const auto& [args, message] : cases) {
    const auto e = glrefcheck(args);
    EXPECT_EQ(e.exit_code, 2) << args << "\n" << e.out << e.err;
    EXPECT_NE(e.err.find(message), std::string::npos) << args << "\n" << e.err;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << args << "\n" << e.err;
    EXPECT_TRUE(e.out.empty()) << args << "\n" << e.out;
  }
  EXPECT_EQ(read(dir_ / "mine.shader_test"), "[require]\n");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.c"));
}

// The library without GL: the harness's shaders and the case's floats, exactly.
TEST(ExportLibrary, EmbedsTheHarnessShadersAndExactFloats) {
  const glrc::Case c = glrc::casefile::load(source("cases/clip_noperspective_x_plane.json"));
  glrc::check::CheckOptions o;
  const glrc::Expectation e = glrc::check::expectation_for(c, o, 8);
  const glrc::Tolerance t = glrc::check::tolerance_for(c, o, 8);
  glrc::reproducer::CReproducerSetup setup;
  setup.shaders = {glrc::gl::vertex_shader_source(c),
                   glrc::gl::geometry_shader_source(c),
                   glrc::gl::fragment_shader_source(c, false),
                   glrc::gl::fragment_shader_source(c, true),
                   glrc::gl::count_vertex_shader_source(c.distances),
                   glrc::gl::count_geometry_shader_source(c.distances)};
  setup.first_draw = glrc::gl::first_draw_case();
  setup.first_draw_shaders = {glrc::gl::vertex_shader_source(setup.first_draw),
                              glrc::gl::geometry_shader_source(setup.first_draw),
                              glrc::gl::fragment_shader_source(setup.first_draw, false),
                              glrc::gl::fragment_shader_source(setup.first_draw, true),
                              glrc::gl::count_vertex_shader_source(setup.first_draw.distances),
                              glrc::gl::count_geometry_shader_source(setup.first_draw.distances)};
  setup.count_fragment = glrc::gl::count_fragment_shader_source();
  setup.trace_fragment = glrc::gl::trace_fragment_shader_source();
  setup.file_name = "repro.c";
  setup.exported_by = "test";
  setup.model = o.model.describe();
  const std::string text = glrc::reproducer::c_reproducer(c, e, t, setup);
  EXPECT_EQ(text.rfind(glrc::reproducer::kCReproducerSignature, 0), 0u);
  EXPECT_NE(text.find(" *   Build:  cc -std=c99 -O2 -o repro repro.c -ldl -lm\n"),
            std::string::npos);
  // Every line of the harness's shaders, as C string literals.
  EXPECT_NE(text.find("    \"noperspective out vec2 v0;\\n\"\n"), std::string::npos);
  EXPECT_NE(text.find("    \"  o_primitive = gl_PrimitiveID;\\n\"\n"), std::string::npos);
  // Vertex B: clip (2, 3, 0.5, 2), n (1, 0), s (1, 0).
  EXPECT_NE(
      text.find("/* vertex 1 */ 0x1p+1, 0x1.8p+1, 0x1p-1, 0x1p+1, 0x1p+0, 0x0p+0, 0x1p+0, 0x0p+0"),
      std::string::npos);
  EXPECT_NE(text.find("#define COMPONENT_COUNT 4\n"), std::string::npos);
  EXPECT_NE(text.find("{\"depth\", \"n.x\", \"n.y\", \"s.x\", \"s.y\"}"), std::string::npos);

  // Not a driver model's bits, and not beyond the size limit.
  glrc::Tolerance exact = t;
  exact.mode = glrc::ToleranceMode::exact;
  EXPECT_THROW(glrc::reproducer::c_reproducer(c, e, exact, setup), std::invalid_argument);
  glrc::Case big = c;
  big.fb_width = big.fb_height = 300;
  EXPECT_GT(glrc::reproducer::reproducer_values(big), glrc::reproducer::kMaxReproducerValues);
  EXPECT_THROW(glrc::reproducer::c_reproducer(big, e, t, setup), std::invalid_argument);
  EXPECT_EQ(glrc::reproducer::c_compile_command("dir/my case.c"),
            "cc -std=c99 -O2 -o 'dir/my case' 'dir/my case.c' -ldl -lm");
}

}  // namespace
