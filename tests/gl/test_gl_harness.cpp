// gl_harness on a real GL implementation. Mesa picks its driver once per process, so this
// binary renders with one backend and driver, chosen by environment:
//   GLRC_TEST_BACKEND = osmesa (default) | egl | egl-device
//   GLRC_TEST_DRIVER  = llvmpipe (default) | softpipe | zink (egl) | "" (set but empty: the
//                       platform's own)
// Cases are built here in C++ so that only gl_harness and core are under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>

#include "casefile/casefile.hpp"
#include "check/check.hpp"
#include "compare/compare.hpp"
#include "core/case.hpp"
#include "core/frame.hpp"
#include "core/result.hpp"
#include "gl_harness/context.hpp"
#include "gl_harness/egl_context.hpp"
#include "gl_harness/first_draw.hpp"
#include "gl_harness/gl_harness.hpp"
#include "ref/reference.hpp"
#include "tests/support/gl_test_target.hpp"
#include "tests/support/same_result.hpp"

namespace glrc::gl {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The one renderer of this process, created on first use and destroyed by the environment
// below before main() returns (while Mesa and LLVM are still alive).
struct Shared {
  std::string unavailable;  // Unavailable::what() when creation failed
  Target target = test::gl_test_target(unavailable);
  std::unique_ptr<Renderer> renderer;
  double create_ms = 0;
  bool tried = false;
};

Shared& shared() {
  static Shared s;
  if (!s.tried && s.unavailable.empty()) {
    s.tried = true;
    auto start = Clock::now();
    try {
      s.renderer = create_renderer(s.target);
      s.create_ms = ms_since(start);
    } catch (const Unavailable& e) {
      s.unavailable = e.what();
    }
  }
  return s;
}

class SharedRendererEnvironment : public ::testing::Environment {
 public:
  void TearDown() override { shared().renderer.reset(); }
};
[[maybe_unused]] auto* const environment =
    ::testing::AddGlobalTestEnvironment(new SharedRendererEnvironment);

// Tests that need the GL renderer. egl-device is optional on a machine (a GPU machine without
// glvnd's device support, or a Mesa without a software device): skipped with the reason. The
// osmesa and egl backends are required where this suite runs: their absence fails.
class Gl : public ::testing::Test {
 protected:
  void SetUp() override {
    Shared& s = shared();
    if (s.renderer) return;
    if (s.target.backend == Backend::egl_device)
      GTEST_SKIP() << "egl-device unavailable: " << s.unavailable;
    FAIL() << "no " << to_string(s.target.backend) << " renderer: " << s.unavailable;
  }
  Renderer& gl() { return *shared().renderer; }
  const Target& target() { return shared().target; }
};

// --- Case building ---

Varying varying(std::string name, int size, Interpolation i) {
  Varying v;
  v.name = std::move(name);
  v.size = size;
  v.interpolation = i;
  return v;
}

Vertex vertex(float x, float y, float z, float w, std::vector<float> values = {}) {
  Vertex v;
  v.clip = {x, y, z, w};
  v.values = std::move(values);
  return v;
}

Case make_case(std::string name, int fb_w, int fb_h, Viewport vp) {
  Case c;
  c.name = std::move(name);
  c.fb_width = fb_w;
  c.fb_height = fb_h;
  c.viewport = vp;
  return c;
}

// Two CCW triangles covering the whole viewport: 0 = (v0 v1 v2) bottom-right, 1 = (v0 v2 v3)
// top-left. Every vertex at (z, w) with clip x, y scaled by w; `values(i)` its varyings.
template <typename Values>
void add_quad(Case& c, float z, float w, Values values) {
  const float xy[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  uint32_t base = uint32_t(c.vertices.size());
  for (int i = 0; i < 4; ++i)
    c.vertices.push_back(vertex(xy[i][0] * w, xy[i][1] * w, z * w, w, values(i)));
  c.triangles.push_back({base, base + 1, base + 2});
  c.triangles.push_back({base, base + 2, base + 3});
}

uint32_t bits(float f) {
  return std::bit_cast<uint32_t>(f);
}

// The quad's expected primitive at pixel (x, y) of an s x s viewport at the origin: the
// diagonal's pixel centres lie exactly on the shared edge, where either triangle may win (but
// exactly one must).
void expect_quad_primitive(int32_t primitive, int x, int y) {
  if (x > y)
    EXPECT_EQ(primitive, 0) << "at " << x << "," << y;
  else if (x < y)
    EXPECT_EQ(primitive, 1) << "at " << x << "," << y;
  else
    EXPECT_TRUE(primitive == 0 || primitive == 1) << primitive << " at " << x << "," << y;
}

void expect_uncovered(const Frame& f, int x, int y) {
  size_t p = f.index(x, y);
  EXPECT_EQ(f.primitive[p], Frame::kNoPrimitive) << "at " << x << "," << y;
  EXPECT_EQ(bits(f.depth[p]), bits(1.0f)) << "at " << x << "," << y;
  for (const auto& comp : f.components)
    EXPECT_EQ(bits(comp[p]), 0u) << "at " << x << "," << y;
}

int count_covered(const Frame& f) {
  int n = 0;
  for (int32_t p : f.primitive)
    n += p != Frame::kNoPrimitive;
  return n;
}

// --- Without a context ---

TEST(GlNames, BackendNamesRoundTrip) {
  for (Backend b : {Backend::osmesa, Backend::egl, Backend::egl_device})
    EXPECT_EQ(backend_from_string(to_string(b)), b);
  EXPECT_STREQ(to_string(Backend::egl_device), "egl-device");
  EXPECT_EQ(backend_from_string("egl_device"), std::nullopt);
  EXPECT_EQ(backend_from_string(""), std::nullopt);
}

TEST(GlLibraries, MissingLibraryNamesItAndHowToGetIt) {
  try {
    open_library({"libglrc-no-such-library.so.7"}, "install glrc-no-such (apt-get install x)");
    FAIL() << "dlopen of a nonexistent soname succeeded";
  } catch (const Unavailable& e) {
    std::string m = e.what();
    EXPECT_EQ(m.rfind("libglrc-no-such-library.so.7 not found", 0), 0u) << m;
    EXPECT_NE(m.find("install glrc-no-such (apt-get install x)"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

TEST(GlLibraries, MissingLibraryMessageNamesFallbacks) {
  std::string m = missing_library_message({"libOSMesa.so.8", "libOSMesa.so.6"}, "",
                                          "install Debian's libosmesa6 (apt-get install "
                                          "libosmesa6)");
  EXPECT_EQ(m,
            "libOSMesa.so.8 not found (nor libOSMesa.so.6): install Debian's libosmesa6 "
            "(apt-get install libosmesa6)");
}

TEST(GlLibraries, ExtensionListsMatchWholeNames) {
  EXPECT_TRUE(has_extension("EGL_KHR_a EGL_MESA_platform_surfaceless", "EGL_KHR_a"));
  EXPECT_TRUE(
      has_extension("EGL_KHR_a EGL_MESA_platform_surfaceless", "EGL_MESA_platform_surfaceless"));
  EXPECT_FALSE(has_extension("EGL_KHR_abc EGL_KHR_x", "EGL_KHR_a"));
  EXPECT_FALSE(has_extension("EGL_EXT_device_base_x", "EGL_EXT_device_base"));
  EXPECT_FALSE(has_extension("", "EGL_KHR_a"));
}

TEST(GlLibraries, WrongDriverIsUnavailable) {
  Target t;
  t.driver = "softpipe";
  EXPECT_NO_THROW(check_driver(t, "SoftPipe", "here"));
  try {
    check_driver(t, "llvmpipe (LLVM 15.0.6, 256 bits)", "OSMesa");
    FAIL() << "llvmpipe accepted for softpipe";
  } catch (const Unavailable& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind(
            "asked for driver softpipe, but GL_RENDERER is 'llvmpipe (LLVM 15.0.6, 256 bits)'", 0),
        0u)
        << e.what();
  }
  t.driver = "";  // the platform's own driver: anything goes
  EXPECT_NO_THROW(check_driver(t, "NVIDIA H100 80GB HBM3/PCIe/SSE2", "EGL device 0"));
  // zink names the Vulkan driver under it: llvmpipe asked for, zink on lavapipe is not it.
  t.driver = "zink";
  EXPECT_NO_THROW(check_driver(t, "zink (llvmpipe (LLVM 15.0.6, 256 bits))", "EGL"));
  t.driver = "llvmpipe";
  EXPECT_THROW(check_driver(t, "zink (llvmpipe (LLVM 15.0.6, 256 bits))", "EGL"), Unavailable);
}

TEST(GlLibraries, ZinkIsACpuDriverOnEglOnly) {
  EXPECT_TRUE(is_mesa_cpu_driver("zink"));
  EXPECT_TRUE(is_mesa_cpu_driver("llvmpipe"));
  EXPECT_FALSE(is_mesa_software_driver("zink"));  // OSMesa cannot run it
  EXPECT_FALSE(is_mesa_cpu_driver("radeonsi"));
  // Refused before libOSMesa is touched (it would segfault in OSMesaCreateContextAttribs).
  Target t;
  t.backend = Backend::osmesa;
  t.driver = "zink";
  try {
    create_osmesa_context(t);
    FAIL() << "OSMesa accepted zink";
  } catch (const Unavailable& e) {
    EXPECT_STREQ(e.what(),
                 "OSMesa runs Mesa's software drivers only: expected --driver llvmpipe or "
                 "softpipe, got \"zink\" (use --backend egl)");
  }
}

// --- The first draw, judged on synthetic frames (a wrong driver is not needed) ---

// What a right implementation draws for first_draw_case().
Frame right_first_draw() {
  Frame f(4, 4, 1);
  for (size_t i = 0; i < f.pixel_count(); ++i) {
    f.primitive[i] = 0;
    f.components[0][i] = 1.0f;
  }
  return f;
}

TEST(FirstDraw, CaseCoversTheWholeFramebuffer) {
  const Case c = first_draw_case();
  EXPECT_EQ(c.fb_width, 4);
  EXPECT_EQ(c.fb_height, 4);
  ASSERT_EQ(c.varyings.size(), 1u);
  EXPECT_EQ(c.varyings[0].interpolation, Interpolation::flat);
  // The reference agrees with what the judge expects.
  const Expectation r = ref::render(c, Model{}, 8);
  EXPECT_TRUE(judge_first_draw(r.frame).right()) << judge_first_draw(r.frame).fault;
}

TEST(FirstDraw, RightFrameIsRight) {
  const FirstDrawVerdict v = judge_first_draw(right_first_draw());
  EXPECT_TRUE(v.right());
  EXPECT_EQ(v.fault, "");
}

TEST(FirstDraw, WrongFlatValueNamesPixelExpectedAndGot) {
  Frame f = right_first_draw();
  f.components[0][f.index(2, 1)] = 0.5f;
  f.components[0][f.index(3, 3)] = 1.00000012f;
  const FirstDrawVerdict v = judge_first_draw(f);
  EXPECT_EQ(v.wrong_pixels, 2);
  EXPECT_EQ(v.fault,
            "pixel (2, 1) expected primitive 0 and flat value 1, got primitive 0 and value 0.5 "
            "(2 of 16 pixels wrong)");
}

TEST(FirstDraw, WrongPrimitiveIdAndNothingDrawnAreWrong) {
  Frame f = right_first_draw();
  f.primitive[f.index(0, 0)] = 7;
  EXPECT_EQ(judge_first_draw(f).fault,
            "pixel (0, 0) expected primitive 0 and flat value 1, got primitive 7 and value 1 "
            "(1 of 16 pixels wrong)");
  const FirstDrawVerdict nothing = judge_first_draw(Frame(4, 4, 1));  // softpipe without a GS
  EXPECT_EQ(nothing.wrong_pixels, 16);
  EXPECT_EQ(nothing.fault,
            "pixel (0, 0) expected primitive 0 and flat value 1, got primitive none and value 0 "
            "(16 of 16 pixels wrong)");
  EXPECT_EQ(judge_first_draw(Frame(2, 2, 1)).wrong_pixels, 16);
}

TEST(FirstDraw, GeometryShaderOnlyWhereItDrawsRight) {
  const FirstDrawVerdict right = judge_first_draw(right_first_draw());
  const FirstDrawVerdict nothing = judge_first_draw(Frame(4, 4, 1));
  Frame one_off = right_first_draw();
  one_off.components[0][0] = 2.0f;
  const FirstDrawVerdict wrong = judge_first_draw(one_off);

  // llvmpipe: right at once; the geometry shader is never tried.
  FirstDrawChoice c = choose_first_draw(right, std::nullopt);
  EXPECT_FALSE(c.geometry_shader);
  EXPECT_EQ(c.warning, "");
  // softpipe 22.3.6: nothing without, right with a geometry shader. Worked around, and the
  // warning names the bug and the work-around.
  c = choose_first_draw(nothing, right);
  EXPECT_TRUE(c.geometry_shader);
  EXPECT_EQ(c.warning,
            "gl_PrimitiveID read in a fragment shader without a geometry shader is wrong (the "
            "first draw, one triangle covering a 4x4 framebuffer: pixel (0, 0) expected "
            "primitive 0 and flat value 1, got primitive none and value 0 (16 of 16 pixels "
            "wrong)); worked around: cases are drawn with a pass-through geometry shader, except "
            "those with \"work_arounds\": false");
  // A wrong flat value with and without: a warning, no geometry shader, the run goes on.
  c = choose_first_draw(wrong, wrong);
  EXPECT_FALSE(c.geometry_shader);
  EXPECT_EQ(c.warning,
            "the first draw (one triangle covering a 4x4 framebuffer) is wrong: pixel (0, 0) "
            "expected primitive 0 and flat value 1, got primitive 0 and value 2 (1 of 16 pixels "
            "wrong); with a pass-through geometry shader for gl_PrimitiveID: pixel (0, 0) "
            "expected primitive 0 and flat value 1, got primitive 0 and value 2 (1 of 16 pixels "
            "wrong); cases are drawn without a geometry shader and each passes or fails on its "
            "own");
  // Nothing drawn without, one pixel wrong with: the geometry shader draws more, and is used.
  c = choose_first_draw(nothing, wrong);
  EXPECT_TRUE(c.geometry_shader);
  EXPECT_NE(c.warning.find("cases are drawn with a geometry shader"), std::string::npos);
  // The geometry shader does not even compile: its fault is the render error.
  c = choose_first_draw(wrong, FirstDrawVerdict{16, "no draw: case 'x': geometry shader ..."});
  EXPECT_FALSE(c.geometry_shader);
  EXPECT_NE(c.warning.find("gl_PrimitiveID: no draw: case 'x'"), std::string::npos) << c.warning;
}

// --- With the renderer ---

TEST_F(Gl, InfoNamesDriverAndVersion) {
  const GlInfo& info = gl().info();
  std::cout << "[ info     ] backend " << to_string(target().backend) << ", driver '"
            << target().driver << "': GL_VENDOR '" << info.vendor << "', GL_RENDERER '"
            << info.renderer << "', GL_VERSION '" << info.version << "', GL_SUBPIXEL_BITS "
            << info.subpixel_bits << "; " << info.platform << "; gl_PrimitiveID through a "
            << (info.primitive_id_from_geometry_shader ? "geometry shader" : "fragment shader only")
            << "; create_renderer took " << shared().create_ms << " ms\n";
  int major = 0, minor = 0;
  ASSERT_EQ(std::sscanf(info.version.c_str(), "%d.%d", &major, &minor), 2) << info.version;
  EXPECT_GE(major * 10 + minor, 33) << info.version;
  EXPECT_GE(info.subpixel_bits, 4);  // GL's minimum
  std::string lower_renderer;
  for (char ch : info.renderer)
    lower_renderer += char(std::tolower((unsigned char)ch));
  EXPECT_NE(lower_renderer.find(target().driver), std::string::npos) << info.renderer;
  // The first draw is right, or (softpipe) right with the work-around, which is reported.
  if (info.primitive_id_from_geometry_shader) {
    ASSERT_EQ(info.warnings.size(), 1u);
    EXPECT_NE(info.warnings[0].find("gl_PrimitiveID read in a fragment shader without a geometry "
                                    "shader is wrong"),
              std::string::npos)
        << info.warnings[0];
    EXPECT_NE(info.warnings[0].find("worked around"), std::string::npos) << info.warnings[0];
  } else {
    EXPECT_TRUE(info.warnings.empty()) << info.warnings.front();
  }
  if (is_mesa_cpu_driver(target().driver)) {
    EXPECT_NE(info.version.find("Mesa"), std::string::npos) << info.version;
    // What the driver models of the reference are built on (MESA_NOTES.md).
    EXPECT_EQ(info.subpixel_bits, target().driver == "llvmpipe" ? 8 : 4);
  }
  // On llvmpipe a geometry shader would change the bits under test.
  if (target().driver == "llvmpipe") {
    EXPECT_FALSE(info.primitive_id_from_geometry_shader);
  }
  EXPECT_FALSE(info.platform.empty());
  // The environment that chose the driver (Mesa reads it when it creates its screen).
  if (!target().driver.empty()) {
    const char* gallium = std::getenv("GALLIUM_DRIVER");
    EXPECT_STREQ(gallium ? gallium : "", target().driver.c_str());
  }
  if (target().driver == "zink") {
    // GL on Vulkan, here on lavapipe (LIBGL_ALWAYS_SOFTWARE picks a CPU Vulkan device).
    EXPECT_EQ(info.renderer.rfind("zink (", 0), 0u) << info.renderer;
    EXPECT_EQ(target().backend, Backend::egl) << "zink runs through EGL only";
  }
  if (target().backend != Backend::osmesa && is_mesa_cpu_driver(target().driver)) {
    const char* software = std::getenv("LIBGL_ALWAYS_SOFTWARE");
    EXPECT_STREQ(software ? software : "", "1");
  }
}

TEST_F(Gl, ConstantQuadIsExactEverywhere) {
  Case c = make_case("constant_quad", 16, 16, {0, 0, 16, 16});
  c.varyings = {varying("color", 4, Interpolation::smooth), varying("id", 1, Interpolation::flat)};
  add_quad(c, 0.0f, 1.0f, [](int) { return std::vector<float>{1.5f, -2.0f, 0.25f, 1e6f, 42.0f}; });
  Frame f = gl().render(c);
  ASSERT_EQ(f.width, 16);
  ASSERT_EQ(f.height, 16);
  ASSERT_EQ(f.components.size(), 5u);
  const float expected[5] = {1.5f, -2.0f, 0.25f, 1e6f, 42.0f};
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      size_t p = f.index(x, y);
      expect_quad_primitive(f.primitive[p], x, y);
      EXPECT_EQ(bits(f.depth[p]), bits(0.5f)) << f.depth[p] << " at " << x << "," << y;
      for (int k = 0; k < 5; ++k)
        EXPECT_EQ(bits(f.components[size_t(k)][p]), bits(expected[k]))
            << "component " << k << " = " << f.components[size_t(k)][p] << " at " << x << "," << y;
    }
}

// The counting pass's traces (core/fragment_trace.hpp): GL's sums of p + 1 and of the hash of p
// are fragment_trace()'s, for one fragment of each of 2,000 triangles (primitive ids up to 1,999,
// each triangle around its own pixel centre), and for two triangles drawn over one centre.
TEST_F(Gl, FragmentTracesAreTheHarnessOwnSums) {
  constexpr int kSide = 50, kCount = 2000;
  Case c = make_case("traces", kSide, kCount / kSide + 1, {0, 0, kSide, kCount / kSide + 1});
  const float w = float(kSide), h = float(kCount / kSide + 1);
  // A small triangle around the centre of pixel (x, y), in clip coordinates.
  auto around = [&](int x, int y) {
    const float cx = (2 * (x + 0.5f)) / w - 1, cy = (2 * (y + 0.5f)) / h - 1;
    const float dx = 0.6f / w, dy = 0.6f / h;
    const uint32_t first = uint32_t(c.vertices.size());
    c.vertices.push_back(vertex(cx - dx, cy - dy, 0, 1, {}));
    c.vertices.push_back(vertex(cx + dx, cy - dy, 0, 1, {}));
    c.vertices.push_back(vertex(cx, cy + dy, 0, 1, {}));
    c.triangles.push_back({first, first + 1, first + 2});
  };
  for (int p = 0; p < kCount; ++p)
    around(p % kSide, p / kSide);
  around(0, kCount / kSide);  // primitives 2000 and 2001 over one centre
  around(0, kCount / kSide);
  const Frame f = gl().render(c);
  std::vector<size_t> pixels;
  for (int p = 0; p < kCount; ++p)
    pixels.push_back(f.index(p % kSide, p / kSide));
  pixels.push_back(f.index(0, kCount / kSide));
  pixels.push_back(f.index(1, kCount / kSide));  // nothing there
  const std::vector<std::optional<FragmentTrace>> traces = gl().fragment_traces(c, pixels);
  ASSERT_EQ(traces.size(), pixels.size());
  for (int p = 0; p < kCount; ++p) {
    ASSERT_TRUE(traces[size_t(p)].has_value()) << p;
    EXPECT_EQ(*traces[size_t(p)], fragment_trace(p)) << "primitive " << p;
  }
  FragmentTrace two = fragment_trace(kCount);
  two += fragment_trace(kCount + 1);
  EXPECT_EQ(traces[size_t(kCount)], two);
  EXPECT_EQ(traces[size_t(kCount) + 1], FragmentTrace{});
}

TEST_F(Gl, RowZeroIsTheBottom) {
  // A 20x12 framebuffer; the quad covers only the bottom half of the viewport (y_c in [-1,0]).
  Case c = make_case("bottom_half", 20, 12, {0, 0, 20, 12});
  c.varyings = {varying("v", 1, Interpolation::smooth)};
  const float xy[4][2] = {{-1, -1}, {1, -1}, {1, 0}, {-1, 0}};
  for (auto& p : xy)
    c.vertices.push_back(vertex(p[0], p[1], 0, 1, {7.0f}));
  c.triangles = {{0, 1, 2}, {0, 2, 3}};
  Frame f = gl().render(c);
  ASSERT_EQ(f.width, 20);
  ASSERT_EQ(f.height, 12);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 20; ++x) {
      if (y < 6) {
        EXPECT_NE(f.primitive[f.index(x, y)], Frame::kNoPrimitive) << "at " << x << "," << y;
        EXPECT_EQ(f.components[0][f.index(x, y)], 7.0f) << "at " << x << "," << y;
      } else {
        expect_uncovered(f, x, y);
      }
    }
}

TEST_F(Gl, ViewportOffsetLeavesTheRestUncovered) {
  Case c = make_case("viewport_offset", 16, 16, {4, 4, 8, 8});
  c.varyings = {varying("v", 2, Interpolation::noperspective)};
  add_quad(c, 0.0f, 1.0f, [](int) { return std::vector<float>{3.0f, -0.5f}; });
  Frame f = gl().render(c);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      bool inside = x >= 4 && x < 12 && y >= 4 && y < 12;
      if (!inside) {
        expect_uncovered(f, x, y);
        continue;
      }
      size_t p = f.index(x, y);
      expect_quad_primitive(f.primitive[p], x - 4, y - 4);
      EXPECT_EQ(bits(f.depth[p]), bits(0.5f));
      EXPECT_EQ(bits(f.components[0][p]), bits(3.0f));
      EXPECT_EQ(bits(f.components[1][p]), bits(-0.5f));
    }
}

TEST_F(Gl, FlatTakesTheProvokingVertex) {
  Case c = make_case("provoking", 16, 16, {0, 0, 16, 16});
  c.varyings = {varying("f", 1, Interpolation::flat)};
  // Distinct per vertex: triangle 0 is (v0 v1 v2), triangle 1 is (v0 v2 v3).
  add_quad(c, 0.0f, 1.0f, [](int i) { return std::vector<float>{10.0f * float(i + 1)}; });
  for (ProvokingVertex pv : {ProvokingVertex::last, ProvokingVertex::first}) {
    c.provoking = pv;
    Frame f = gl().render(c);
    for (size_t p = 0; p < f.pixel_count(); ++p) {
      ASSERT_NE(f.primitive[p], Frame::kNoPrimitive);
      float expected = pv == ProvokingVertex::first ? 10.0f : f.primitive[p] == 0 ? 30.0f : 40.0f;
      EXPECT_EQ(f.components[0][p], expected)
          << (pv == ProvokingVertex::first ? "first" : "last") << ", primitive " << f.primitive[p];
    }
  }
}

TEST_F(Gl, CullingFollowsFrontFace) {
  Case c = make_case("cull", 16, 16, {0, 0, 16, 16});
  // Clockwise in window coordinates (y up): up the left edge, then to the bottom right.
  c.vertices = {vertex(-1, -1, 0, 1), vertex(-1, 1, 0, 1), vertex(1, -1, 0, 1)};
  c.triangles = {{0, 1, 2}};
  c.cull = CullFace::none;
  const int half = count_covered(gl().render(c));
  EXPECT_GT(half, 100);  // 120 or 136: the diagonal's centres are on the edge
  c.cull = CullFace::back;
  c.front_face = FrontFace::ccw;
  EXPECT_EQ(count_covered(gl().render(c)), 0);
  c.front_face = FrontFace::cw;
  EXPECT_EQ(count_covered(gl().render(c)), half);
  c.cull = CullFace::front;
  EXPECT_EQ(count_covered(gl().render(c)), 0);
  c.cull = CullFace::front_and_back;
  c.front_face = FrontFace::ccw;
  EXPECT_EQ(count_covered(gl().render(c)), 0);
}

TEST_F(Gl, DepthRangeIncludingReversed) {
  Case c = make_case("depth_range", 8, 8, {0, 0, 8, 8});
  add_quad(c, 0.0f, 1.0f, [](int) { return std::vector<float>{}; });  // z_ndc 0
  Case half = make_case("depth_range_half", 8, 8, {0, 0, 8, 8});
  add_quad(half, 0.5f, 2.0f, [](int) { return std::vector<float>{}; });  // z_c = 0.5 w_c
  struct Expect {
    float n, f, at_zero, at_half;
  };
  for (Expect e :
       {Expect{0, 1, 0.5f, 0.75f}, Expect{1, 0, 0.5f, 0.25f}, Expect{0.25f, 0.75f, 0.5f, 0.625f}}) {
    for (Case* k : {&c, &half}) {
      k->depth_near = e.n;
      k->depth_far = e.f;
      Frame f = gl().render(*k);
      float expected = k == &c ? e.at_zero : e.at_half;
      for (size_t p = 0; p < f.pixel_count(); ++p)
        EXPECT_EQ(bits(f.depth[p]), bits(expected))
            << f.depth[p] << " with glDepthRange(" << e.n << ", " << e.f << ")";
    }
  }
}

TEST_F(Gl, DepthFuncLessKeepsTheNearer) {
  Case c = make_case("depth_func", 8, 8, {0, 0, 8, 8});
  c.varyings = {varying("layer", 1, Interpolation::flat)};
  add_quad(c, -0.5f, 1.0f, [](int) { return std::vector<float>{1.0f}; });  // triangles 0, 1
  add_quad(c, 0.5f, 1.0f, [](int) { return std::vector<float>{2.0f}; });   // triangles 2, 3
  c.depth_func = DepthFunc::always;                                        // the later draw wins
  Frame f = gl().render(c);
  for (size_t p = 0; p < f.pixel_count(); ++p) {
    EXPECT_GE(f.primitive[p], 2);
    EXPECT_EQ(f.depth[p], 0.75f);
    EXPECT_EQ(f.components[0][p], 2.0f);
  }
  c.depth_func = DepthFunc::less;  // the nearer one wins
  f = gl().render(c);
  for (size_t p = 0; p < f.pixel_count(); ++p) {
    EXPECT_LE(f.primitive[p], 1);
    EXPECT_EQ(f.depth[p], 0.25f);
    EXPECT_EQ(f.components[0][p], 1.0f);
  }
}

TEST_F(Gl, EveryVaryingSizeLandsInItsComponents) {
  Case c = make_case("layout", 4, 4, {0, 0, 4, 4});
  c.varyings = {varying("a", 1, Interpolation::smooth), varying("b", 2, Interpolation::flat),
                varying("c", 3, Interpolation::noperspective),
                varying("d", 4, Interpolation::smooth)};
  std::vector<float> values;
  for (int k = 0; k < 10; ++k)
    values.push_back(0.5f * float(k + 1) * (k % 2 ? -1.0f : 1.0f));
  add_quad(c, 0.0f, 1.0f, [&](int) { return values; });
  Frame f = gl().render(c);
  ASSERT_EQ(f.components.size(), 10u);
  for (size_t k = 0; k < 10; ++k)
    for (size_t p = 0; p < f.pixel_count(); ++p)
      EXPECT_EQ(bits(f.components[k][p]), bits(values[k])) << "component " << k;
}

// A readback converted on the CPU goes through a staging band of about a megabyte
// (framebuffer.cpp): 1000 pixels wide, an RGBA32F attachment's band holds 65 rows and the
// fragment counts' and a 24-bit depth's 262, so 300 rows take several bands of each, the last
// one short (with the default 32F depth, and from a second renderer with a 24-bit one). Every
// row read alone (a band of one row) is that row of the frame read whole: no band lands in
// another's rows. The values change from row to row and pixel to pixel (perspective), and a
// nearer triangle over a corner gives fragment counts of 2, so a misplaced band would show.
TEST_F(Gl, ReadBackThroughStagingBandsPutsEveryRowInItsPlace) {
  Case c = make_case("staging_bands", 1000, 300, {0, 0, 1000, 300});
  c.depth_func = DepthFunc::less;
  c.varyings = {varying("a", 3, Interpolation::smooth),
                varying("b", 4, Interpolation::noperspective)};
  const float w[4] = {1.0f, 2.0f, 4.0f, 3.0f};
  const float xy[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int i = 0; i < 4; ++i) {
    std::vector<float> values;
    for (int k = 0; k < 7; ++k)
      values.push_back(float(1 + i * 7 + k) * (k % 2 ? -0.375f : 1.25f));
    c.vertices.push_back(
        vertex(xy[i][0] * w[i], xy[i][1] * w[i], (0.2f * float(i) - 0.3f) * w[i], w[i], values));
  }
  c.triangles = {{0, 1, 2}, {0, 2, 3}};
  c.vertices.push_back(vertex(-1, -1, -0.5f, 1, std::vector<float>(7, 3.0f)));
  c.vertices.push_back(vertex(0, -1, -0.5f, 1, std::vector<float>(7, -1.0f)));
  c.vertices.push_back(vertex(-1, 0, -0.5f, 1, std::vector<float>(7, 0.5f)));
  c.triangles.push_back({4, 5, 6});
  Target unorm24 = target();
  unorm24.depth_format = DepthFormat::unorm24;
  const std::unique_ptr<Renderer> second = create_renderer(unorm24);
  for (Renderer* renderer : {&gl(), second.get()}) {
    SCOPED_TRACE(renderer == &gl() ? "32F depth" : "24-bit depth");
    const Frame whole = renderer->render(c);
    ASSERT_EQ(whole.height, 300);
    ASSERT_EQ(whole.components.size(), 7u);
    ASSERT_EQ(whole.fragments.size(), whole.pixel_count());
    EXPECT_GT(std::count(whole.fragments.begin(), whole.fragments.end(), uint16_t(2)), 10000);
    EXPECT_NE(whole.components[0][whole.index(500, 10)],
              whole.components[0][whole.index(500, 290)]);
    EXPECT_NE(whole.depth[whole.index(500, 10)], whole.depth[whole.index(500, 290)]);
    renderer->draw(c);
    for (int y = 0; y < c.fb_height; ++y) {
      SCOPED_TRACE("row " + std::to_string(y));
      const Frame row = renderer->read_rows(c, y, 1);
      const Frame expected = whole.rows(y, 1);
      EXPECT_EQ(row.primitive, expected.primitive);
      EXPECT_EQ(row.fragments, expected.fragments);
      EXPECT_EQ(row.depth, expected.depth);
      EXPECT_EQ(ref::digest(row), ref::digest(expected));  // every component, bit for bit
    }
  }
}

TEST_F(Gl, SmoothIsPerspectiveCorrectAndNoperspectiveIsNot) {
  // Window triangle (0,0) (16,0) (0,16) in a 16x16 viewport, with w = 1, 2, 4 at the vertices.
  Case c = make_case("perspective", 16, 16, {0, 0, 16, 16});
  c.varyings = {varying("s", 1, Interpolation::smooth),
                varying("n", 1, Interpolation::noperspective)};
  const float w[3] = {1, 2, 4}, ndc[3][2] = {{-1, -1}, {1, -1}, {-1, 1}}, v[3] = {0, 1, 0.25f};
  for (int i = 0; i < 3; ++i)
    c.vertices.push_back(vertex(ndc[i][0] * w[i], ndc[i][1] * w[i], 0, w[i], {v[i], v[i]}));
  c.triangles = {{0, 1, 2}};
  Frame f = gl().render(c);
  int checked = 0;
  double largest_difference = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x + y < 15; ++x) {  // strictly inside: no edge ties
      double l1 = (x + 0.5) / 16, l2 = (y + 0.5) / 16, l0 = 1 - l1 - l2;
      double linear = l0 * v[0] + l1 * v[1] + l2 * v[2];
      double smooth = (l0 * v[0] / w[0] + l1 * v[1] / w[1] + l2 * v[2] / w[2]) /
                      (l0 / w[0] + l1 / w[1] + l2 / w[2]);
      size_t p = f.index(x, y);
      ASSERT_EQ(f.primitive[p], 0) << "at " << x << "," << y;
      EXPECT_NEAR(f.components[0][p], smooth, 1e-5) << "smooth at " << x << "," << y;
      EXPECT_NEAR(f.components[1][p], linear, 1e-5) << "noperspective at " << x << "," << y;
      largest_difference = std::max(largest_difference, std::abs(smooth - linear));
      ++checked;
    }
  EXPECT_EQ(checked, 120);
  EXPECT_GT(largest_difference, 0.1);  // the case does tell the two apart
}

TEST_F(Gl, SevenVaryingsWorkEightAreARenderError) {
  Case c = make_case("seven", 4, 4, {0, 0, 4, 4});
  for (int k = 0; k < 7; ++k)
    c.varyings.push_back(varying("v" + std::to_string(k), 4, Interpolation::smooth));
  std::vector<float> values;
  for (int k = 0; k < 28; ++k)
    values.push_back(float(k));
  add_quad(c, 0.0f, 1.0f, [&](int) { return values; });
  Frame f = gl().render(c);
  ASSERT_EQ(f.components.size(), 28u);
  for (size_t k = 0; k < 28; ++k)
    EXPECT_EQ(f.components[k][5], float(k));

  c.name = "eight";
  c.varyings.push_back(varying("v7", 1, Interpolation::flat));
  for (auto& vertex : c.vertices)
    vertex.values.push_back(1.0f);
  try {
    gl().render(c);
    FAIL() << "8 varyings rendered";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("case 'eight': 8 varyings"), std::string::npos)
        << e.what();
  }
}

