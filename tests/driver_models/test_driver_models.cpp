// driver_models without GL: names, the frame layout, and driver behaviours the models must
// reproduce whatever GL is installed (the bit-for-bit comparison with GL is in tests/gl).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "casefile/casefile.hpp"
#include "core/case.hpp"
#include "core/frame.hpp"
#include "driver_models/driver_models.hpp"
#include "ref/reference.hpp"

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

// A zero-area triangle through the eye: the clipper's vertex at w_c = 0 is (0, 0, 0, 0), its
// window position NaN. llvmpipe snaps NaN to INT32_MIN, its 32-bit edge steps wrap, and the
// whole-tile rasterizer then fills every row from the line y_w = 10.5 up, twice (two fan
// triangles), with NaN values and depth 1 (min(NaN, 1) is 1): what Mesa 22.3.6 draws.
// softpipe's setup draws nothing from a NaN position.
TEST(DriverModelCoverage, LlvmpipeFillsAboveATriangleThroughTheEye) {
  const Case c = load_case("degenerate_through_eye");
  const Frame l = render(c, Driver::llvmpipe);
  for (int y = 0; y < l.height; ++y)
    for (int x = 0; x < l.width; ++x) {
      const size_t p = l.index(x, y);
      EXPECT_EQ(l.fragments[p], y >= 10 ? 2 : 0) << x << "," << y;
      if (y < 10) continue;
      EXPECT_EQ(l.primitive[p], 0) << x << "," << y;
      EXPECT_TRUE(std::isnan(l.components[0][p])) << x << "," << y;
      EXPECT_EQ(l.depth[p], 1.0f) << x << "," << y;
    }
  const Frame s = render(c, Driver::softpipe);
  for (size_t p = 0; p < s.pixel_count(); ++p)
    EXPECT_EQ(s.fragments[p], 0) << p;
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

// Mesa computes GL_UPPER_LEFT as scale[1] = -half_height (main/viewport.c) and flips
// front_ccw (st_atom_rasterizer.c); the models follow it, not the reference's y_c negation. The
// two agree bit for bit: x·(-s) rounds as -(x·s), and fma(a, -s, t) as fma(-a, s, t). So every
// suite case drawn upper-left equals its lower-left twin (y_c negated, the other front face),
// but for one thing: the twin's negated y_c swap the planes y_c <= w_c and -w_c <= y_c, and the
// clipper cuts by them in plane order, so a triangle beyond both is cut in the other order, with
// other roundings. Cases with such a triangle are left out.
TEST(DriverModelClipControl, UpperLeftIsLowerLeftWithYNegatedAndFacingReversed) {
  size_t compared = 0;
  for (const auto& path : casefile::collect({std::string(GLRC_SOURCE_DIR) + "/cases"})) {
    Case upper = casefile::load(path);
    if (upper.clip_origin == ClipOrigin::upper_left) continue;
    bool both_y_planes = false;
    for (const auto& t : upper.triangles) {
      bool above = false, below = false;
      for (uint32_t k : t) {
        const auto& p = upper.vertices[k].clip;
        above = above || !(p[1] <= p[3]);
        below = below || !(-p[3] <= p[1]);
      }
      both_y_planes = both_y_planes || (above && below);
    }
    if (both_y_planes) continue;
    ++compared;
    upper.clip_origin = ClipOrigin::upper_left;
    Case twin = upper;
    twin.clip_origin = ClipOrigin::lower_left;
    for (Vertex& v : twin.vertices)
      v.clip[1] = -v.clip[1];
    twin.front_face = twin.front_face == FrontFace::ccw ? FrontFace::cw : FrontFace::ccw;
    for (Driver d : kDrivers) {
      const Frame a = render(upper, d), b = render(twin, d);
      EXPECT_EQ(a.primitive, b.primitive) << upper.name << " " << to_string(d);
      EXPECT_EQ(std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)), 0)
          << upper.name << " " << to_string(d);
      for (size_t k = 0; k < a.components.size(); ++k)
        EXPECT_EQ(std::memcmp(a.components[k].data(), b.components[k].data(),
                              a.components[k].size() * sizeof(float)),
                  0)
            << upper.name << " " << to_string(d);
    }
  }
  EXPECT_GT(compared, 100u);
}

