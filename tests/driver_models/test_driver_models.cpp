// driver_models without GL: names, the frame layout, and driver behaviours the models must
// reproduce whatever GL is installed (the bit-for-bit comparison with GL is in tests/gl).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "casefile/casefile.hpp"
#include "core/case.hpp"
#include "core/frame.hpp"
#include "driver_models/driver_models.hpp"

namespace glrc::driver_models {
namespace {

constexpr Driver kDrivers[] = {Driver::llvmpipe, Driver::softpipe};

Case load_case(const std::string& name) {
  return casefile::load(std::string(GLRC_SOURCE_DIR) + "/cases/" + name + ".json");
}

// Two triangles covering an 8x8 viewport, split along the diagonal through pixel centres.
Case quad_case() {
  Case c;
  c.name = "quad";
  c.fb_width = c.fb_height = 8;
  c.viewport = {0, 0, 8, 8};
  c.varyings = {Varying{"v", 1, Interpolation::smooth}};
  for (auto [x, y] : {std::pair{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}})
    c.vertices.push_back(Vertex{{x, y, 0.0f, 1.0f}, {x + y}});
  c.triangles = {{0, 1, 2}, {0, 2, 3}};
  return c;
}

TEST(DriverModelNames, RoundTrip) {
  for (Driver d : kDrivers)
    EXPECT_EQ(driver_from_string(to_string(d)), d);
  EXPECT_STREQ(to_string(Driver::softpipe), "softpipe");
  EXPECT_EQ(driver_from_string("swrast"), std::nullopt);
}

TEST(DriverModelFrame, UncoveredPixelsKeepTheClearValues) {
  Case c = quad_case();
  c.viewport = {0, 0, 4, 8};  // left half only
  for (Driver d : kDrivers) {
    const Frame f = render(c, d);
    ASSERT_EQ(f.width, 8);
    ASSERT_EQ(f.components.size(), 1u);
    for (int y = 0; y < 8; ++y)
      for (int x = 4; x < 8; ++x) {
        const size_t p = f.index(x, y);
        EXPECT_EQ(f.primitive[p], Frame::kNoPrimitive) << to_string(d);
        EXPECT_EQ(f.depth[p], 1.0f);
        EXPECT_EQ(f.components[0][p], 0.0f);
        EXPECT_EQ(f.fragments[p], 0);
      }
  }
}

// Centres on the shared diagonal belong to exactly one triangle, and every pixel gets exactly
// one fragment, on both drivers.
TEST(DriverModelCoverage, SharedDiagonalIsWatertight) {
  for (Driver d : kDrivers) {
    const Frame f = render(quad_case(), d);
    for (size_t p = 0; p < f.pixel_count(); ++p) {
      EXPECT_NE(f.primitive[p], Frame::kNoPrimitive) << to_string(d) << " pixel " << p;
      EXPECT_EQ(f.fragments[p], 1) << to_string(d) << " pixel " << p;
    }
  }
}

// Mesa's clipper recomputes noperspective's t from NDC x; when the cut edge lies on x = w at
// both ends it divides 0 by 0. Both drivers share the clipper, so both give NaN there, and
// smooth varyings stay finite.
TEST(DriverModelClipper, NoperspectiveOnTheXPlaneIsNaN) {
  const Case c = load_case("clip_noperspective_x_plane");
  for (Driver d : kDrivers) {
    const Frame f = render(c, d);
    int nan = 0, covered = 0;
    for (size_t p = 0; p < f.pixel_count(); ++p) {
      if (f.primitive[p] == Frame::kNoPrimitive) continue;
      ++covered;
      bool any = false;
      for (const auto& component : f.components)
        any = any || std::isnan(component[p]);
      nan += any;
    }
    EXPECT_GT(covered, 0) << to_string(d);
    EXPECT_GT(nan, 0) << to_string(d);
  }
}

// llvmpipe evaluates planes with fused multiply-adds where the CPU has FMA, softpipe never:
// the option changes llvmpipe's bits and leaves softpipe's alone.
TEST(DriverModelOptions, FmaMattersOnlyToLlvmpipe) {
  const Case c = load_case("checkerboard_quad");
  auto differs = [&c](Driver d) {
    const Frame a = render(c, d, Options{true}), b = render(c, d, Options{false});
    return a.components != b.components || a.depth != b.depth;
  };
  EXPECT_TRUE(differs(Driver::llvmpipe));
  EXPECT_FALSE(differs(Driver::softpipe));
}

// The model's bits do not depend on how often or in which order it runs.
TEST(DriverModelDeterminism, SameCaseSameBits) {
  for (const auto& path : casefile::collect({std::string(GLRC_SOURCE_DIR) + "/cases"})) {
    const Case c = casefile::load(path);
    for (Driver d : kDrivers) {
      const Frame a = render(c, d), b = render(c, d);
      EXPECT_EQ(a.primitive, b.primitive) << c.name;
      EXPECT_EQ(std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)), 0)
          << c.name;
      for (size_t k = 0; k < a.components.size(); ++k)
        EXPECT_EQ(std::memcmp(a.components[k].data(), b.components[k].data(),
                              a.components[k].size() * sizeof(float)),
                  0)
            << c.name;
    }
  }
}

}  // namespace
}  // namespace glrc::driver_models