TEST_F(Gl, BadCaseIsARenderErrorAndTheRendererGoesOn) {
  Case c = make_case("bad_index", 4, 4, {0, 0, 4, 4});
  add_quad(c, 0.0f, 1.0f, [](int) { return std::vector<float>{}; });
  c.triangles.push_back({0, 1, 4});
  EXPECT_THROW(gl().render(c), RenderError);
  c.triangles.pop_back();
  EXPECT_EQ(count_covered(gl().render(c)), 16);
}

TEST_F(Gl, ManyCasesOnOneContext) {
  // Hundreds of cases per context is the normal run: objects must not pile up, programs come
  // from the cache, every frame is still right.
  const Interpolation kinds[3] = {Interpolation::smooth, Interpolation::flat,
                                  Interpolation::noperspective};
  auto start = Clock::now();
  for (int i = 0; i < 300; ++i) {
    int size = 1 + i % 4, s = 8 + i % 13;
    Case c = make_case("many_" + std::to_string(i), s, s, {0, 0, s, s});
    c.varyings = {varying("v", size, kinds[i % 3])};
    std::vector<float> values(static_cast<size_t>(size), float(i));
    add_quad(c, 0.0f, 1.0f, [&](int) { return values; });
    Frame f = gl().render(c);
    ASSERT_EQ(count_covered(f), s * s) << c.name;
    ASSERT_EQ(f.components[size_t(size) - 1][f.index(s - 1, 0)], float(i)) << c.name;
  }
  std::cout << "[ timing   ] 300 small cases: " << ms_since(start) << " ms\n";
}