// The largest share of the allowance any smooth value or depth of the driver's frame uses,
// over the pixels both draw with the case's first triangle; `compared` counts them.
double worst_share(const Case& c, Driver d, long& compared) {
  const Expectation r = ref::render(c, Model{}, d == Driver::llvmpipe ? 8 : 4);
  const Frame f = render(c, d);
  double worst = 0;
  for (size_t i = 0; i < f.pixel_count(); ++i) {
    if (r.frame.primitive[i] != 0 || f.primitive[i] != 0) continue;
    ++compared;
    auto share = [&](float ref, float got, float allowed) {
      worst = std::max(worst, std::fabs(double(got) - double(ref)) / double(allowed));
    };
    share(r.frame.depth[i], f.depth[i], r.allowed.depth[i]);
    for (size_t k = 0; k < r.frame.components.size(); ++k)
      share(r.frame.components[k][i], f.components[k][i], r.allowed.components[k][i]);
  }
  return worst;
}

// Mesa's own clipper and setup, bit for bit, on random clip-heavy triangles (x, y within
// ±3·w_c, z within ±1.2·w_c, some w_c <= 0): every smooth value and depth stays within the
// specification's allowance the reference derives from the clipped polygon (ref/freedom.hpp).
TEST(DriverModelAllowance, ClippedTrianglesStayWithinTheAllowance) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (Driver d : kDrivers) {
    double worst = 0;
    long compared = 0;
    for (int attempt = 0; attempt < 150; ++attempt) {
      Case c;
      c.name = "clip";
      c.varyings = {{"c", 2, Interpolation::smooth}};
      for (int i = 0; i < 3; ++i) {
        const double w = attempt % 3 == i ? 1.5 * unit(rng) - 0.5 : 1.1 + unit(rng);
        const double s = std::max(std::fabs(w), 0.05);
        c.vertices.push_back({{float(3 * s * unit(rng)), float(3 * s * unit(rng)),
                               float(1.2 * s * unit(rng)), float(w)},
                              {float(unit(rng)), float(unit(rng))}});
      }
      c.triangles = {{0, 1, 2}};
      worst = std::max(worst, worst_share(c, d, compared));
    }
    EXPECT_GT(compared, 50000) << to_string(d);
    EXPECT_LE(worst, 1.0) << to_string(d);
  }
}

// A vertex with w_c between 1e-7 and 1e-2 (either sign): clipping leaves polygons whose fan
// has slivers (a clipped vertex next to another), and llvmpipe's float setup of a sliver's
// planes loses the cancellation of its gradients (2.3e-4 relative error in one plane of
// cases/clip_fan_sliver_tiny_w, 1.14x the allowance before the setup term). Mesa's clipper and
// setup, bit for bit, stay within the allowance on that case and on random ones.
TEST(DriverModelAllowance, TinyWFanSliversStayWithinTheAllowance) {
  const Case sliver =
      casefile::load(std::string(GLRC_SOURCE_DIR) + "/cases/clip_fan_sliver_tiny_w.json");
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (Driver d : kDrivers) {
    long compared = 0;
    double worst = worst_share(sliver, d, compared);
    EXPECT_GT(compared, 2000) << to_string(d);
    for (int attempt = 0; attempt < 150; ++attempt) {
      Case c;
      c.name = "tiny-w";
      c.fb_width = 96;
      c.viewport = {0, 0, 96, 64};
      c.varyings = {{"s", 2, Interpolation::smooth}};
      for (int i = 0; i < 3; ++i) {
        double w = 0.05 + 4 * (1 + unit(rng));
        if (attempt % 3 == i)
          w = std::pow(10.0, -4.5 + 2.5 * unit(rng)) * (unit(rng) < 0.2 ? -1 : 1);
        const double s = std::fabs(w);
        c.vertices.push_back({{float(3 * s * unit(rng)), float(3 * s * unit(rng)),
                               float(1.2 * s * unit(rng)), float(w)},
                              {float(100 * unit(rng)), float(100 * unit(rng))}});
      }
      c.triangles = {{0, 1, 2}};
      worst = std::max(worst, worst_share(c, d, compared));
    }
    EXPECT_GT(compared, 100000) << to_string(d);
    EXPECT_LE(worst, 1.0) << to_string(d);
  }
}

