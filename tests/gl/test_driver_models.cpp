// driver_models against the real driver: every suite case and a few hundred random, clip- and
// tie-heavy triangles, rendered on GL and by the model of the running driver, must agree in
// every bit (primitive id, depth, every component, fragment counts; NaN only where GL has NaN).
// Same environment as test_gl_harness.cpp: GLRC_TEST_BACKEND and GLRC_TEST_DRIVER.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>

#include "casefile/casefile.hpp"
#include "core/case.hpp"
#include "core/frame.hpp"
#include "driver_models/driver_models.hpp"
#include "gl_harness/gl_harness.hpp"
#include "tests/support/gl_test_target.hpp"

namespace glrc {
namespace {

struct ModelShared {
  std::string unavailable;
  gl::Target target;
  std::optional<driver_models::Driver> driver;
  std::unique_ptr<gl::Renderer> renderer;
  bool tried = false;
};

ModelShared& model_shared() {
  static ModelShared s;
  if (s.tried) return s;
  s.tried = true;
  s.target = test::gl_test_target(s.unavailable);
  s.driver = driver_models::driver_from_string(s.target.driver);
  if (!s.driver || !s.unavailable.empty()) return s;
  try {
    s.renderer = gl::create_renderer(s.target);
  } catch (const gl::Unavailable& e) {
    s.unavailable = e.what();
  }
  return s;
}

// Destroyed before main() returns, while Mesa and LLVM are still alive.
class ModelRendererEnvironment : public ::testing::Environment {
 public:
  void TearDown() override { model_shared().renderer.reset(); }
};
[[maybe_unused]] auto* const model_environment =
    ::testing::AddGlobalTestEnvironment(new ModelRendererEnvironment);

class DriverModel : public ::testing::Test {
 protected:
  void SetUp() override {
    ModelShared& s = model_shared();
    if (!s.driver) GTEST_SKIP() << "no model of driver '" << s.target.driver << "'";
    if (s.renderer) return;
    if (s.target.backend == gl::Backend::egl_device)
      GTEST_SKIP() << "egl-device unavailable: " << s.unavailable;
    FAIL() << "no " << gl::to_string(s.target.backend) << " renderer: " << s.unavailable;
  }
  gl::Renderer& gl() { return *model_shared().renderer; }
  driver_models::Driver driver() { return *model_shared().driver; }
};

bool same_bits(float a, float b) {
  return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b) ||
         (std::isnan(a) && std::isnan(b));
}

// Every differing pixel, counted per channel; the first few described.
struct Difference {
  uint64_t pixels = 0, primitive = 0, depth = 0, components = 0, fragments = 0, nan_pixels = 0;
  std::string first;
  std::string summary() const {
    std::ostringstream s;
    s << pixels << " px differ (primitive " << primitive << ", depth " << depth << ", components "
      << components << ", fragment counts " << fragments << ")" << first;
    return s.str();
  }
};

Difference difference(const Case& c, const Frame& gl_frame, const Frame& model) {
  Difference d;
  const bool counts = !gl_frame.fragments.empty();
  for (int y = 0; y < gl_frame.height; ++y)
    for (int x = 0; x < gl_frame.width; ++x) {
      const size_t p = gl_frame.index(x, y);
      std::ostringstream what;
      if (gl_frame.primitive[p] != model.primitive[p]) {
        ++d.primitive;
        what << " primitive " << gl_frame.primitive[p] << " vs " << model.primitive[p];
      }
      if (!same_bits(gl_frame.depth[p], model.depth[p])) {
        ++d.depth;
        what << " depth " << gl_frame.depth[p] << " vs " << model.depth[p];
      }
      bool nan = false;
      for (size_t k = 0; k < gl_frame.components.size(); ++k) {
        nan = nan || std::isnan(gl_frame.components[k][p]);
        if (!same_bits(gl_frame.components[k][p], model.components[k][p])) {
          ++d.components;
          what << " c" << k << " " << gl_frame.components[k][p] << " vs " << model.components[k][p];
        }
      }
      d.nan_pixels += nan;
      if (counts && gl_frame.fragments[p] != model.fragments[p]) {
        ++d.fragments;
        what << " fragments " << gl_frame.fragments[p] << " vs " << model.fragments[p];
      }
      if (!what.str().empty()) {
        if (++d.pixels <= 5)
          d.first += "\n  " + c.name + " (" + std::to_string(x) + "," + std::to_string(y) +
                     "): GL vs model" + what.str();
      }
    }
  return d;
}

// Pixels compared bit for bit over several cases.
struct Tally {
  uint64_t pixels = 0, covered = 0, nan = 0;
};

// Renders c on GL and with the model; every bit must agree.
void expect_bit_exact(const Case& c, gl::Renderer& renderer, driver_models::Driver driver,
                      Tally& tally) {
  const Frame g = renderer.render(c);
  const Frame m = driver_models::render(c, driver);
  const Difference d = difference(c, g, m);
  EXPECT_EQ(d.pixels, 0u) << c.name << ": " << d.summary();
  tally.pixels += g.pixel_count();
  for (int32_t p : g.primitive)
    tally.covered += p != Frame::kNoPrimitive;
  tally.nan += d.nan_pixels;
}

TEST_F(DriverModel, EverySuiteCaseIsBitExact) {
  Tally tally;
  int cases = 0;
  int skipped = 0;
  for (const auto& path : casefile::collect({std::string(GLRC_SOURCE_DIR) + "/cases"})) {
    const Case c = casefile::load(path);
    try {
      expect_bit_exact(c, gl(), driver(), tally);
    } catch (const gl::FeatureMissing&) {  // softpipe: glPolygonOffsetClamp (run skips it too)
      ++skipped;
      continue;
    }
    ++cases;
  }
  EXPECT_LE(skipped, 2);
  const uint64_t pixels = tally.pixels, covered = tally.covered, nan = tally.nan;
  std::cout << "[ driver_models ] " << driver_models::to_string(driver()) << ": " << cases
            << " suite cases, " << pixels << " pixels (" << covered << " covered, " << nan
            << " with NaN) compared bit for bit\n";
}

// llvmpipe fuses its multiply-adds exactly where the CPU has FMA (Options' default): the
// model with the other choice must disagree with GL somewhere in the suite, or the choice
// would not need detecting.
TEST_F(DriverModel, LlvmpipeFmaChoiceIsTheCpus) {
  if (driver() != driver_models::Driver::llvmpipe) GTEST_SKIP() << "softpipe never fuses";
  driver_models::Options other;
  other.fma = !driver_models::Options{}.fma;
  uint64_t differing = 0;
  for (const auto& path : casefile::collect({std::string(GLRC_SOURCE_DIR) + "/cases"})) {
    const Case c = casefile::load(path);
    differing += difference(c, gl().render(c), driver_models::render(c, driver(), other)).pixels;
  }
  std::cout << "[ driver_models ] llvmpipe with fma=" << other.fma << " instead of " << !other.fma
            << ": " << differing << " pixels differ\n";
  EXPECT_GT(differing, 0u);
}

// Random cases built to hit the drivers' corner cases: vertices behind the eye and far
// outside the view volume (clipping on every plane, noperspective NaN), window positions on
// pixel centres and half pixels (ties), slivers, viewports off the origin and past the
// framebuffer, reversed depth ranges, every cull mode, both provoking vertices.
Case random_case(std::mt19937& rng, int index, int triangles) {
  auto uniform = [&rng](float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
  };
  auto pick = [&rng](int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); };
  Case c;
  c.name = "random_" + std::to_string(index);
  const int sizes[][2] = {{64, 64}, {37, 23}, {96, 40}, {17, 61}};
  const auto& size = sizes[pick(4)];
  c.fb_width = size[0];
  c.fb_height = size[1];
  c.viewport = {pick(3) == 0 ? 0 : pick(21) - 10, pick(3) == 0 ? 0 : pick(21) - 10,
                c.fb_width + pick(25) - 8, c.fb_height + pick(25) - 8};
  const float ranges[][2] = {{0, 1}, {1, 0}, {0.25f, 0.75f}, {0.9f, 0.1f}};
  const auto& range = ranges[pick(4)];
  c.depth_near = range[0];
  c.depth_far = range[1];
  c.cull = CullFace(pick(4) == 0 ? 1 + pick(3) : 0);
  c.front_face = FrontFace(pick(2));
  c.provoking = ProvokingVertex(pick(2));
  c.depth_func = DepthFunc(pick(2));
  const Interpolation kinds[] = {Interpolation::smooth, Interpolation::noperspective,
                                 Interpolation::flat};
  const int varyings = 1 + pick(3);
  for (int k = 0; k < varyings; ++k)
    c.varyings.push_back(Varying{"v" + std::to_string(k), 1 + pick(4), kinds[pick(3)]});

