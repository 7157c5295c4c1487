// The reference renderer against values computed by hand and by an independent solver.
#include <gtest/gtest.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "ref/coverage.hpp"
#include "ref/reference.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {
namespace {

Vertex vtx(float x, float y, float z, float w, std::vector<float> values) {
  return {{x, y, z, w}, std::move(values)};
}

Case base_case(int w, int h) {
  Case c;
  c.name = "test";
  c.fb_width = w, c.fb_height = h;
  c.viewport = {0, 0, w, h};
  return c;
}

// An 8x8 viewport, window positions A(0,0) w=1, B(8,0) w=2, C(0,8) w=4; v = (0, 8, 0) and
// z_n = (0, 0.5, -0.25). At the centre (1.5, 1.5) the screen barycentrics are
// lambda = (10/16, 3/16, 3/16), so by hand:
//   smooth        (3/16·8/2) / (10/16 + 3/32 + 3/64) = (3/4) / (49/64) = 48/49
//   noperspective 3/16·8 = 3/2
//   depth         10/16·1/2 + 3/16·3/4 + 3/16·3/8 = 67/128
TEST(Expectation, PerspectiveTriangleByHand) {
  Case c = base_case(8, 8);
  c.varyings = {{"s", 1, Interpolation::smooth}, {"n", 1, Interpolation::noperspective}};
  c.vertices = {vtx(-1, -1, 0, 1, {0, 0}), vtx(2, -2, 1, 2, {8, 8}), vtx(-4, 4, -1, 4, {0, 0})};
  c.triangles = {{0, 1, 2}};
  for (int bits : {0, 8}) {
    Model m;
    m.subpixel_bits = bits;  // all positions are on the grid: snapping changes nothing
    for (Planes planes : {Planes::unsnapped, Planes::snapped}) {
      m.planes = planes;
      const Expectation r = render(c, m);
      const size_t i = r.frame.index(1, 1);
      EXPECT_EQ(r.frame.primitive[i], 0);
      EXPECT_EQ(r.frame.components[0][i], 48.0f / 49.0f) << m.describe();
      EXPECT_EQ(r.frame.components[1][i], 1.5f) << m.describe();
      EXPECT_EQ(r.frame.depth[i], 67.0f / 128.0f) << m.describe();
      // Outside the hypotenuse x + y = 8: pixel (4,4) has centre sum 9.
      EXPECT_EQ(r.frame.primitive[r.frame.index(4, 4)], Frame::kNoPrimitive);
    }
  }
}

// The quad tilted away from the eye, as two triangles: along their shared diagonal both must
// give the same perspective-correct value (the seam a screen-linear interpolation would show).
TEST(Expectation, TiltedQuadHasNoSeam) {
  Case c = base_case(32, 32);
  c.varyings = {{"uv", 2, Interpolation::smooth}};
  // Bottom edge near (w=1), top edge far (w=3): x_c, y_c scaled by w keep a trapezoid on screen.
  c.vertices = {vtx(-0.9f, -0.9f, 0, 1, {0, 0}), vtx(0.9f, -0.9f, 0, 1, {1, 0}),
                vtx(1.2f, 2.4f, 0, 3, {1, 1}), vtx(-1.2f, 2.4f, 0, 3, {0, 1})};
  c.triangles = {{0, 1, 2}, {0, 2, 3}};
  const Expectation r = render(c, Model{});
  // The exact interpolant u is the same rational function over the whole quad; check that u
  // is monotone along each row across the seam (a screen-linear split would kink).
  int rows_checked = 0;
  for (int y = 4; y < 28; ++y) {
    std::vector<float> u;
    std::set<int> prims;
    for (int x = 0; x < 32; ++x) {
      const size_t i = r.frame.index(x, y);
      if (r.frame.primitive[i] < 0) continue;
      u.push_back(r.frame.components[0][i]);
      prims.insert(r.frame.primitive[i]);
    }
    if (prims.size() < 2) continue;
    ++rows_checked;
    for (size_t k = 1; k < u.size(); ++k)
      EXPECT_GT(u[k], u[k - 1]) << "row " << y;
  }
  EXPECT_GT(rows_checked, 10);
}

// Counts, per pixel, how many triangles cover it, straight from CoverageTest.
std::vector<int> coverage_counts(const Case& c, const Model& m) {
  std::vector<int> count(size_t(c.fb_width) * c.fb_height, 0);
  for (int p = 0; p < int(c.triangles.size()); ++p) {
    const TriangleSetup t = setup_triangle(c, m, p);
    if (!t.drawn) continue;
    const CoverageTest cov(t, m);
    for (int y = 0; y < c.fb_height; ++y)
      for (int x = 0; x < c.fb_width; ++x)
        count[size_t(y) * c.fb_width + x] += cov.covers(x, y);
  }
  return count;
}

// A fan around a pixel centre with spokes through pixel centres, horizontal, vertical and
// diagonal (the tie cases): every pixel inside is covered exactly once, for every model.
TEST(Expectation, FanCoversEachPixelOnce) {
  Case c = base_case(32, 32);
  // Window position p -> clip (p/16 - 1) with w = 1 on a 32x32 viewport.
  auto at = [](float x_w, float y_w) { return vtx(x_w / 16 - 1, y_w / 16 - 1, 0, 1, {}); };
  c.vertices.push_back(at(16.5f, 16.5f));
  const float ring[][2] = {{28.5f, 16.5f}, {28.5f, 28.5f}, {16.5f, 28.5f}, {4.5f, 28.5f},
                           {4.5f, 16.5f},  {4.5f, 4.5f},   {16.5f, 4.5f},  {28.5f, 4.5f}};
  for (auto& p : ring)
    c.vertices.push_back(at(p[0], p[1]));
  for (uint32_t k = 0; k < 8; ++k)
    c.triangles.push_back({0, 1 + k, 1 + (k + 1) % 8});
  for (int bits : {0, 4, 8}) {
    for (TieBreak tie : {TieBreak::bottom_left, TieBreak::top_left}) {
      Model m;
      m.subpixel_bits = bits, m.tie_break = tie;
      const auto count = coverage_counts(c, m);
      int inside = 0;
      for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
          const int n = count[size_t(y) * 32 + x];
          EXPECT_LE(n, 1) << x << "," << y << " " << m.describe();
          // Strictly inside the outer square [4.5, 28.5]^2: covered exactly once.
          if (x >= 5 && x <= 27 && y >= 5 && y <= 27) {
            EXPECT_EQ(n, 1) << x << "," << y << " " << m.describe();
            ++inside;
          }
        }
      EXPECT_EQ(inside, 23 * 23);
      // The outer square's edges are on pixel centres: bottom_left takes its left and bottom
      // edges, top_left its left and top edges; the right edge never.
      EXPECT_EQ(count[4 * 32 + 10], tie == TieBreak::bottom_left ? 1 : 0) << m.describe();
      EXPECT_EQ(count[28 * 32 + 10], tie == TieBreak::top_left ? 1 : 0) << m.describe();
      EXPECT_EQ(count[10 * 32 + 4], 1) << m.describe();
      EXPECT_EQ(count[10 * 32 + 28], 0) << m.describe();
    }
  }
}

