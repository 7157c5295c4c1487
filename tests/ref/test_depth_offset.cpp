// The polygon offset's freedom (ref/depth_offset.hpp), from both sides: every slope of a
// triangle whose vertices move within their freedom lies within slope_bounds, and the offset of
// an implementation that uses either of GL's slopes (14.11 or 14.12) lies within
// depth_offset_freedom of the reference's, while the faults a driver has had (units ignored or
// doubled, the slope along x alone) lie beyond it.
#include <gtest/gtest.h>

#include <cmath>

#include "ref/depth_offset.hpp"
#include "ref/freedom.hpp"
#include "ref/reference.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {
namespace {

// ∂z/∂x and ∂z/∂y of the triangle (p[i], z[i]), in double.
std::array<double, 2> slopes(const std::array<std::array<double, 2>, 3>& p,
                             const std::array<double, 3>& z) {
  const double dx1 = p[1][0] - p[0][0], dy1 = p[1][1] - p[0][1], dz1 = z[1] - z[0];
  const double dx2 = p[2][0] - p[0][0], dy2 = p[2][1] - p[0][1], dz2 = z[2] - z[0];
  const double area = dx1 * dy2 - dx2 * dy1;
  return {(dz1 * dy2 - dz2 * dy1) / area, (dx1 * dz2 - dx2 * dz1) / area};
}

TEST(DepthOffset, SlopeBoundsHoldAtEveryCornerOfTheFreedom) {
  const std::array<std::array<double, 2>, 3> p{{{3.25, 2.5}, {40.75, 9.125}, {12.5, 33.0}}};
  const std::array<double, 3> z{0.125, 0.8, 0.45};
  const std::array<double, 3> delta{1.0 / 16, 1.0 / 16, 1.0 / 16}, depth{1e-6, 1e-6, 1e-6};
  const auto b = slope_bounds(p, z, delta, depth);
  const auto exact = slopes(p, z);
  EXPECT_LT(b[0][0], std::fabs(exact[0]));
  EXPECT_GT(b[0][1], std::fabs(exact[0]));
  // Every corner: each vertex's x, y and z at either end of its freedom (2^9 triangles).
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {0, 0};
  for (int corner = 0; corner < 512; ++corner) {
    auto q = p;
    auto w = z;
    for (size_t i = 0; i < 3; ++i) {
      const int bits = corner >> (3 * i);
      q[i][0] += bits & 1 ? delta[i] : -delta[i];
      q[i][1] += bits & 2 ? delta[i] : -delta[i];
      w[i] += bits & 4 ? depth[i] : -depth[i];
    }
    const auto s = slopes(q, w);
    for (int k = 0; k < 2; ++k) {
      EXPECT_GE(std::fabs(s[size_t(k)]), b[size_t(k)][0]) << corner;
      EXPECT_LE(std::fabs(s[size_t(k)]), b[size_t(k)][1]) << corner;
      lo[k] = std::min(lo[k], std::fabs(s[size_t(k)]));
      hi[k] = std::max(hi[k], std::fabs(s[size_t(k)]));
    }
  }
  // Not vacuous: the bounds are within a few times the corners' own spread of them.
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(hi[k] - lo[k], b[size_t(k)][1] - b[size_t(k)][0]);
    EXPECT_LT(b[size_t(k)][1] - b[size_t(k)][0], 4 * (hi[k] - lo[k]));
  }
}

TEST(DepthOffset, ATriangleThatMayTurnOverBoundsNoSlope) {
  // Half a pixel high, its vertices free by a pixel: its area may reach 0.
  const std::array<std::array<double, 2>, 3> p{{{0, 0}, {30, 0.25}, {60, 0.5}}};
  const auto b = slope_bounds(p, {0.1, 0.5, 0.9}, {1, 1, 1}, {0, 0, 0});
  EXPECT_EQ(b[0][1], INFINITY);
  EXPECT_EQ(b[1][1], INFINITY);
}

// A 64x64 case of one triangle, polygon offset (factor, units), with the triangle's window
// positions and depths (vertices' clip w 1: z_w = (z_c + 1)/2).
struct OffsetCase {
  Case c;
  std::array<std::array<double, 2>, 3> window{};
  std::array<double, 3> z{};
};
OffsetCase offset_case(float factor, float units) {
  OffsetCase o;
  o.c.name = "offset";
  o.c.fb_width = o.c.fb_height = 64;
  o.c.viewport = {0, 0, 64, 64};
  o.c.polygon_offset = PolygonOffset{factor, units, std::nullopt};
  // Depth changes 8 times faster along y than along x.
  const std::array<std::array<float, 4>, 3> clip{
      {{-0.75f, -0.75f, -0.5f, 1.0f}, {0.75f, -0.75f, -0.375f, 1.0f}, {-0.75f, 0.75f, 0.5f, 1.0f}}};
  for (size_t i = 0; i < 3; ++i) {
    Vertex v;
    v.clip = clip[i];
    o.c.vertices.push_back(v);
    o.window[i] = {(clip[i][0] + 1) * 32.0, (clip[i][1] + 1) * 32.0};
    o.z[i] = (clip[i][2] + 1) / 2.0;
  }
  o.c.triangles = {{0, 1, 2}};
  return o;
}