// Coverage at the near and far planes. Mesa clips against x and y before z, and a vertex made
// on an x or y plane has its z_c and w_c rounded to float32, so the far (or near) plane cuts the
// polygon where it cuts the rounded one: a fuzz campaign found llvmpipe covering a pixel whose
// exact z_n is 1 + 1.4e-8 (two vertices on z = w_c, the third 2^-21 beyond it). Every pixel
// Mesa's clipper (the models, bit for bit) covers differently from the exact reference lies
// within a band the reference marks (ref/freedom.hpp, PositionFreedom::z_clip_at), on that case
// and on random triangles with vertices on, near and beyond the near and far planes.
TEST(DriverModelCoverage, AtTheNearAndFarPlanesOnlyMarkedPixelsDiffer) {
  Case found;
  found.name = "fuzz-fill-rule";
  found.fb_width = found.fb_height = 1;
  found.viewport = {0, 0, 1, 1};
  found.vertices = {{{0, -32, 1.0000005f, 1}, {}}, {{1, 0, 1, 1}, {}}, {{0, 1, 1, 1}, {}}};
  found.triangles = {{0, 1, 2}};
  std::vector<Case> cases = {found};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int attempt = 0; attempt < 200; ++attempt) {
    Case c;
    c.name = "near-far";
    c.fb_width = c.fb_height = 32;
    c.viewport = {0, 0, 32, 32};
    for (int i = 0; i < 3; ++i) {
      const float w = float(1.5 + unit(rng));
      const float side = unit(rng) < 0 ? -1.0f : 1.0f;
      // On the plane, a few ulps either side of it, or anywhere in depth.
      float z = side * w;
      const double pick = unit(rng);
      if (pick > 0.3) z = float(z * (1 + std::ldexp(unit(rng), -20)));
      if (pick > 0.8) z = float(1.2 * w * unit(rng));
      c.vertices.push_back({{float(3 * w * unit(rng)), float(3 * w * unit(rng)), z, w}, {}});
    }
    c.triangles = {{0, 1, 2}};
    cases.push_back(c);
  }
  for (Driver d : kDrivers) {
    long differ = 0;
    for (const Case& c : cases) {
      const Expectation r = ref::render(c, Model{}, d == Driver::llvmpipe ? 8 : 4);
      const Frame f = render(c, d);
      for (size_t i = 0; i < f.pixel_count(); ++i)
        if (r.frame.primitive[i] != f.primitive[i]) {
          ++differ;
          EXPECT_NE(r.edges[i], 0) << to_string(d) << ": case " << c.name << " pixel " << i;
        }
    }
    // The band is not everything: the models differ from the reference somewhere at all.
    EXPECT_GT(differ, 0) << to_string(d);
  }
}

// cases/clip_distance_sliver_piece: a user clip plane cuts the second triangle 0.002 px beside
// the vertex it shares with the first, and llvmpipe's fan of the clipped polygon has a sliver
// piece that, snapped to 1/256 px, turns over and covers the shared edge's centre (9, 15) the
// first triangle covers too (found by a `distances` campaign). The reference leaves the count
// there free (PositionFreedom::turning_pieces), and only near the piece; with the plane
// moved 0.1 away from the vertex no piece may turn over, nothing is left free, and the model's
// counts differ from the reference's only in the bands.
TEST(DriverModelCoverage, AClippedPieceThatMayTurnOverIsFreeOnlyWhereItReaches) {
  const Case sliver = load_case("clip_distance_sliver_piece");
  const Frame f = render(sliver, Driver::llvmpipe);
  const size_t centre = f.index(9, 15);
  EXPECT_EQ(f.fragments[centre], 2);
  const Expectation r = ref::render(sliver, Model{}, 8);
  EXPECT_EQ(r.frame.fragments[centre], 1);
  EXPECT_TRUE(r.edges[centre] & edge::unstable);
  size_t free = 0, covered = 0;
  for (size_t i = 0; i < r.edges.size(); ++i)
    free += (r.edges[i] & edge::unstable) != 0, covered += r.frame.primitive[i] >= 0;
  EXPECT_LE(free, 4u);  // the piece is a sliver: a few centres, not the triangles'
  EXPECT_GT(covered, 50u);

  Case apart = sliver;
  for (uint32_t v : {1u, 3u})  // the plane's distances at the second triangle's own vertices
    apart.vertices[v].distances[0] -= 0.1f;
  const Expectation a = ref::render(apart, Model{}, 8);
  for (size_t i = 0; i < a.edges.size(); ++i)
    EXPECT_FALSE(a.edges[i] & edge::unstable) << "pixel " << i;
  const Frame g = render(apart, Driver::llvmpipe);
  for (size_t i = 0; i < g.pixel_count(); ++i)
    if (g.fragments[i] != a.frame.fragments[i]) {
      EXPECT_NE(a.edges[i], 0) << "pixel " << i;
    }
}

}  // namespace
}  // namespace glrc::driver_models
