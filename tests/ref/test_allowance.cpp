// The specification-derived allowance, checked the way its derivation says it holds: render the
// same triangles with every vertex moved to the extremes of the position freedom, exactly, and
// every value that moves must stay within the allowance of the unmoved reference.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>

#include "ref/allowance.hpp"
#include "ref/deferred.hpp"
#include "ref/depth.hpp"
#include "ref/interpolation.hpp"
#include "ref/mesh.hpp"
#include "ref/reference.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {
namespace {

Case base_case(int size) {
  Case c;
  c.name = "allowance";
  c.fb_width = c.fb_height = size;
  c.viewport = {0, 0, size, size};
  c.varyings = {{"s", 2, Interpolation::smooth}, {"n", 1, Interpolation::noperspective}};
  return c;
}

// Moves vertex `v` of the case by (dx, dy) window pixels: x_c += dx·w_c·2/width, rounded to
// float (an error of ~1e-6 pixel, far below the moves).
void move(Case& c, size_t v, double dx, double dy) {
  auto& clip = c.vertices[v].clip;
  clip[0] = float(double(clip[0]) + dx * double(clip[3]) * 2.0 / c.viewport.width);
  clip[1] = float(double(clip[1]) + dy * double(clip[3]) * 2.0 / c.viewport.height);
}

// For all 4^n corner moves of +-0.9·2^-bits of the first n vertices (n = 3: every one), the
// largest |moved - reference| / allowed over pixels both cover with the same triangle, over
// every channel.
double worst_share_of_allowance(const Case& c, int bits, size_t n = 3) {
  const Expectation r = render(c, Model{}, bits);
  const double d = 0.9 * std::ldexp(1.0, -bits);
  double worst = 0;
  for (int corners = 0; corners < (1 << (2 * n)); ++corners) {
    Case moved = c;
    for (size_t v = 0; v < n; ++v) {
      const int k = (corners >> (2 * v)) & 3;
      move(moved, v, k & 1 ? d : -d, k & 2 ? d : -d);
    }
    const Expectation m = render(moved, Model{});
    for (size_t i = 0; i < r.frame.pixel_count(); ++i) {
      if (r.frame.primitive[i] < 0 || m.frame.primitive[i] != r.frame.primitive[i]) continue;
      auto share = [&](float ref, float got, float allowed) {
        worst = std::max(worst, std::fabs(double(got) - double(ref)) / double(allowed));
      };
      share(r.frame.depth[i], m.frame.depth[i], r.allowed.depth[i]);
      for (size_t k = 0; k < r.frame.components.size(); ++k)
        share(r.frame.components[k][i], m.frame.components[k][i], r.allowed.components[k][i]);
    }
  }
  return worst;
}

TEST(Allowance, BoundsEveryExtremeVertexMoveOfAPerspectiveTriangle) {
  Case c = base_case(32);
  // w from 1 to 6: strongly perspective, values of several magnitudes.
  c.vertices = {{{-0.9f, -0.8f, 0.1f, 1.0f}, {0.0f, 10.0f, -3.0f}},
                {{5.1f, -4.5f, 2.0f, 6.0f}, {1.0f, -10.0f, 5.0f}},
                {{-1.2f, 2.7f, -0.7f, 3.0f}, {0.5f, 1000.0f, 0.25f}}};
  c.triangles = {{0, 1, 2}};
  for (int bits : {4, 6, 8}) {
    const double worst = worst_share_of_allowance(c, bits);
    EXPECT_LE(worst, 1.0) << bits << " bits";
    // Not vacuous: the moves use a good part of the allowance.
    EXPECT_GE(worst, 0.3) << bits << " bits";
  }
}

TEST(Allowance, BoundsEveryExtremeVertexMoveOfASliver) {
  Case c = base_case(48);
  // 40 pixels long, about 1.5 pixels wide: the first-order bound is under the most strain.
  c.vertices = {{{-0.9f, -0.9f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f}},
                {{1.6f, 1.5f, 0.5f, 2.0f}, {1.0f, 1.0f, 1.0f}},
                {{-0.9f, -0.84f, 0.0f, 1.0f}, {0.0f, 1.0f, 2.0f}}};
  c.triangles = {{0, 1, 2}};
  for (int bits : {4, 8})
    EXPECT_LE(worst_share_of_allowance(c, bits), 1.0) << bits << " bits";
}

// Found by glrefcheck fuzz on an NVIDIA GPU (seed 4242, case 8111 of --generator clip, shrunk):
// the third vertex is just behind the eye, so the polygon drawn has vertices at w_c near 0 and
// D changes fast across a pixel. Snapping the second vertex by 0.00165 px moved the value at
// pixel (7, 7) from 0.0037 to 0.0185, five times the first-order bound; the GPU's value was
// that one. Every move of the two vertices in front of the eye must stay within the allowance
// (the third one's window position is not defined: clipping makes the polygon's).
TEST(Allowance, BoundsVertexMovesWhereTheDenominatorChangesFast) {
  Case c = base_case(16);
  c.fb_height = c.viewport.height = 23;
  c.varyings = {{"v0", 1, Interpolation::smooth}};
  c.vertices = {{{-32.0f, -0.15625f, 0.0f, 1.0f}, {0.0f}},
                {{0.0f, -0.34802246f, 0.0f, 1.0f}, {1.0f}},
                {{0.0f, 0.0f, 0.0f, -0x1p-19f}, {0.0f}}};
  c.triangles = {{0, 1, 2}};
  // The fuzz case itself: the second vertex moved by 0.00165 px down, at pixel (7, 7).
  const Expectation r = render(c, Model{}, 8);
  const size_t i = r.frame.index(7, 7);
  ASSERT_EQ(r.frame.primitive[i], 0);
  Case snapped = c;
  move(snapped, 1, 0.0, -0.00165);
  const Expectation s = render(snapped, Model{});
  ASSERT_EQ(s.frame.primitive[i], 0);
  const double moved_by = std::fabs(double(s.frame.components[0][i]) - r.frame.components[0][i]);
  EXPECT_GT(moved_by, 0.01);  // the value is that sensitive here
  EXPECT_LE(moved_by, double(r.allowed.components[0][i]));
  EXPECT_LE(worst_share_of_allowance(c, 8, 2), 1.0);
  // Each of those two vertices moved alone, in x or in y, by parts of the freedom 1/20 apart:
  // every pixel both cover. The value changes so fast that the moves the fuzz case found are
  // between 0.3 and 0.6 of it.
  double worst = 0;
  for (size_t v : {0, 1})
    for (int twentieths = -18; twentieths <= 18; ++twentieths)
      for (bool in_y : {false, true}) {
        Case moved = c;
        const double d = twentieths / 20.0 * 0x1p-8;
        move(moved, v, in_y ? 0.0 : d, in_y ? d : 0.0);
        const Expectation m = render(moved, Model{});
        for (size_t p = 0; p < r.frame.pixel_count(); ++p)
          if (r.frame.primitive[p] == 0 && m.frame.primitive[p] == 0)
            worst = std::max(worst, std::fabs(double(m.frame.components[0][p]) -
                                              double(r.frame.components[0][p])) /
                                        double(r.allowed.components[0][p]));
      }
  EXPECT_LE(worst, 1.0);
  EXPECT_GE(worst, 0.5);  // not vacuous: the allowance is about what the moves need
}

TEST(Allowance, FlatIsExactAndDepthIsPositive) {
  Case c = base_case(16);
  c.varyings = {{"f", 1, Interpolation::flat}};
  c.vertices = {{{-1, -1, 0, 1}, {1}}, {{1, -1, 0.5f, 1}, {2}}, {{-1, 1, -0.5f, 1}, {3}}};
  c.triangles = {{0, 1, 2}};
  const Expectation r = render(c, Model{}, 8);
  const size_t i = r.frame.index(2, 2);
  ASSERT_EQ(r.frame.primitive[i], 0);
  EXPECT_EQ(r.allowed.components[0][i], 0.0f);
  // z_w changes by 1/64 per pixel along x and along y: 1.5·2^-8·(1/64 + 1/64) from position,
  // plus a little arithmetic (evaluation and setup: under 2%).
  EXPECT_GT(r.allowed.depth[i], 1.5 * 0x1p-8 * (1.0 / 64 + 1.0 / 64));
  EXPECT_LT(r.allowed.depth[i], 1.5 * 0x1p-8 * (1.0 / 64 + 1.0 / 64) * 1.02);
}

// The block forms (kRowBlock pixels at once, render.cpp's fragments) must give every bit the
// single-pixel forms give, for ordinary lanes and for the lanes that return early there: a
// NaN or infinite value, D = 0 at the pixel.
TEST(Allowance, BlocksGiveTheSingularFormsBits) {
  // N = 3x - 2y + 7/3, D = x - y (0 on the diagonal), a fan polygon and a guard-band triangle.
  const LinearForm n{mpq_class(3), mpq_class(-2), mpq_class(7, 3)};
  const LinearForm d{mpq_class(1), mpq_class(-1), mpq_class(0)};
  const WindowPolygon polygon = {{0.25, 0.5}, {40.5, 3.75}, {7.125, 30.5}, {1.5, 20}};
  const WindowPolygon guard = {{-100, -3}, {300, 2}, {5, 400}};
  const Anchors anchors(polygon, guard);
  for (double spread : {2.5, double(INFINITY)}) {
    const Allowance a(n, d, spread, 1e-7, anchors);
    double px[kRowBlock], py[kRowBlock], delta[kRowBlock], extra[kRowBlock], cond[kRowBlock],
        outside[kRowBlock];
    float value[kRowBlock];
    for (int j = 0; j < kRowBlock; ++j) {
      px[j] = 3 + 5 * j, py[j] = j % 3 == 0 ? px[j] : 11 - j;  // lanes 0, 3, 6: D = 0
      delta[j] = 0x1p-8 * (1 + j), extra[j] = j * 1e-6, cond[j] = 5 + 3 * j;
      value[j] = float(1.0 / (j + 1) - 0.3);
      // Lanes 2 and 5 outside the polygon, 5 where no value is determined.
      outside[j] = j == 2 ? 0.01 : j == 5 ? INFINITY : -1;
    }
    value[1] = NAN, value[4] = INFINITY, value[7] = -1e30f;
    Anchors::RowDistances blocks;
    anchors.distances(px, py, blocks);
    double out[kRowBlock];
    a.at(px, py, value, delta, extra, cond, outside, blocks, out);
    for (int j = 0; j < kRowBlock; ++j) {
      Anchors::Distances one;
      anchors.distances(int(px[j]), int(py[j]), one);
      for (size_t i = 0; i < anchors.size(); ++i) {
        EXPECT_EQ(std::bit_cast<uint64_t>(one.dx[i]), std::bit_cast<uint64_t>(blocks.dx[i][j]));
        EXPECT_EQ(std::bit_cast<uint64_t>(one.dy[i]), std::bit_cast<uint64_t>(blocks.dy[i][j]));
        EXPECT_EQ(std::bit_cast<uint64_t>(one.most[i]), std::bit_cast<uint64_t>(blocks.most[i][j]));
      }
      const double single =
          a.at(int(px[j]), int(py[j]), value[j], delta[j], extra[j], cond[j], outside[j], one);
      EXPECT_EQ(std::bit_cast<uint64_t>(single), std::bit_cast<uint64_t>(out[j])) << "lane " << j;
    }
    // What the frames store: each lane's bound rounded up to a float, bit for bit.
    float stored[kRowBlock];
    a.at_rounded_up(px, py, value, delta, extra, cond, outside, blocks, stored);
    for (int j = 0; j < kRowBlock; ++j)
      EXPECT_EQ(std::bit_cast<uint32_t>(stored[j]), std::bit_cast<uint32_t>(round_up(out[j])))
          << "lane " << j;
    EXPECT_EQ(out[0], INFINITY);  // D = 0
    EXPECT_EQ(out[1], INFINITY);  // NaN
    EXPECT_TRUE(std::isfinite(out[2]));
    // Outside the polygon: the spread no longer caps it, and the reach counts.
    EXPECT_GE(out[2], a.at(int(px[2]), int(py[2]), value[2], delta[2], extra[2], cond[2]));
    EXPECT_EQ(out[5], INFINITY);
  }
  // round_up: bounds that round up, down, exactly, negative, infinite, NaN and beyond float.
  const double bounds[kRowBlock] = {0.1, 1.0, 1e-45, -0.1, INFINITY, NAN, 1e300, 3.4028235e38};
  float block[kRowBlock];
  round_up(bounds, block);
  for (int j = 0; j < kRowBlock; ++j)
    EXPECT_EQ(std::bit_cast<uint32_t>(round_up(bounds[j])), std::bit_cast<uint32_t>(block[j]))
        << "lane " << j;
  const double ordinary[kRowBlock] = {0.1, 1.0, 1e-45, 0, 2.5e-300, 7, 1e38, 3.4028235e38};
  round_up(ordinary, block);
  for (int j = 0; j < kRowBlock; ++j) {
    EXPECT_EQ(std::bit_cast<uint32_t>(round_up(ordinary[j])), std::bit_cast<uint32_t>(block[j]));
    EXPECT_GE(double(block[j]), ordinary[j]);
  }
}

// The allowance of case c's triangle 0, one noperspective component, at 8 subpixel bits.
std::unique_ptr<TriangleAllowance> triangle_allowance(const Case& c) {
  const Model m;
  const TriangleSetup t = setup_triangle(c, m, 0);
  auto a = std::make_unique<TriangleAllowance>(c, t, 8);
  Barycentrics b;
  barycentrics(t, m, b);
  const Plane depth = depth_plane(t, b);
  a->set(c, t, component_planes(c, t, b, depth), depth, {false});
  return a;
}

// Outside the triangle (allowance.hpp, "Outside the polygon"): a centre that snapping covers
// beyond the exact edges of a sliver gets the sliver's plane extrapolated, and an
// implementation whose planes come from its unsnapped float positions (llvmpipe) moves that
// value with the positions' rounding. A sliver `apex` px high above a row of centres 0.003 px
// below its long edge (within 2^-8 snapping), in a viewport `size` wide: every corner of its
// vertices' float rounding boxes (0.99 of them, and `scale` times them) moves the value at each
// centre of that row; what the moves give, over the allowance there.
struct OutsideMoves {
  size_t centres = 0;
  size_t beyond_spread = 0;     // within the rounding, the value moved by more than the spread
  double most_used = 0;         // the largest error / allowance within the rounding
  size_t beyond_allowance = 0;  // at `scale` times the rounding, moves beyond the allowance
};
OutsideMoves outside_moves(int size, double x0, double length, double apex, double scale) {
  Case c;
  c.name = "outside";
  c.fb_width = size, c.fb_height = 64;
  c.viewport = {0, 0, size, 64};
  c.varyings = {{"n", 1, Interpolation::noperspective}};
  const double y0 = 10.503;
  const std::array<std::array<double, 2>, 3> q = {
      {{x0, y0}, {x0 + length, y0}, {x0 + length / 2, y0 + apex}}};
  const float values[3] = {0, 0, 1};
  for (size_t j = 0; j < 3; ++j)
    c.vertices.push_back(
        {{float(q[j][0] * 2 / size - 1), float(q[j][1] / 32 - 1), 0, 1}, {values[j]}});
  c.triangles = {{0, 1, 2}};
  // The window positions the float clip coordinates give (powers of two: exactly).
  std::array<std::array<double, 2>, 3> w{};
  for (size_t j = 0; j < 3; ++j)
    w[j] = {(double(c.vertices[j].clip[0]) + 1) * size / 2,
            (double(c.vertices[j].clip[1]) + 1) * 32};
  const auto allowance = triangle_allowance(c);
  const TriangleAllowance& a = *allowance;
  const double rounding = a.freedom().largest() - 0x1p-8;
  // The value of the plane through (f_j, values[j]) at (x, y).
  const auto value_at = [&](const std::array<std::array<double, 2>, 3>& f, double x, double y) {
    const auto cross = [](const std::array<double, 2>& o, const std::array<double, 2>& u,
                          const std::array<double, 2>& v) {
      return (u[0] - o[0]) * (v[1] - o[1]) - (v[0] - o[0]) * (u[1] - o[1]);
    };
    const std::array<double, 2> p{x, y};
    return (cross(f[0], f[1], p) * values[2] + cross(f[2], f[0], p) * values[1] +
            cross(f[1], f[2], p) * values[0]) /
           cross(f[0], f[1], f[2]);
  };
  OutsideMoves out;
  for (int px = int(std::ceil(w[0][0])); px + 0.5 < w[1][0]; px += kRowBlock) {
    double x[kRowBlock], y[kRowBlock];
    float exact[kRowBlock], allowed[kRowBlock];
    for (int j = 0; j < kRowBlock; ++j) {
      x[j] = std::min(px + j, int(w[1][0] - 0.5)), y[j] = 10;
      exact[j] = float(value_at(w, x[j] + 0.5, 10.5));
    }
    TriangleAllowance::Block block;
    a.prepare(x, y, block);
    a.component_at(block, 0, exact, allowed);
    for (int j = 0; j < kRowBlock && px + j + 0.5 < w[1][0]; ++j) {
      EXPECT_GE(block.outside[j], 0) << "centre " << x[j] << " lies outside the sliver";
      EXPECT_TRUE(std::isfinite(allowed[j]));
      ++out.centres;
      for (double s : {0.99, scale})
        for (int corner = 0; corner < 64; ++corner) {
          auto f = w;
          for (int k = 0; k < 6; ++k)
            f[size_t(k / 2)][size_t(k % 2)] += ((corner >> k) & 1 ? 1 : -1) * s * rounding;
          const double error = std::fabs(value_at(f, x[j] + 0.5, 10.5) - double(exact[j]));
          if (s < 1) {
            EXPECT_LE(error, double(allowed[j])) << "centre " << x[j] << " corner " << corner;
            out.most_used = std::max(out.most_used, error / double(allowed[j]));
            out.beyond_spread += error > 1;
          } else {
            out.beyond_allowance += error > double(allowed[j]);
          }
        }
    }
  }
  return out;
}

TEST(Allowance, OutsideASliverTheUnsnappedPlanesExtrapolationIsBoundedBothWays) {
  // A long sliver near the origin: the rounding moves the value beyond the spread the old
  // bound capped at (the plane setup's rounding dominates its allowance there).
  const OutsideMoves near = outside_moves(64, 4.5, 40, 2e-4, 6);
  EXPECT_EQ(near.centres, 39u);
  EXPECT_GT(near.beyond_spread, 0u);
  // A short one far from the origin, where the positions' rounding dominates: the bound is
  // not loose, and six times the rounding (a driver rounding worse than float32) is beyond it.
  const OutsideMoves far = outside_moves(4096, 3000.5, 3, 0.012, 6);
  EXPECT_EQ(far.centres, 2u);
  EXPECT_GT(far.most_used, 0.25);
  EXPECT_GT(far.beyond_allowance, 0u);
}

TEST(Allowance, InsideATriangleNoCentreIsOutside) {
  Case c;
  c.name = "inside";
  c.fb_width = c.fb_height = 64;
  c.viewport = {0, 0, 64, 64};
  c.varyings = {{"n", 1, Interpolation::noperspective}};
  c.vertices = {{{-0.9f, -0.9f, 0, 1}, {0}}, {{0.9f, -0.9f, 0, 1}, {0}}, {{0, 0.9f, 0, 1}, {1}}};
  c.triangles = {{0, 1, 2}};
  const auto allowance = triangle_allowance(c);
  const TriangleAllowance& a = *allowance;
  double x[kRowBlock], y[kRowBlock];
  for (int j = 0; j < kRowBlock; ++j)
    x[j] = 20 + j, y[j] = 20;
  TriangleAllowance::Block block;
  a.prepare(x, y, block);
  for (int j = 0; j < kRowBlock; ++j)
    EXPECT_EQ(block.outside[j], -1);
}

// Where the float rounding alone may turn the sliver over (llvmpipe's sliver from a `sizes`
// campaign, 1.8e-6 px² doubled area at x_w = 1307), its plane's value outside it is not
// determined; inside the polygon of a triangle that cannot turn, the reach is -1.
TEST(Allowance, OutsideASliverTheFloatRoundingMayTurnNoValueIsDetermined) {
  const WindowPolygon sliver = {
      {1307.49858442, 4.503437875}, {1307.4856184, 4.538928425}, {1307.503908, 4.488723575}};
  const FanTriangles fan(sliver, 0.0053, 0.0014);
  EXPECT_EQ(fan.outside_reach(1307.5, 4.5), INFINITY);
  const FanTriangles still(sliver, 0.0053, 0);  // no rounding: a finite reach of 0
  EXPECT_EQ(still.outside_reach(1307.5, 4.5), 0.0);
  const WindowPolygon quad = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const FanTriangles q(quad, 0.004, 0.001);
  EXPECT_EQ(q.outside_reach(5, 5), -1);
  EXPECT_EQ(q.outside_reach(10, 5), -1);  // on an edge
  EXPECT_GT(q.outside_reach(10.001, 5), 0.001);
  EXPECT_TRUE(q.holds_run(0.5, 9.5, 5));
  EXPECT_FALSE(q.holds_run(0.5, 10.5, 5));
  // The block form gives each lane's bits.
  double x[kRowBlock], y[kRowBlock], out[kRowBlock];
  for (int j = 0; j < kRowBlock; ++j)
    x[j] = 8.5 + 0.75 * j, y[j] = j % 2 ? 5 : -0.25;
  q.outside_reach(x, y, out);
  for (int j = 0; j < kRowBlock; ++j)
    EXPECT_EQ(std::bit_cast<uint64_t>(out[j]), std::bit_cast<uint64_t>(q.outside_reach(x[j], y[j])))
        << "lane " << j;
  EXPECT_EQ(out[1], -1);
  EXPECT_GT(out[0], 0);
}

TEST(Allowance, GrowsWithDistanceFromTheOrigin) {
  Case near = base_case(16);
  near.vertices = {
      {{-1, -1, 0, 1}, {0, 0, 0}}, {{1, -1, 0, 1}, {1, 1, 1}}, {{-1, 1, 0, 1}, {0, 0, 0}}};
  near.triangles = {{0, 1, 2}};
  Case far = near;
  far.fb_width = 4096;
  far.viewport = {4080, 0, 16, 16};
  const Expectation a = render(near, Model{}, 16), b = render(far, Model{}, 16);
  // The same triangle, 4080 pixels further: float positions and planes lose precision there.
  EXPECT_GT(b.allowed.components[0][b.frame.index(4082, 2)],
            4 * a.allowed.components[0][a.frame.index(2, 2)]);
}

TEST(SharedEdges, AQuadsDiagonalIsSharedAnOverlapIsNot) {
  Case c = base_case(16);
  c.varyings = {};
  for (auto [x, y] : {std::pair{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}})
    c.vertices.push_back({{x, y, 0, 1}, {}});
  // The third overlaps the first: a centre on the diagonal gets 2 fragments on their side, 1 on
  // the other's, so the diagonal is no shared edge; a copy of the second too makes it one again.
  c.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}};
  std::vector<TriangleSetup> setups;
  for (int p = 0; p < 3; ++p)
    setups.push_back(setup_triangle(c, Model{}, p));
  auto shared = shared_edges(setups);
  for (const auto& e : shared)
    EXPECT_EQ(e, (std::array<bool, 3>{false, false, false}));
  c.triangles.push_back({0, 2, 3});
  setups.push_back(setup_triangle(c, Model{}, 3));
  shared = shared_edges(setups);
  // Edge i is opposite the triangle's i-th vertex: the diagonal 0-2 is edge 1 of (0, 1, 2) and
  // edge 2 of (0, 2, 3).
  EXPECT_EQ(shared[0], (std::array<bool, 3>{false, true, false}));
  EXPECT_EQ(shared[1], (std::array<bool, 3>{false, false, true}));
  EXPECT_EQ(shared[2], (std::array<bool, 3>{false, true, false}));
  EXPECT_EQ(shared[3], (std::array<bool, 3>{false, false, true}));

  // Pixels along the diagonal are marked shared, not snapping; the outer edges snapping.
  c.triangles = {{0, 1, 2}, {0, 2, 3}};
  const Expectation r = render(c, Model{}, 8);
  EXPECT_EQ(r.edges[r.frame.index(7, 7)], edge::shared | edge::tie);  // centre on the diagonal
  EXPECT_EQ(r.edges[r.frame.index(8, 8)], edge::shared | edge::tie);
  EXPECT_EQ(r.edges[r.frame.index(5, 9)], 0);
  EXPECT_EQ(r.frame.fragments[r.frame.index(7, 7)], 1);
}

}  // namespace
}  // namespace glrc::ref