TEST_F(Gl, Timing256) {
  Case c = make_case("timing_256", 256, 256, {0, 0, 256, 256});
  c.varyings = {varying("v", 4, Interpolation::smooth)};
  add_quad(c, 0.0f, 1.0f, [](int i) { return std::vector<float>(4, float(i)); });
  c.vertices[2].clip = {2, 2, 0, 2};  // some perspective
  auto start = Clock::now();
  Frame f = gl().render(c);
  double first = ms_since(start);
  start = Clock::now();
  f = gl().render(c);
  double warm = ms_since(start);
  EXPECT_EQ(count_covered(f), 256 * 256);
  std::cout << "[ timing   ] 256x256, 2 triangles, 1 vec4: first " << first << " ms, warm " << warm
            << " ms\n";
}

TEST_F(Gl, SecondRendererWithTheSameDriverAgrees) {
  Case c = make_case("two_renderers", 16, 16, {0, 0, 16, 16});
  c.varyings = {varying("v", 3, Interpolation::smooth)};
  add_quad(c, 0.25f, 1.0f, [](int i) { return std::vector<float>{float(i), 0.5f, -1.0f}; });
  c.vertices[1].clip = {3, -3, 0.75f, 3};
  Frame a = gl().render(c);
  std::unique_ptr<Renderer> other = create_renderer(target());
  Frame b = other->render(c);
  Frame a2 = gl().render(c);  // back on the first context
  other.reset();
  Frame a3 = gl().render(c);  // still fine after the second is gone
  for (const Frame* f : {&b, &a2, &a3}) {
    EXPECT_EQ(f->primitive, a.primitive);
    EXPECT_EQ(f->depth, a.depth);
    EXPECT_EQ(f->components, a.components);
  }
}