// A perspective grid mesh with irregular vertices: no pixel twice, no gap inside.
TEST(Expectation, PerspectiveGridIsWatertight) {
  Case c = base_case(64, 64);
  const int n = 6;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float w = 1.0f + 0.37f * j;  // receding rows
      const float x = (-0.95f + 1.9f * i / n + 0.013f * ((i * 7 + j * 3) % 5)) * w;
      const float y = (-0.95f + 1.9f * j / n + 0.011f * ((i * 5 + j) % 3)) * w;
      c.vertices.push_back(vtx(x, y, 0.1f * w, w, {}));
    }
  auto id = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      c.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      c.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  for (int bits : {0, 8}) {
    Model m;
    m.subpixel_bits = bits;
    const auto count = coverage_counts(c, m);
    // The mesh's outline is inside x, y in [2, 61]: the centre region must be covered once.
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        EXPECT_LE(count[size_t(y) * 64 + x], 1) << x << "," << y;
        if (x >= 6 && x < 58 && y >= 6 && y < 58) {
          EXPECT_EQ(count[size_t(y) * 64 + x], 1) << x << "," << y;
        }
      }
  }
}

// An independent solver: the clip-space barycentrics b of the point under a pixel centre,
// from M b = w·(x_n, y_n, 1) by Cramer's rule, with sum b = 1. Returns false if the point is
// not on the visible (w > 0) part.
bool solve_barycentrics(const Case& c, const std::array<uint32_t, 3>& tri, int px, int py,
                        std::array<mpq_class, 3>& b) {
  const mpq_class x_n = mpq_class(2 * px + 1 - 2 * c.viewport.x, c.viewport.width) - 1;
  const mpq_class y_n = mpq_class(2 * py + 1 - 2 * c.viewport.y, c.viewport.height) - 1;
  mpq_class m[3][3];
  for (int i = 0; i < 3; ++i) {
    const auto& v = c.vertices[tri[i]].clip;
    m[0][i] = double(v[0]), m[1][i] = double(v[1]), m[2][i] = double(v[3]);
  }
  auto det3 = [](mpq_class a[3][3]) -> mpq_class {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const mpq_class d = det3(m);
  const mpq_class rhs[3] = {x_n, y_n, 1};
  mpq_class e[3], sum = 0;
  for (int i = 0; i < 3; ++i) {
    mpq_class mi[3][3];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k)
        mi[r][k] = k == i ? rhs[r] : m[r][k];
    e[i] = det3(mi) / d;
    sum += e[i];
  }
  for (int i = 0; i < 3; ++i) {
    b[i] = e[i] / sum;
    if (sgn(e[i]) * sgn(sum) < 0) return false;
  }
  return sum > 0;  // w at the point is 1/sum
}

