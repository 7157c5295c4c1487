// Depth offset (glPolygonOffset, OpenGL 4.6 section 14.6.5): every fragment of a filled polygon
// has o = m·factor + r·units added to its z_w (min(o, clamp) for clamp > 0, max(o, clamp) for
// clamp < 0: glPolygonOffsetClamp), then the sum is clamped to [0, 1] (core/case.hpp
// fragment_depth).
//
// The freedom GL leaves, and how it is bounded here (docs/allowance.md, "Polygon offset"):
//   m   the polygon's largest depth slope, sqrt((∂z_w/∂x_w)² + (∂z_w/∂y_w)²) (equation 14.11),
//       or as approximated by max(|∂z_w/∂x_w|, |∂z_w/∂y_w|) (14.12): anything between the two.
//       z_w is linear in window coordinates over the whole triangle, so every piece of its
//       clipped polygon has the same exact slopes; an implementation computes them from its own
//       rounded positions and depths, each within its freedom (PolygonVertex::delta and the
//       float rounding of z_w), which bounds its slopes by first principles (no first-order
//       step): for a piece of doubled area 2A and slope numerators N, |N'| <= |N| + e_N and
//       |2A'| >= |2A| - e_A, with e_N, e_A the products' worst moves. A piece whose rounding may
//       take its area to 0 bounds nothing: m is unbounded there.
//   r   the minimum resolvable difference. This harness's depth buffer is 32F: r = 2^(e − 23),
//       e the exponent of the largest |z_w| over the primitive, which an implementation that
//       offsets each piece of a clipped polygon takes over the piece: from the least a piece of
//       any triangulation may have (the three vertices of least |z_w|) to the polygon's
//       largest, each z_w within its rounding. Below 2^-100 an implementation may take r as 0
//       (Mesa's exponent arithmetic flushes it).
//   o   computed in float: each product and the sum within a few ulps, and the sum z_w + o
//       rounded once more.
// The reference adds one value of that set, exactly: m the midpoint of (14.12) and (14.11)
// (the latter rounded to a double), r from the exact vertices' largest |z_w| (the clipped
// polygon's, in double, for a clipped triangle). The freedom is how far the set reaches from it.
#pragma once

#include "core/case.hpp"
#include "ref/exact.hpp"
#include "ref/freedom.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

// The float depth buffer's mantissa bits (GL_DEPTH_COMPONENT32F): n in r = 2^(e − n).
inline constexpr int kDepthMantissaBits = 23;

struct DepthOffset {
  mpq_class value;  // the o the reference adds to triangle t's z_w (z_w units), exact
  // The m and r it is made of (the clamp aside), in double: each within the freedom's bounds.
  double m = 0, r = 0;
};

// The reference's offset for triangle t of c (0 without a polygon offset, or for a triangle
// of zero area, whose slope is not defined: its m is taken as 0).
DepthOffset depth_offset(const Case& c, const TriangleSetup& t);

// How far the offset of a conforming implementation may be from `reference` (z_w units): the
// freedom of m and r above over the pieces of the triangle's clipped polygon (`freedom`'s
// vertices), and the float rounding of o and of z_w + o; infinite where m is unbounded and factor
// is not 0. 0 without a polygon offset.
double depth_offset_freedom(const Case& c, const PositionFreedom& freedom,
                            const DepthOffset& reference);

// The interval of |∂z/∂x| and |∂z/∂y| (in that order, each {lo, hi}) over every triangle whose
// window vertices lie within delta[i] of p[i] in x and in y and whose depths lie within
// depth[i] of z[i]; hi infinite where the area may reach 0. Exposed for tests.
std::array<std::array<double, 2>, 2> slope_bounds(const std::array<std::array<double, 2>, 3>& p,
                                                  const std::array<double, 3>& z,
                                                  const std::array<double, 3>& delta,
                                                  const std::array<double, 3>& depth);

}  // namespace glrc::ref
