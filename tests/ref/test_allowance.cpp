// The specification-derived allowance, checked the way its derivation says it holds: render the
// same triangles with every vertex moved to the extremes of the position freedom, exactly, and
// every value that moves must stay within the allowance of the unmoved reference.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

#include "ref/allowance.hpp"
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
    double px[kRowBlock], py[kRowBlock], delta[kRowBlock], extra[kRowBlock], cond[kRowBlock];
    float value[kRowBlock];
    for (int j = 0; j < kRowBlock; ++j) {
      px[j] = 3 + 5 * j, py[j] = j % 3 == 0 ? px[j] : 11 - j;  // lanes 0, 3, 6: D = 0
      delta[j] = 0x1p-8 * (1 + j), extra[j] = j * 1e-6, cond[j] = 5 + 3 * j;
      value[j] = float(1.0 / (j + 1) - 0.3);
    }
    value[1] = NAN, value[4] = INFINITY, value[7] = -1e30f;
    Anchors::RowDistances blocks;
    anchors.distances(px, py, blocks);
    double out[kRowBlock];
    a.at(px, py, value, delta, extra, cond, blocks, out);
    for (int j = 0; j < kRowBlock; ++j) {
      Anchors::Distances one;
      anchors.distances(int(px[j]), int(py[j]), one);
      for (size_t i = 0; i < anchors.size(); ++i) {
        EXPECT_EQ(std::bit_cast<uint64_t>(one.dx[i]), std::bit_cast<uint64_t>(blocks.dx[i][j]));
        EXPECT_EQ(std::bit_cast<uint64_t>(one.dy[i]), std::bit_cast<uint64_t>(blocks.dy[i][j]));
        EXPECT_EQ(std::bit_cast<uint64_t>(one.most[i]), std::bit_cast<uint64_t>(blocks.most[i][j]));
      }
      const double single =
          a.at(int(px[j]), int(py[j]), value[j], delta[j], extra[j], cond[j], one);
      EXPECT_EQ(std::bit_cast<uint64_t>(single), std::bit_cast<uint64_t>(out[j])) << "lane " << j;
    }
    // What the frames store: each lane's bound rounded up to a float, bit for bit.
    float stored[kRowBlock];
    a.at_rounded_up(px, py, value, delta, extra, cond, blocks, stored);
    for (int j = 0; j < kRowBlock; ++j)
      EXPECT_EQ(std::bit_cast<uint32_t>(stored[j]), std::bit_cast<uint32_t>(round_up(out[j])))
          << "lane " << j;
    EXPECT_EQ(out[0], INFINITY);  // D = 0
    EXPECT_EQ(out[1], INFINITY);  // NaN
    EXPECT_TRUE(std::isfinite(out[2]));
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
