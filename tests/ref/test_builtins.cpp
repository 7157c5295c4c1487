// The built-ins a case writes out (core/case.hpp, ref/interpolation.hpp): gl_FragCoord's x and
// y exactly the pixel's centre under each layout, z the depth's bits and allowance, w the float
// nearest 1/w_c; gl_FrontFacing the triangle's facing, free only where the triangle may turn
// over (docs/allowance.md, "Built-ins").
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ref/deferred.hpp"
#include "ref/depth.hpp"
#include "ref/freedom.hpp"
#include "ref/interpolation.hpp"
#include "ref/reference.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {
namespace {

// A perspective triangle (w 1, 2, 4) over a 37x29 framebuffer, with gl_FragCoord and
// gl_FrontFacing after a smooth varying.
Case perspective(const FragCoordLayout& layout = {}) {
  Case c;
  c.name = "builtins";
  c.fb_width = 37, c.fb_height = 29;
  c.viewport = {0, 0, 37, 29};
  c.varyings = {{"c", 1, Interpolation::smooth},
                builtin_varying(Builtin::frag_coord, layout),
                builtin_varying(Builtin::front_facing)};
  c.vertices = {{{-0.9f, -0.8f, -0.5f, 1}, {0, 0, 0, 0, 0, 0}},
                {{1.6f, -1.2f, 0.25f, 2}, {1, 0, 0, 0, 0, 0}},
                {{-0.5f, 3.0f, 1.5f, 4}, {2, 0, 0, 0, 0, 0}}};
  c.triangles = {{0, 1, 2}};
  return c;
}

// f(px, py, i) at every pixel e's frame covers (i its index); how many there are.
template <class F>
size_t for_each_covered(const Case& c, const Expectation& e, F f) {
  size_t covered = 0;
  for (int py = 0; py < c.fb_height; ++py)
    for (int px = 0; px < c.fb_width; ++px)
      if (const size_t i = e.frame.index(px, py); e.frame.primitive[i] >= 0) {
        ++covered;
        f(px, py, i);
      }
  return covered;
}

TEST(Builtins, FragCoordXYAreThePixelCentresUnderEachLayout) {
  for (bool upper : {false, true})
    for (bool integer : {false, true}) {
      const Case c = perspective({upper, integer});
      const Expectation e = render(c, Model{}, 8);
      const double half = integer ? 0 : 0.5;
      const size_t covered = for_each_covered(c, e, [&](int px, int py, size_t i) {
        const double y = upper ? c.fb_height - py - (1 - half) : py + half;
        ASSERT_EQ(e.frame.components[1][i], float(px + half));
        ASSERT_EQ(e.frame.components[2][i], float(y));
        ASSERT_EQ(e.allowed.components[1][i], 0.0f);
        ASSERT_EQ(e.allowed.components[2][i], 0.0f);
      });
      EXPECT_GT(covered, 200u);
    }
}

TEST(Builtins, FragCoordZIsTheDepthAndWOneOverW) {
  const Case c = perspective();
  const Expectation e = render(c, Model{}, 8);
  // Window positions and 1/w_c of the vertices, in double: 1/w_c is Σ λ_i/w_i with λ the
  // window-space barycentrics of the pixel's centre.
  double x[3], y[3], inverse[3];
  for (int i = 0; i < 3; ++i) {
    const auto& p = c.vertices[size_t(i)].clip;
    x[i] = (p[0] / p[3] + 1) * c.fb_width / 2, y[i] = (p[1] / p[3] + 1) * c.fb_height / 2;
    inverse[i] = 1 / double(p[3]);
  }
  const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  const size_t covered = for_each_covered(c, e, [&](int px, int py, size_t i) {
    ASSERT_EQ(e.frame.components[3][i], e.frame.depth[i]);
    ASSERT_EQ(e.allowed.components[3][i], e.allowed.depth[i]);
    const double qx = px + 0.5, qy = py + 0.5;
    double w = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      w += ((x[a] - qx) * (y[b] - qy) - (x[b] - qx) * (y[a] - qy)) / area * inverse[k];
    }
    ASSERT_NEAR(e.frame.components[4][i], w, 1e-6 * w);
    ASSERT_GT(e.allowed.components[4][i], 0.0f);
    ASSERT_LT(e.allowed.components[4][i], 1e-3 * w);
    ASSERT_EQ(e.frame.components[5][i], 1.0f);  // counter-clockwise, GL_CCW
    ASSERT_EQ(e.allowed.components[5][i], 0.0f);
  });
  EXPECT_GT(covered, 200u);
  Case cw = c;
  cw.front_face = FrontFace::cw;
  const Expectation back = render(cw, Model{}, 8);
  for (size_t i = 0; i < back.frame.pixel_count(); ++i)
    if (back.frame.primitive[i] >= 0) {
      ASSERT_EQ(back.frame.components[5][i], 0.0f);
    }
}

// gl_FrontFacing's allowance: 1 (either value) on a sliver the freedom may turn over, 0 on a
// triangle it may not.
TEST(Builtins, FrontFacingIsFreeOnlyWhereTheTriangleMayTurnOver) {
  Case c;
  c.name = "sliver";
  c.fb_width = c.fb_height = 256;
  c.viewport = {0, 0, 256, 256};
  c.varyings = {builtin_varying(Builtin::front_facing)};
  // test_freedom's sliver, 0.0014 pixels wide and 100 long, and a wide one.
  c.vertices = {{{0.9045995473861694f, 0.8882501125335693f, 0, 1}, {0}},
                {{0.21741044521331787f, -0.7137936353683472f, 0, 1}, {0}},
                {{0.21742117404937744f, -0.7137902975082397f, 0, 1}, {0}},
                {{0.3f, -0.7f, 0, 1}, {0}}};
  c.triangles = {{0, 1, 2}, {0, 1, 3}};
  const Model m;
  for (int p : {0, 1}) {
    const TriangleSetup t = setup_triangle(c, m, p);
    TriangleAllowance a(c, t, 8);
    Barycentrics b;
    barycentrics(t, m, b);
    const Plane depth = depth_plane(t, b);
    a.set(c, t, component_planes(c, t, b, depth), depth, {false});
    EXPECT_EQ(a.freedom().may_turn_over(), p == 0);
    TriangleAllowance::Block block;
    double px[kRowBlock], py[kRowBlock];
    float value[kRowBlock], out[kRowBlock];
    for (int j = 0; j < kRowBlock; ++j)
      px[j] = 100 + j, py[j] = 20, value[j] = t.front_facing ? 1.0f : 0.0f;
    a.prepare(px, py, block);
    a.component_at(block, 0, value, out);
    EXPECT_EQ(out[0], p == 0 ? 1.0f : 0.0f) << "triangle " << p;
  }
}

}  // namespace
}  // namespace glrc::ref