  for (int t = 0; t < triangles * 3; ++t) {
    Vertex v;
    const int style = pick(4);
    float w = style == 3 ? uniform(-1.5f, 2.5f) : uniform(0.5f, 3.0f);
    if (pick(8) == 0) w = 1.0f;
    float xn, yn;
    if (style == 0) {
      // Window positions on half-pixel steps of the viewport: pixel centres and corners.
      xn = (2.0f * float(pick(2 * c.viewport.width + 1)) / 2.0f) / float(c.viewport.width) - 1.0f;
      yn = (2.0f * float(pick(2 * c.viewport.height + 1)) / 2.0f) / float(c.viewport.height) - 1.0f;
    } else if (style == 1) {
      xn = uniform(-1.0f, 1.0f);
      yn = uniform(-1.0f, 1.0f);
    } else {
      // Far outside: several clip planes at once; exactly on x = ±w sometimes.
      xn = pick(5) == 0 ? float(2 * pick(2) - 1) : uniform(-3.0f, 3.0f);
      yn = uniform(-3.0f, 3.0f);
    }
    const float zn = uniform(-1.4f, 1.4f);
    v.clip = {xn * w, yn * w, zn * w, w};
    for (const Varying& var : c.varyings)
      for (int i = 0; i < var.size; ++i)
        v.values.push_back(pick(4) == 0 ? uniform(-1000.0f, 1000.0f) : uniform(-2.0f, 2.0f));
    c.vertices.push_back(v);
  }
  for (int t = 0; t < triangles; ++t) {
    const uint32_t b = uint32_t(3 * t);
    // Now and then share vertices with the previous triangle: shared edges, fans.
    if (t > 0 && pick(3) == 0)
      c.triangles.push_back({b - 3, b - 1, b + 2});
    else
      c.triangles.push_back({b, b + 1, b + 2});
  }
  return c;
}

TEST_F(DriverModel, RandomClipAndTieHeavyTrianglesAreBitExact) {
  std::mt19937 rng(20240613u);
  Tally tally;
  uint64_t triangles = 0;
  for (int i = 0; i < 48; ++i) {
    // The last few are long draws: Mesa's draw module cuts them into segments of 341
    // triangles, and only a segment with a clipped vertex runs the clip and cull stages.
    const Case c = random_case(rng, i, i < 44 ? 8 : 400);
    expect_bit_exact(c, gl(), driver(), tally);
    triangles += c.triangles.size();
  }
  const uint64_t pixels = tally.pixels, covered = tally.covered, nan = tally.nan;
  std::cout << "[ driver_models ] " << driver_models::to_string(driver()) << ": " << triangles
            << " random triangles, " << pixels << " pixels (" << covered << " covered, " << nan
            << " with NaN) compared bit for bit\n";
}

}  // namespace
}  // namespace glrc