TEST_F(Gl, AnotherDriverInTheSameProcessIsUnavailable) {
  Target other = target();
  other.driver = other.driver == "softpipe" ? "llvmpipe" : "softpipe";
  try {
    create_renderer(other);
    FAIL() << "a second driver was accepted";
  } catch (const Unavailable& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("driver '" + target().driver + "'"), std::string::npos) << m;
    EXPECT_NE(m.find("driver '" + other.driver + "'"), std::string::npos) << m;
    EXPECT_NE(m.find("once per process"), std::string::npos) << m;
  }
}

// EGL-only checks: they load libEGL, which an OSMesa process has no business doing.
class GlEgl : public Gl {
 protected:
  void SetUp() override {
    if (shared().target.backend == Backend::osmesa) GTEST_SKIP() << "EGL backends only";
    Gl::SetUp();
  }
};

// End to end on cases of the suite: the real driver against the exact reference, judged by
// check/ with the default options (the case file's own tolerance, where it sets one).
// GL's frame read back band by band (glReadPixels of each band's rows) is the frame render()
// reads whole; a case checked band by band (streamed) gets the whole check's verdict and
// statistics, bit for bit.
TEST_F(Gl, BandsReadBackAndStreamedChecksAreTheWholeOnes) {
  for (const char* name : {"fan", "clip_near", "depth_range_reversed", "viewport_offset"}) {
    SCOPED_TRACE(name);
    const Case c =
        casefile::load(std::string(GLRC_SOURCE_DIR) + "/cases/" + std::string(name) + ".json");
    const Frame whole = gl().render(c);
    gl().draw(c);
    Frame last;  // each band read into the last one's buffers too (read_rows_reusing)
    for (int y0 = 0; y0 < c.fb_height; y0 += 5) {
      const int rows = std::min(5, c.fb_height - y0);
      EXPECT_EQ(ref::digest(gl().read_rows(c, y0, rows)), ref::digest(whole.rows(y0, rows)));
      last = gl().read_rows_reusing(c, y0, rows, std::move(last));
      EXPECT_EQ(ref::digest(last), ref::digest(whole.rows(y0, rows)));
    }
    EXPECT_THROW(gl().read_rows(c, c.fb_height - 1, 2), RenderError);

    // Read back into the buffers of another case's frame: the same frame. Checked in the
    // frames of the last check of another case: the same result and frames.
    const Case other = casefile::load(std::string(GLRC_SOURCE_DIR) + "/cases/face_on.json");
    EXPECT_EQ(ref::digest(gl().render_reusing(c, gl().render(other))), ref::digest(whole));
    {
      const check::Checked fresh = check::check_with_frames(c, gl(), check::CheckOptions{});
      const check::Checked reused = check::check_with_frames(
          c, gl(), check::CheckOptions{}, check::check_with_frames(other, gl(), {}));
      test::expect_same_result(reused.result, fresh.result);
      EXPECT_EQ(ref::expectation_digest(reused.expected), ref::expectation_digest(fresh.expected));
      EXPECT_EQ(ref::digest(reused.gl), ref::digest(fresh.gl));
    }

    check::CheckOptions streamed;
    streamed.whole_frame_bytes = 0;
    streamed.slice_bytes = 3 * check::frame_bytes(c) / size_t(c.fb_height);  // 3 rows a band
    for (const bool exact : {false, true}) {
      check::CheckOptions o;
      if (exact) o.tolerance = streamed.tolerance = ToleranceMode::exact;
      const check::Checked a = check::check_with_frames(c, gl(), o);
      const check::Checked b = check::check_with_frames(c, gl(), streamed);
      EXPECT_FALSE(a.streamed);
      EXPECT_TRUE(b.streamed);
      EXPECT_TRUE(b.gl.components.empty() && b.expected.frame.primitive.empty());
      test::expect_same_result(a.result, b.result);
    }
  }
}

