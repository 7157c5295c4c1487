// CoverageTest::row_span, row_spans and covered_rows (ref/coverage.hpp): the reference walks only
// the pixels of each row a triangle can reach, so the span must never miss a pixel that covers() or
// classify() would mark, with render.cpp's reach, which is no wider than the freedom's bands
// and the snapping need. Checked against every pixel of the framebuffer for random triangles of
// every kind the cases hold: thin, large, nearly horizontal or vertical, reaching behind the eye,
// far outside the viewport, snapped and unsnapped, with freedoms from a model step to several
// pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
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
// spans held, to show that they are tight. Counts the triangles CoveredRows walks in `walked`,
// and the edges its walks leave out (passed by every pixel walked) in `left_out`.
size_t check_spans(const Case& c, const Model& m, double freedom, size_t& walked,
                   size_t* left_out = nullptr) {
  const TriangleSetup t = setup_triangle(c, m, 0);
  if (!t.has_edges) return 0;
  const CoverageTest coverage(t, m);
  // render.cpp's reach_px: the largest band, or on the snapped path half a subpixel step (how
  // far a snapped vertex moves along x and y), times 1.5 > sqrt(2).
  const double snapping =
      t.path == CoveragePath::snapped ? std::ldexp(1.0, -(m.subpixel_bits + 1)) : 0.0;
  const double reach = std::max(freedom, snapping) * 1.5;
  const CoverageTest::RowSpans spans = coverage.row_spans(reach, 0, kSize - 1, 0, kSize - 1);
  // CoveredRows walks the rows: over the whole framebuffer, and over part of it (from a row
  // other than 0, between columns 5 and 30).
  std::optional<CoverageTest::CoveredRows> walk = coverage.covered_rows(0, kSize - 1, 0, kSize - 1);
  std::optional<CoverageTest::CoveredRows> part_walk = coverage.covered_rows(7, kSize - 1, 5, 30);
  EXPECT_EQ(walk.has_value(), t.path == CoveragePath::snapped && !clip_planes(t).any());
  walked += walk.has_value();
  if (left_out && walk) *left_out += size_t(3 - walk->edges()) + size_t(3 - part_walk->edges());
  // for_each_row gives the runs next() gives, row after row.
  std::vector<std::pair<int, int>> runs;
  if (auto all = coverage.covered_rows(0, kSize - 1, 0, kSize - 1)) {
    all->for_each_row(kSize / 2, [&](int lo, int hi) { runs.emplace_back(lo, hi); });
    all->for_each_row(kSize - kSize / 2, [&](int lo, int hi) { runs.emplace_back(lo, hi); });
  }
  // covered_columns walks the columns: each column's covered pixels, one run of them, over the
  // whole framebuffer and over part of it; columns_of_rows holds every column a range of rows
  // covers, within the box.
  if (walk) {
    std::vector<std::pair<int, int>> column_runs;
    auto columns = coverage.covered_columns(0, kSize - 1, 0, kSize - 1);
    auto part_columns = coverage.covered_columns(5, 30, 7, kSize - 1);
    EXPECT_TRUE(columns && part_columns);
    if (columns && part_columns) {
      columns->for_each_row(kSize, [&](int lo, int hi) { column_runs.emplace_back(lo, hi); });
      for (int px = 0; px < kSize; ++px) {
        std::vector<int> in;
        for (int py = 0; py < kSize; ++py)
          if (coverage.covers(px, py)) in.push_back(py);
        const auto whole = in.empty() ? std::pair(0, -1) : std::pair(in.front(), in.back());
        EXPECT_EQ(column_runs[size_t(px)], whole) << "column " << px;
        if (!in.empty()) {
          EXPECT_EQ(size_t(in.back() - in.front() + 1), in.size());
        }
        if (px < 5 || px > 30) continue;
        std::vector<int> part;
        for (int py : in)
          if (py >= 7) part.push_back(py);
        EXPECT_EQ(part_columns->next(),
                  part.empty() ? std::pair(7, 6) : std::pair(part.front(), part.back()))
            << "column " << px;
      }
    }
    for (const auto& [y0, y1] :
         {std::pair(0, kSize - 1), std::pair(3, 9), std::pair(20, 20), std::pair(17, 38)}) {
      const auto [first, last] = coverage.columns_of_rows(y0, y1);
      int lo = kSize, hi = -1;
      for (int py = y0; py <= y1; ++py)
        for (int px = 0; px < kSize; ++px)
          if (coverage.covers(px, py)) lo = std::min(lo, px), hi = std::max(hi, px);
      if (hi < 0) continue;
      EXPECT_LE(first, lo) << "rows " << y0 << " to " << y1;
      EXPECT_GE(last, hi) << "rows " << y0 << " to " << y1;
      EXPECT_GE(first, t.box.x0);
      EXPECT_LE(last, t.box.x1);
    }
  }
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
    // A walked row's run: the covered pixels, one run of them (a convex triangle's row).
    auto run_of = [&](int from, int to) {
      std::vector<int> in;
      for (int px : tested)
        if (px >= from && px <= to) in.push_back(px);
      return in.empty() ? std::pair(from, from - 1) : std::pair(in.front(), in.back());
    };
    if (walk) {
      EXPECT_EQ(walk->next(), run_of(0, kSize - 1)) << "row " << py;
      EXPECT_EQ(runs.at(size_t(py)), run_of(0, kSize - 1)) << "row " << py;
      if (!tested.empty()) {
        EXPECT_EQ(size_t(tested.back() - tested.front() + 1), tested.size());
      }
    }
    if (part_walk && py >= 7) {
      EXPECT_EQ(part_walk->next(), run_of(5, 30)) << "row " << py;
    }
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
  size_t walked = 0, left_out = 0;
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
    check_spans(triangle(v), m, k % 4 == 1 ? std::ldexp(1.0, -8) : freedom(rng), walked, &left_out);
  }
  EXPECT_GT(walked, 150u);  // the snapped ones not reaching behind the eye
  // Many reach past the framebuffer, or past the part walked: edges every pixel there passes.
  EXPECT_GT(left_out, 100u);
}