float nearest_float(const mpq_class& q) {
  mpfr_t r;
  mpfr_init2(r, 24);
  mpfr_set_q(r, q.get_mpq_t(), MPFR_RNDN);
  const float f = mpfr_get_flt(r, MPFR_RNDN);
  mpfr_clear(r);
  return f;
}

// A triangle with a vertex behind the eye (w_c < 0) and one beyond the far plane: coverage and
// values of every pixel against the independent solver (unsnapped, so no ties with the model).
TEST(Expectation, BehindTheEyeAndFarPlaneAgainstSolver) {
  Case c = base_case(48, 40);
  c.varyings = {{"a", 2, Interpolation::smooth}, {"f", 1, Interpolation::flat}};
  c.vertices = {vtx(-0.7f, -0.6f, 0.2f, 1.0f, {3.0f, -1.0f, 7}),
                vtx(0.9f, -0.3f, 2.6f, 2.0f, {-5.0f, 2.5f, 8}),
                vtx(0.2f, 0.8f, -1.6f, -1.5f, {10.0f, 0.125f, 9})};
  c.triangles = {{0, 1, 2}};
  Model m;
  m.subpixel_bits = 0;
  const Expectation r = render(c, m);
  int covered = 0;
  for (int py = 0; py < 40; ++py)
    for (int px = 0; px < 48; ++px) {
      std::array<mpq_class, 3> b;
      bool inside = solve_barycentrics(c, c.triangles[0], px, py, b);
      mpq_class z = 0, w = 0;
      for (int i = 0; i < 3; ++i) {
        z += b[i] * double(c.vertices[i].clip[2]);
        w += b[i] * double(c.vertices[i].clip[3]);
      }
      inside = inside && z >= -w && z <= w;
      const size_t i = r.frame.index(px, py);
      ASSERT_EQ(r.frame.primitive[i] == 0, inside) << px << "," << py;
      if (!inside) continue;
      ++covered;
      for (int k = 0; k < 2; ++k) {
        mpq_class v = 0;
        for (int j = 0; j < 3; ++j)
          v += b[j] * double(c.vertices[j].values[k]);
        EXPECT_EQ(r.frame.components[k][i], nearest_float(v)) << px << "," << py;
      }
      EXPECT_EQ(r.frame.components[2][i], 9.0f);  // flat: last vertex
      EXPECT_EQ(r.frame.depth[i], nearest_float(mpq_class(z / w + 1) / 2)) << px << "," << py;
    }
  EXPECT_GT(covered, 50);
  EXPECT_LT(covered, 48 * 40);
}

TEST(Expectation, ProvokingVertexCullingAndDepthRange) {
  Case c = base_case(16, 16);
  c.varyings = {{"f", 1, Interpolation::flat}};
  c.vertices = {vtx(-1, -1, 0.5f, 1, {1}), vtx(1, -1, 0.5f, 1, {2}), vtx(-1, 1, 0.5f, 1, {3})};
  c.triangles = {{0, 1, 2}};
  const size_t i = 2 * 16 + 2;
  EXPECT_EQ(render(c, Model{}).frame.components[0][i], 3.0f);
  c.provoking = ProvokingVertex::first;
  EXPECT_EQ(render(c, Model{}).frame.components[0][i], 1.0f);
  // z_n = 0.5: depth 0.75 with (0, 1), 0.25 reversed, 0.625 on (0.5, 0.75).
  EXPECT_EQ(render(c, Model{}).frame.depth[i], 0.75f);
  c.depth_near = 1, c.depth_far = 0;
  EXPECT_EQ(render(c, Model{}).frame.depth[i], 0.25f);
  c.depth_near = 0.5f, c.depth_far = 0.75f;
  EXPECT_EQ(render(c, Model{}).frame.depth[i], 0.6875f);
  // The triangle is counter-clockwise: culled as a back face only with front_face cw.
  c.cull = CullFace::back;
  EXPECT_EQ(render(c, Model{}).frame.primitive[i], 0);
  c.front_face = FrontFace::cw;
  EXPECT_EQ(render(c, Model{}).frame.primitive[i], Frame::kNoPrimitive);
}