// A streamed case whose deferral pays (check::deferral_pays: one large perspective triangle):
// each band's allowance deferred (ref::render_rows_deferred), and GL's bands digested while the
// next is compared; the whole check's verdict and statistics, bit for bit, deferred or not.
TEST_F(Gl, StreamedChecksDeferTheAllowanceBandByBand) {
  const Case c = casefile::parse(R"({
    "description": "One large perspective triangle with a smooth vec4.",
    "framebuffer": {"width": 256, "height": 192},
    "varyings": [{"name": "v", "size": 4}],
    "vertices": [
      {"clip": [-1.6, -1.5, 0.2, 2], "v": [1, -40, 0.25, 3]},
      {"clip": [0.9, -0.6, -0.2, 1], "v": [0, 7, 0.5, -2]},
      {"clip": [0.02, 0.45, 0.1, 0.5], "v": [-3, 0.5, 1, 100]}
    ]
  })",
                                 "inline", "large_perspective");
  ASSERT_TRUE(check::deferral_pays(c));
  check::CheckOptions streamed;
  streamed.deferred_allowance = true;
  streamed.whole_frame_bytes = 0;
  streamed.slice_bytes = 7 * check::frame_bytes(c) / size_t(c.fb_height);  // 7 rows a band
  const check::Checked b = check::check_with_frames(c, gl(), streamed);
  EXPECT_TRUE(b.streamed);
  EXPECT_GT(b.result.coverage.both, 10000u);
  for (const bool deferred : {false, true}) {
    check::CheckOptions o;
    o.deferred_allowance = deferred;
    const check::Checked a = check::check_with_frames(c, gl(), o);
    EXPECT_FALSE(a.streamed);
    EXPECT_EQ(bool(a.expected.deferred), deferred);
    test::expect_same_result(a.result, b.result);
  }
}