TEST(RowSpan, AWalkStepsOnlyTheEdgesThatBind) {
  size_t walked = 0;
  // A fan's triangle: its rim far outside the framebuffer, two edges from the centre.
  const Case fan = triangle({{{0.1f, 0.2f, 0, 1}, {30, 2, 0, 1}, {30, 3, 0, 1}}});
  // A triangle enclosing the framebuffer: no edge binds, every row is covered whole.
  const Case enclosing = triangle({{{-5, -5, 0, 1}, {5, -5, 0, 1}, {0, 5, 0, 1}}});
  for (const auto& [c, edges] : {std::pair(&fan, 2), std::pair(&enclosing, 0)}) {
    const TriangleSetup t = setup_triangle(*c, Model{}, 0);
    const CoverageTest coverage(t, Model{});
    auto walk = coverage.covered_rows(0, kSize - 1, 0, kSize - 1);
    ASSERT_TRUE(walk);
    EXPECT_EQ(walk->edges(), edges);
    check_spans(*c, Model{}, std::ldexp(1.0, -8), walked);
  }
  auto walk = CoverageTest(setup_triangle(enclosing, Model{}, 0), Model{})
                  .covered_rows(0, kSize - 1, 0, kSize - 1);
  ASSERT_TRUE(walk);
  walk->for_each_row(kSize, [](int lo, int hi) {
    EXPECT_EQ(lo, 0);
    EXPECT_EQ(hi, kSize - 1);
  });
  EXPECT_EQ(walked, 2u);
}

TEST(RowSpan, RowsWalkedThroughExactTies) {
  // Vertices on pixel centres and edges of small integer slopes: many centres lie exactly on an
  // edge, where the tie rule decides (a remainder of exactly 0 when a row is walked), under
  // every rule, for both facings.
  auto at = [](double x, double y) {  // window (x, y) to clip coordinates of the 40x40 viewport
    return std::array<float, 4>{float(x / 20 - 1), float(y / 20 - 1), 0, 1};
  };
  const std::array<std::array<double, 2>, 3> shapes[] = {
      {{{0.5, 0.5}, {30.5, 10.5}, {5.5, 35.5}}},
      {{{2.5, 3.5}, {38.5, 3.5}, {20.5, 39.5}}},
      {{{1.5, 1.5}, {1.5, 37.5}, {37.5, 19.5}}},
      {{{10.5, 0.5}, {13.5, 39.5}, {11.5, 39.5}}}};
  size_t walked = 0;
  for (const auto& shape : shapes)
    for (bool reversed : {false, true})
      for (TieBreak rule : {TieBreak::top_left, TieBreak::bottom_left, TieBreak::top_right,
                            TieBreak::bottom_right}) {
        Model m;
        m.tie_break = rule;
        std::array<std::array<float, 4>, 3> v = {at(shape[0][0], shape[0][1]),
                                                 at(shape[1][0], shape[1][1]),
                                                 at(shape[2][0], shape[2][1])};
        if (reversed) std::swap(v[1], v[2]);
        check_spans(triangle(v), m, std::ldexp(1.0, -8), walked);
      }
  EXPECT_EQ(walked, 32u);
}

TEST(RowSpan, HugeCoordinatesTakeEveryPixel) {
  // Edge forms far beyond 2^40 pixels: distance() may be off by more than a quarter pixel, so
  // the span gives up and every pixel is tested, as before.
  const Case c = triangle({{{-3e30f, -1, 0, 1}, {3e30f, -1, 0, 1}, {0, 1e30f, 0, 1}}});
  size_t walked = 0;
  check_spans(c, Model{}, 0.5, walked);
}

TEST(RowSpan, AThinTriangleIsWalkedAlongItsLengthOnly) {
  // A sliver from corner to corner: its bounding box is the whole framebuffer (1,600 pixels),
  // its spans one or two pixels per row (its width, under half a pixel, the reach, 1.5/256
  // pixel, and the rounding of the spans, a few ulps: none a whole pixel).
  const Case c = triangle({{{-1, -1, 0, 1}, {1, 1, 0, 1}, {1, 0.98f, 0, 1}}});
  size_t walked = 0;
  const size_t held = check_spans(c, Model{}, std::ldexp(1.0, -8), walked);
  EXPECT_EQ(walked, 1u);
  EXPECT_GE(held, size_t(kSize));
  EXPECT_LT(held, size_t(2 * kSize));
  // Its part in rows 10 to 14 lies in x 10.5 to about 14.6: the columns a pixel wider each side,
  // not its box's 40.
  const TriangleSetup t = setup_triangle(c, Model{}, 0);
  const auto [first, last] = CoverageTest(t, Model{}).columns_of_rows(10, 14);
  EXPECT_EQ(first, 9);
  EXPECT_EQ(last, 15);
}

}  // namespace
}  // namespace glrc::ref