TEST(Expectation, ViewportOffsetAndEdgeBand) {
  Case c = base_case(40, 30);
  c.viewport = {10, 5, 20, 20};
  c.varyings = {};
  c.vertices = {vtx(-3, -3, 0, 1, {}), vtx(6, -3, 0, 1, {}), vtx(-3, 6, 0, 1, {})};
  c.triangles = {{0, 1, 2}};
  const Expectation r = render(c, Model{});
  // The triangle covers the whole viewport, nothing outside it.
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      const bool in_viewport = x >= 10 && x < 30 && y >= 5 && y < 25;
      EXPECT_EQ(r.frame.primitive[r.frame.index(x, y)] == 0, in_viewport) << x << "," << y;
    }
  // A vertical edge exactly through centres x = 15.5 is in the band; 2 pixels off is not.
  Case e = base_case(32, 32);
  e.vertices = {vtx(-1.0f / 32, -0.5f, 0, 1, {}), vtx(0.5f, -0.5f, 0, 1, {}),
                vtx(-1.0f / 32, 0.5f, 0, 1, {})};
  e.triangles = {{0, 1, 2}};
  const Expectation re = render(e, Model{});
  EXPECT_EQ(re.edges[re.frame.index(15, 16)], edge::snapping | edge::tie);
  EXPECT_EQ(re.edges[re.frame.index(17, 16)], 0);
  EXPECT_EQ(re.edges[re.frame.index(13, 16)], 0);
}

// A triangle of zero area covers no centre exactly, but an implementation's rounded vertices may
// make a sliver of it (llvmpipe does, in a campaign): the centres within the position freedom of
// its segment are unstable, no others; one through the eye has a vertex of undefined position,
// and every centre of the viewport is; culling both faces draws neither.
TEST(Expectation, AZeroAreaTriangleLeavesOnlyItsSliverUndecided) {
  auto unstable = [](const Expectation& r, int x, int y) {
    return (r.edges[r.frame.index(x, y)] & edge::unstable) != 0;
  };
  // Collinear along the row of centres y_w = 10.5 of a 64x48 viewport, from x_w = 8.5 to 40.5,
  // the middle vertex divided by w_c = 3.
  Case c = base_case(64, 48);
  const float y_n = 10.5f / 24 - 1;
  c.vertices = {vtx(8.5f / 32 - 1, y_n, 0, 1, {}), vtx(3 * (20.5f / 32 - 1), 3 * y_n, 0, 3, {}),
                vtx(40.5f / 32 - 1, y_n, 0, 1, {})};
  c.triangles = {{0, 1, 2}};
  ASSERT_FALSE(setup_triangle(c, Model{}, 0).has_edges);
  const Expectation r = render(c, Model{}, 8);
  for (int x = 8; x <= 40; ++x)
    EXPECT_TRUE(unstable(r, x, 10)) << x;
  for (int x : {6, 7, 41, 42})
    EXPECT_FALSE(unstable(r, x, 10)) << x;
  for (int x = 0; x < 64; ++x)
    EXPECT_FALSE(unstable(r, x, 9) || unstable(r, x, 11)) << x;
  for (size_t i = 0; i < r.frame.pixel_count(); ++i)
    EXPECT_EQ(r.frame.primitive[i], Frame::kNoPrimitive);
  // Without an allowance (a driver model), nothing is undecided.
  const Expectation model = render(c, Model{});
  EXPECT_TRUE(
      std::all_of(model.edges.begin(), model.edges.end(), [](uint8_t e) { return e == 0; }));

  // Vertex 0 is -2 times vertex 1: the triangle holds the eye (the point between them at
  // w_c = 0). llvmpipe's clipper makes a vertex there of rounding noise and fills 1,005 pixels.
  Case eye = base_case(64, 48);
  eye.vertices = {vtx(-2 * 0.25f, -2 * -0.5625f, -2 * 0.125f, -2, {}),
                  vtx(0.25f, -0.5625f, 0.125f, 1, {}), vtx(-0.75f, -0.5625f, 0, 1, {})};
  eye.triangles = {{0, 1, 2}};
  const Expectation re = render(eye, Model{}, 8);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      ASSERT_TRUE(unstable(re, x, y)) << x << "," << y;
  eye.cull = CullFace::front_and_back;
  const Expectation culled = render(eye, Model{}, 8);
  EXPECT_TRUE(
      std::all_of(culled.edges.begin(), culled.edges.end(), [](uint8_t e) { return e == 0; }));
  eye.cull = CullFace::back;  // its facing is either
  EXPECT_TRUE(unstable(render(eye, Model{}, 8), 0, 0));
}

}  // namespace
}  // namespace glrc::ref