TEST_F(Gl, SuiteCasesAgreeWithTheReference) {
  const char* names[] = {"face_on",
                         "checkerboard_quad",
                         "fan",
                         "grid_mesh",
                         "clip_near",
                         "behind_eye_partial",
                         "flat_provoking_first",
                         "noperspective_smooth",
                         "depth_range_reversed",
                         "viewport_offset"};
  for (const char* name : names) {
    const Case c =
        casefile::load(std::string(GLRC_SOURCE_DIR) + "/cases/" + std::string(name) + ".json");
    // The fixed default model: under the specification's allowance a tie rule or grid other
    // than the driver's is within the freedom.
    const CaseResult r = check::check(c, gl(), check::CheckOptions{});
    EXPECT_EQ(r.status, Status::pass) << name << ": " << r.message;
    EXPECT_GT(r.coverage.both, 100u) << name;  // the case does draw something
    EXPECT_LE(r.coverage.boundary, r.coverage.both / 10) << name;
  }
}

TEST_F(GlEgl, MissingClientExtensionIsNamed) {
  try {
    require_client_extension(egl_library(), "EGL_GLRC_no_such_extension", "install nothing");
    FAIL() << "a nonexistent EGL extension is listed";
  } catch (const Unavailable& e) {
    EXPECT_STREQ(e.what(),
                 "EGL_GLRC_no_such_extension not supported by libEGL.so.1: install nothing");
  }
}

TEST_F(GlEgl, DeviceIndexOutOfRangeListsTheDevices) {
  Target t = target();
  t.backend = Backend::egl_device;
  t.device_index = 1000;
  try {
    create_renderer(t);
    FAIL() << "device 1000 exists";
  } catch (const Unavailable& e) {
    std::string m = e.what();
    std::cout << "[ devices  ] " << m << "\n";
    EXPECT_EQ(m.rfind("EGL device 1000 asked for, but libEGL.so.1 lists ", 0), 0u) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace glrc::gl
