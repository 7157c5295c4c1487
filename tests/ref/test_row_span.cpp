// CoverageTest::row_span and row_spans (ref/coverage.hpp): the reference walks only the pixels
// of each row a triangle can reach, so the span must never miss a pixel that covers() or
// classify() would mark, with render.cpp's reach, which is no wider than the freedom's bands
// and the snapping need. Checked against every pixel of the framebuffer for random triangles of
// every kind the cases hold: thin, large, nearly horizontal or vertical, reaching behind the eye,
// far outside the viewport, snapped and unsnapped, with freedoms from a model step to several
// pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "ref/coverage.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {
namespace {

constexpr int kSize = 40;

Case triangle(std::array<std::array<float, 4>, 3> v) {
  Case c;
  c.name = "span";
  c.fb_width = c.fb_height = kSize;
  c.viewport = {0, 0, kSize, kSize};
  for (const auto& p : v)
    c.vertices.push_back({p, {}});
  c.triangles = {{0, 1, 2}};
  return c;
}

// Every pixel the span leaves out is neither covered nor classified; returns the pixels the
// spans held, to show that they are tight.
size_t check_spans(const Case& c, const Model& m, double freedom) {
  const TriangleSetup t = setup_triangle(c, m, 0);
  if (!t.has_edges) return 0;
  const CoverageTest coverage(t, m);
  // render.cpp's reach_px: the largest band, or on the snapped path half a subpixel step (how
  // far a snapped vertex moves along x and y), times 1.5 > sqrt(2).
  const double snapping =
      t.path == CoveragePath::snapped ? std::ldexp(1.0, -(m.subpixel_bits + 1)) : 0.0;
  const double reach = std::max(freedom, snapping) * 1.5;
  const CoverageTest::RowSpans spans = coverage.row_spans(reach, 0, kSize - 1, 0, kSize - 1);
  size_t held = 0;
  for (int py = 0; py < kSize; ++py) {
    // for_each_covered steps the edge functions along the row: the very pixels covers() gives.
    std::vector<int> stepped, tested;
    coverage.for_each_covered(py, 0, kSize - 1, [&](int px) { stepped.push_back(px); });
    for (int px = 0; px < kSize; ++px) {
      if (coverage.covers(px, py)) tested.push_back(px);
      // classifies_nothing for the largest freedom holds for every smaller one.
      for (bool unstable : {false, true})
        if (coverage.classifies_nothing(px, py, freedom, unstable)) {
          for (double f : {freedom, freedom / 2, 0.0})
            EXPECT_EQ(coverage.classify(px, py, f, {true, false, true}, unstable), 0)
                << "pixel " << px << "," << py << " freedom " << f;
        }
    }
    EXPECT_EQ(stepped, tested) << "row " << py;
    // Parts of the row, narrower than the run found by dividing (stepped) and not (divided).
    for (const auto& [from, to] : {std::pair(3, 36), std::pair(5, 20), std::pair(30, 31)}) {
      std::vector<int> part, want;
      coverage.for_each_covered(py, from, to, [&](int px) { part.push_back(px); });
      for (int px : tested)
        if (px >= from && px <= to) want.push_back(px);
      EXPECT_EQ(part, want) << "row " << py << " pixels " << from << " to " << to;
    }
    const auto [x0, x1] = coverage.row_span(py, reach, 0, kSize - 1);
    // The walked spans hold at least the pixels the row's own does not leave out.
    const auto [w0, w1] = spans.at(py);
    for (int px = 0; px < kSize; ++px)
      if (coverage.covers(px, py) ||
          coverage.classify(px, py, freedom, {true, false, true}, true)) {
        EXPECT_TRUE(px >= w0 && px <= w1)
            << "pixel " << px << "," << py << " outside the walked span";
      }
    EXPECT_GE(x0, 0);
    EXPECT_LE(x1, kSize - 1);
    held += size_t(std::max(0, x1 - x0 + 1));
    for (int px = 0; px < kSize; ++px) {
      if (px >= x0 && px <= x1) continue;
      EXPECT_FALSE(t.drawn && coverage.covers(px, py))
          << "pixel " << px << "," << py << " covered outside the span [" << x0 << ", " << x1
          << "]";
      for (bool unstable : {false, true})
        EXPECT_EQ(coverage.classify(px, py, freedom, {true, false, true}, unstable), 0)
            << "pixel " << px << "," << py << " classified outside the span [" << x0 << ", " << x1
            << "]";
    }
  }
  return held;
}

TEST(RowSpan, NeverMissesAPixelOfRandomTriangles) {
  std::mt19937 rng(1301);
  std::uniform_real_distribution<float> unit(-1.2f, 1.2f), far(-40.0f, 40.0f), w(0.2f, 4.0f);
  std::uniform_real_distribution<double> freedom(0.0, 3.0);
  for (int k = 0; k < 600; ++k) {
    std::array<std::array<float, 4>, 3> v{};
    for (auto& p : v) {
      const float pw = k % 7 == 0 ? -w(rng) : w(rng);  // some reach behind the eye
      const bool outside = k % 5 == 0;
      p = {(outside ? far(rng) : unit(rng)) * pw, (outside ? far(rng) : unit(rng)) * pw, 0, pw};
    }
    if (k % 3 == 0) v[1][1] = v[0][1] * v[1][3] / v[0][3] + 1e-4f;  // nearly horizontal edge
    if (k % 4 == 0) v[2][0] = v[0][0] * v[2][3] / v[0][3] - 1e-4f;  // nearly vertical edge
    Model m;
    m.subpixel_bits = k % 2 ? 8 : 0;
    m.planes = k % 3 ? Planes::unsnapped : Planes::snapped;
    SCOPED_TRACE("triangle " + std::to_string(k));
    check_spans(triangle(v), m, k % 4 == 1 ? std::ldexp(1.0, -8) : freedom(rng));
  }
}

TEST(RowSpan, HugeCoordinatesTakeEveryPixel) {
  // Edge forms far beyond 2^40 pixels: distance() may be off by more than a quarter pixel, so
  // the span gives up and every pixel is tested, as before.
  const Case c = triangle({{{-3e30f, -1, 0, 1}, {3e30f, -1, 0, 1}, {0, 1e30f, 0, 1}}});
  check_spans(c, Model{}, 0.5);
}

TEST(RowSpan, AThinTriangleIsWalkedAlongItsLengthOnly) {
  // A sliver from corner to corner: its bounding box is the whole framebuffer (1,600 pixels),
  // its spans one or two pixels per row (its width, under half a pixel, the reach, 1.5/256
  // pixel, and the rounding of the spans, a few ulps: none a whole pixel).
  const Case c = triangle({{{-1, -1, 0, 1}, {1, 1, 0, 1}, {1, 0.98f, 0, 1}}});
  const size_t held = check_spans(c, Model{}, std::ldexp(1.0, -8));
  EXPECT_GE(held, size_t(kSize));
  EXPECT_LT(held, size_t(2 * kSize));
}

}  // namespace
}  // namespace glrc::ref