TEST(DepthOffset, EitherSlopeOfGLPassesAndDriversFaultsDoNot) {
  for (const int bits : {4, 8}) {
    const OffsetCase o = offset_case(3.0f, 50000.0f);
    const TriangleSetup t = setup_triangle(o.c, Model{}, 0);
    const PositionFreedom freedom(o.c, t, bits);
    const DepthOffset reference = depth_offset(o.c, t);
    const double allowed = depth_offset_freedom(o.c, freedom, reference);
    ASSERT_TRUE(std::isfinite(allowed));
    const auto g = slopes(o.window, o.z);
    const double gx = std::fabs(g[0]), gy = std::fabs(g[1]);
    ASSERT_GT(gy, 4 * gx);
    const double r = std::ldexp(1.0, -1 - 23);  // the largest z_w is 0.75: e = -1
    const double o_ref = reference.value.get_d();
    auto error = [&](double m, double units_scale) {
      return std::fabs(3.0 * m + 50000.0 * units_scale * r - o_ref);
    };
    EXPECT_LE(error(std::max(gx, gy), 1), allowed) << bits;    // (14.12): llvmpipe's
    EXPECT_LE(error(std::hypot(gx, gy), 1), allowed) << bits;  // (14.11)
    EXPECT_GT(error(gx, 1), allowed) << bits;                  // the slope along x alone
    EXPECT_GT(error(std::max(gx, gy), 0), allowed) << bits;    // units ignored
    EXPECT_GT(error(std::max(gx, gy), 2), allowed) << bits;    // units doubled (zink's)
  }
}

TEST(DepthOffset, TheReferencesOffsetIsExactAndClamped) {
  OffsetCase o = offset_case(0.0f, 1000.0f);
  const TriangleSetup t = setup_triangle(o.c, Model{}, 0);
  // Units alone: o = 1000·2^-24 exactly.
  EXPECT_EQ(depth_offset(o.c, t).value, mpq_class(1000) / mpq_class(1 << 24));
  o.c.polygon_offset->clamp = 1e-5f;
  EXPECT_EQ(depth_offset(o.c, t).value, mpq_class(double(1e-5f)));
  o.c.polygon_offset->clamp = -1e-5f;  // clamps from below: a positive offset stays
  EXPECT_EQ(depth_offset(o.c, t).value, mpq_class(1000) / mpq_class(1 << 24));
  o.c.polygon_offset.reset();
  EXPECT_EQ(depth_offset(o.c, t).value, 0);
}

// gl_FragCoord.z under a polygon offset may be z_w + o before or after the clamp to [0, 1]: its
// allowance reaches the clamped value where z_w + o leaves [0, 1], and only there.
TEST(DepthOffset, FragCoordZMayBeClampedOnlyBeyondTheUnitRange) {
  OffsetCase o = offset_case(0.0f, 8e6f);  // o = 8e6·2^-24 = 0.477: z_w + o passes 1 at the top
  o.c.varyings = {builtin_varying(Builtin::frag_coord)};
  for (Vertex& v : o.c.vertices)
    v.values.assign(4, 0.0f);
  const Expectation r = render(o.c, Model{}, 8);
  size_t beyond = 0, inside = 0;
  for (size_t i = 0; i < r.frame.pixel_count(); ++i) {
    if (r.frame.primitive[i] < 0) continue;
    const double z = r.frame.components[2][i], allowed = r.allowed.components[2][i];
    EXPECT_LE(r.frame.depth[i], 1.0f);  // the depth itself is clamped
    if (z > 1) {
      ++beyond;
      EXPECT_GE(allowed, z - 1) << i;                  // the clamped value passes
      EXPECT_LT(allowed, 1.01 * (z - 1) + 1e-4) << i;  // not much more
    } else {
      ++inside;
      EXPECT_LT(allowed, 1e-4) << i;  // no excuse inside [0, 1]
    }
  }
  EXPECT_GT(beyond, 10u);
  EXPECT_GT(inside, 10u);
}

}  // namespace
}  // namespace glrc::ref
